#include "impactkit/io/branch_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/normal_form_json.hpp"

namespace impactkit {
namespace {

/// The CSV's `special` column: the special point's type by name, empty for
/// an ordinary point.
std::string SpecialName(const Branch& branch, const BranchPoint& point) {
  for (const SpecialPoint& s : branch.special_points) {
    if (s.point.arclength == point.arclength) return ToString(s.type);
  }
  return "";
}

/// A sticking orbit's stuck phases: stick_phases, release_phases (t mod
/// T), stuck_durations, contact_margin (the least Fs(t*)).
nlohmann::json StuckJson(const PeriodicOrbit& orbit) {
  std::vector<double> stick, release, duration;
  for (const StuckPhase& stuck : orbit.stuck) {
    stick.push_back(stuck.stick_phase);
    release.push_back(stuck.release_phase);
    duration.push_back(stuck.Duration());
  }
  return {{"stick_phases", stick},
          {"release_phases", release},
          {"stuck_durations", duration},
          {"contact_margin", orbit.contacts.contact_margin}};
}

nlohmann::json SpecialJson(const SpecialPoint& s, const std::string& parameter) {
  nlohmann::json j = {
      {"type", ToString(s.type)},
      {"param", s.parameter},
      {"parameter", parameter},
      {"description", s.Describe(parameter)},
      {"monitor", s.monitor},
      {"stop", s.point.orbit.stop + 1},
      {"eta", std::vector<double>(s.point.orbit.eta.data(),
                                  s.point.orbit.eta.data() + s.point.orbit.eta.size())}};
  if (s.type == SpecialPointType::kGrazing || s.type == SpecialPointType::kSticking) {
    j["vanishing_impact"] =
        s.vanishing_impact < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.vanishing_impact + 1);
    if (s.type == SpecialPointType::kGrazing) AddNormalForm(s.normal_form, s.normal_form_note, &j);
  } else if (s.type == SpecialPointType::kUserTest) {
    j["user_test"] = s.user_test;
  } else if (s.type != SpecialPointType::kNoSticking && s.type != SpecialPointType::kEarlyRelease) {
    j["multiplier"] = {s.multiplier.real(), s.multiplier.imag()};
  }
  j["impacts"] = nlohmann::json::array();
  for (const OrbitImpact& i : LeadingImpacts(s.point.orbit)) {
    j["impacts"].push_back({{"phase", i.phase}, {"velocity", i.velocity}});
  }
  if (s.point.orbit.Sticks()) j.update(StuckJson(s.point.orbit));
  return j;
}

}  // namespace

std::vector<std::string> BranchColumns(const Branch& branch) {
  std::vector<std::string> columns = {branch.parameter, "arclength"};
  if (branch.section == OrbitSection::kRelease) {
    for (const char* name : {"stick_phase", "release_phase", "stuck"}) {
      for (int i = 1; i <= branch.releases; ++i) columns.push_back(fmt::format("{}{}", name, i));
    }
  }
  // A sticking orbit's first impact after each release.
  const int impacts = branch.section == OrbitSection::kRelease ? branch.releases : branch.p;
  // Prefixed: v1..vN name the masses' velocities in every other table.
  for (int i = 1; i <= impacts; ++i) columns.push_back(fmt::format("impact_phase{}", i));
  for (int i = 1; i <= impacts; ++i) columns.push_back(fmt::format("impact_velocity{}", i));
  columns.push_back("range_xN");
  const Eigen::Index multipliers = branch.points.front().orbit.multipliers.size();
  for (Eigen::Index i = 1; i <= multipliers; ++i) columns.push_back(fmt::format("mod{}", i));
  const bool sticks = branch.section == OrbitSection::kRelease;
  for (const char* name : {"stable", "clearance", sticks ? "contact_margin" : "depth", "special"}) {
    columns.push_back(name);
  }
  return columns;
}

void WriteBranchRows(CsvWriter& csv, const Branch& branch) {
  for (const BranchPoint& point : branch.points) {
    const PeriodicOrbit& orbit = point.orbit;
    std::vector<double> row = {point.parameter, point.arclength};
    for (const StuckPhase& stuck : orbit.stuck) row.push_back(stuck.stick_phase);
    for (const StuckPhase& stuck : orbit.stuck) row.push_back(stuck.release_phase);
    for (const StuckPhase& stuck : orbit.stuck) row.push_back(stuck.Duration());
    const std::vector<OrbitImpact> impacts = LeadingImpacts(orbit);
    for (const OrbitImpact& i : impacts) row.push_back(i.phase);
    for (const OrbitImpact& i : impacts) row.push_back(i.velocity);
    row.push_back(orbit.contacts.Range());
    for (const std::complex<double>& m : orbit.multipliers) row.push_back(std::abs(m));
    row.push_back(orbit.stable ? 1.0 : 0.0);
    // No interior maximum: the clearance is the whole way down to the
    // lowest point, reported as the range (never NaN in a table).
    row.push_back(orbit.contacts.clearance.value_or(orbit.contacts.Range()));
    row.push_back(orbit.Sticks() ? orbit.contacts.contact_margin
                                 : std::min(orbit.contacts.slowest_depth, 1e300));
    csv.WriteRow(row, std::vector<std::string>{SpecialName(branch, point)});
  }
}

std::string BranchJson(const Branch& b, std::string_view label, std::string_view origin) {
  nlohmann::json j = {{"label", label},
                      {"origin", origin},
                      {"section", ToString(b.section)},
                      {"p", b.p},
                      {"q", b.q},
                      {"releases", b.releases},
                      {"stop", b.stop + 1},
                      {"points", b.points.size()},
                      {"end_reason", ToString(b.end)},
                      {"end_message", b.end_message},
                      {"seconds", b.seconds}};
  if (b.begin) {
    j["begin_reason"] = ToString(*b.begin);
    j["begin_message"] = b.begin_message;
  }
  j["param_range"] = {b.points.front().parameter, b.points.back().parameter};
  j["special_points"] = nlohmann::json::array();
  for (const SpecialPoint& s : b.special_points)
    j["special_points"].push_back(SpecialJson(s, b.parameter));
  j["unlocated"] = nlohmann::json::array();
  for (const UnlocatedZero& u : b.unlocated) {
    j["unlocated"].push_back({{"type", ToString(u.type)},
                              {"from", u.from},
                              {"to", u.to},
                              {"description", u.Describe(b.parameter)}});
  }
  return j.dump();
}

}  // namespace impactkit
