#include "impactkit/io/grazing_output.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "io/normal_form_json.hpp"

namespace impactkit {

std::string GrazingChecksJson(const std::vector<GrazingCheck>& checks,
                              const std::string& parameter) {
  nlohmann::json grazings = nlohmann::json::array();
  for (const GrazingCheck& c : checks) {
    const GrazingSweeps& s = c.sweeps;
    grazings.push_back({{"param", c.parameter},
                        {"grazing_orbit", c.grazing_orbit},
                        {"contact", c.new_contact ? "new" : "vanishing"},
                        {"prediction", PredictionJson(c.prediction)},
                        {"sweeps",
                         {{"values", s.values},
                          {"toward", s.toward},
                          {"back", s.back},
                          {"past_distance", s.past_distance},
                          {"past", s.past},
                          {"expected", s.expected},
                          {"follows", s.follows},
                          {"agrees", s.agrees},
                          {"hysteresis", s.hysteresis}}}});
  }
  return nlohmann::json{{"parameter", parameter}, {"grazings", grazings}}.dump(2);
}

std::string DescribeGrazingCheck(const GrazingCheck& check, const std::string& parameter) {
  const GrazingSweeps& s = check.sweeps;
  const std::string verdict = !s.follows ? "the sweep does not follow the grazing orbit"
                              : s.agrees ? "agrees"
                                         : "DISAGREES";
  return fmt::format(
      "{} = {:.10g}, {} ({}): predicted {} ({}), swept {}: {}{}", parameter, check.parameter,
      check.grazing_orbit, check.new_contact ? "new contact" : "vanishing impact", s.expected,
      check.prediction.scenario, s.past, verdict, s.hysteresis ? "; hysteresis" : "");
}

}  // namespace impactkit
