#include "continue/sticking.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit::cli {
namespace {

/// The largest section multiplier's modulus (0 where the section has none: N = 1).
double LeadingModulus(const PeriodicOrbit& orbit) {
  return orbit.multipliers.size() ? std::abs(orbit.multipliers(0)) : 0.0;
}

std::vector<std::string> Columns(const std::string& parameter) {
  return {parameter,        "stick_phase",    "release_phase",
          "stuck_duration", "contact_margin", "max_modulus",
          "stable",         "impacts",        "v1"};
}

/// One row; `impacts` and `v1` (the first, fastest impact after the
/// release) of the first sticking phase.
std::vector<double> Row(const StickingBranchPoint& p) {
  const PeriodicOrbit& o = p.orbit;
  const StuckPhase& stuck = o.stuck.front();
  return {p.parameter,
          stuck.stick_phase,
          stuck.release_phase,
          stuck.Duration(),
          o.contacts.contact_margin,
          LeadingModulus(o),
          o.stable ? 1.0 : 0.0,
          static_cast<double>(stuck.impacts),
          o.impacts.front().velocity};
}

nlohmann::json PointJson(const StickingBranchPoint& p) {
  const PeriodicOrbit& o = p.orbit;
  nlohmann::json multipliers = nlohmann::json::array();
  for (const std::complex<double>& m : o.multipliers) multipliers.push_back({m.real(), m.imag()});
  std::vector<double> stick_phases, release_phases, stuck_durations;
  for (const StuckPhase& stuck : o.stuck) {
    stick_phases.push_back(stuck.stick_phase);
    release_phases.push_back(stuck.release_phase);
    stuck_durations.push_back(stuck.Duration());
  }
  return {{"param", p.parameter},
          {"stick_phases", stick_phases},
          {"release_phases", release_phases},
          {"stuck_durations", stuck_durations},
          {"contact_margin", o.contacts.contact_margin},
          // null where no free flight has an interior maximum of x_c
          {"clearance",
           o.contacts.clearance ? nlohmann::json(*o.contacts.clearance) : nlohmann::json()},
          {"multipliers", multipliers},
          {"stable", o.stable},
          {"state", std::vector<double>(o.eta.data(), o.eta.data() + o.eta.size())}};
}

}  // namespace

void RunStickingContinue(const System& system, const PeriodicOrbit& start,
                         const StickingBranchOptions& options, OutputSet& outputs,
                         AtomicOutputFile* out, AtomicOutputFile* json,
                         const Provenance& provenance) {
  fmt::print("start:      sticking P(inf,{}) at {} = {}, {}\n", start.q, options.parameter,
             GetParameter(system, options.parameter), start.stable ? "stable" : "unstable");
  const StickingBranch branch = ContinueStickingBranch(system, start, options);
  fmt::print("branch:     sticking P(inf,{}), {} points from {} = {} to {}, {:.3g} s\n", branch.q,
             branch.points.size(), options.parameter, branch.points.front().parameter,
             branch.points.back().parameter, branch.seconds);
  for (const StickingSpecialPoint& s : branch.special_points) {
    fmt::print("special:    {}\n", s.Describe(options.parameter));
  }
  fmt::print("end:        {} ({})\n", ToString(branch.end), branch.end_message);
  if (branch.points.size() < 2) {
    throw std::runtime_error(
        fmt::format("the sticking branch could not be continued beyond its start: {} ({})",
                    ToString(branch.end), branch.end_message));
  }
  if (out) {
    CsvWriter& csv = outputs.AddCsv(*out, provenance.Text(), Columns(options.parameter));
    for (const StickingBranchPoint& p : branch.points) csv.WriteRow(Row(p));
  }
  if (json) {
    nlohmann::json j = {{"provenance", provenance.Json()}};
    j["kind"] = "sticking";
    j["parameter"] = options.parameter;
    j["releases"] = branch.releases;
    j["q"] = branch.q;
    j["end_reason"] = ToString(branch.end);
    j["end_message"] = branch.end_message;
    j["param_range"] = {branch.points.front().parameter, branch.points.back().parameter};
    j["special_points"] = nlohmann::json::array();
    for (const StickingSpecialPoint& s : branch.special_points) {
      nlohmann::json point = PointJson(s.point);
      point["type"] = ToString(s.type);
      point["parameter"] = options.parameter;
      point["description"] = s.Describe(options.parameter);
      j["special_points"].push_back(point);
    }
    j["points"] = nlohmann::json::array();
    for (const StickingBranchPoint& p : branch.points) j["points"].push_back(PointJson(p));
    j["system"] = nlohmann::json::parse(SystemToJson(system));
    json->Write(j.dump(2) + "\n");
  }
}

}  // namespace impactkit::cli
