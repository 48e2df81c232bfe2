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
    auto optional = [](const std::optional<double>& x) {
      return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
    };
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
                          {"expected_within_reach", s.expected_within_reach},
                          {"family_speed_gap", optional(s.family_speed_gap)},
                          {"family_speed_step", optional(s.family_speed_step)},
                          {"follows", s.follows},
                          {"agrees", s.agrees},
                          {"hysteresis", s.hysteresis}}}});
  }
  return nlohmann::json{{"parameter", parameter}, {"grazings", grazings}}.dump(2);
}

std::string DescribeGrazingCheck(const GrazingCheck& check, const std::string& parameter) {
  const GrazingSweeps& s = check.sweeps;
  std::string verdict = s.agrees                  ? "agrees"
                        : s.expected_within_reach ? "DISAGREES"
                                                  : "DISAGREES beyond the normal form's reach";
  if (!s.follows) verdict = "the sweep does not follow the grazing orbit";
  if (!s.follows && s.family_speed_gap) {
    verdict = fmt::format(
        "the sweep holds another {} (impact speeds {:.2g} from the grazing orbit's, changing "
        "{:.2g} over the step before)",
        check.grazing_orbit, *s.family_speed_gap, *s.family_speed_step);
  }
  return fmt::format(
      "{} = {:.10g}, {} ({}): predicted {} ({}), swept {}: {}{}", parameter, check.parameter,
      check.grazing_orbit, check.new_contact ? "new contact" : "vanishing impact", s.expected,
      check.prediction.scenario, s.past, verdict, s.hysteresis ? "; hysteresis" : "");
}

}  // namespace impactkit
