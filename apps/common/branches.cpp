#include "common/branches.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "impactkit/io/csv.hpp"

namespace impactkit::cli {
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
  } else if (s.type != SpecialPointType::kNoSticking && s.type != SpecialPointType::kEarlyRelease) {
    j["multiplier"] = {s.multiplier.real(), s.multiplier.imag()};
  }
  j["impacts"] = nlohmann::json::array();
  for (const OrbitImpact& i : LeadingImpacts(s.point.orbit)) {
    j["impacts"].push_back({{"phase", i.phase}, {"v", i.velocity}});
  }
  if (s.point.orbit.Sticks()) j.update(StuckJson(s.point.orbit));
  return j;
}

}  // namespace

BranchProgress::BranchProgress(std::string parameter)
    : enabled_(::isatty(STDERR_FILENO) == 1), parameter_(std::move(parameter)) {}

BranchProgress::~BranchProgress() {
  if (drawn_) fmt::print(stderr, "\r\033[K");
}

void BranchProgress::operator()(int branches, const BranchPoint& point) {
  ++points_;
  const auto now = std::chrono::steady_clock::now();
  if (!enabled_ || now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  fmt::print(stderr, "\r\033[Kcontinue: {} branches done, {} points, {} = {:.8g}", branches,
             points_, parameter_, point.parameter);
}

std::vector<TracedBranch> LabelBranches(const Diagram& diagram) {
  std::vector<TracedBranch> labelled;
  for (std::size_t k = 0; k < diagram.branches.size(); ++k) {
    const DiagramBranch& b = diagram.branches[k];
    std::string label = k == 0 ? "main" : fmt::format("seed{}", k + 1);
    if (b.parent >= 0) {
      const SpecialPointType at = diagram.nodes[b.parent].special;
      const char* kind = at == SpecialPointType::kPeriodDoubling ? "pd"
                         : at == SpecialPointType::kBranchPoint  ? "bp"
                         : at == SpecialPointType::kPitchfork    ? "pf"
                                                                 : "graze";
      label = fmt::format("{}{}", kind, k);
    }
    labelled.push_back({label, b.origin, b.branch});
  }
  return labelled;
}

namespace {

/// "a to b", or "a to c to b" through each value c where the parameter
/// turns back between points first and last (a branch that goes out and
/// returns would otherwise read "from a to a").
std::string ParameterPath(const Branch& branch, std::size_t first, std::size_t last) {
  std::vector<std::string> values = {fmt::format("{:.6g}", branch.points[first].parameter)};
  for (std::size_t k = first + 1; k < last; ++k) {
    const double before = branch.points[k].parameter - branch.points[k - 1].parameter;
    const double after = branch.points[k + 1].parameter - branch.points[k].parameter;
    if (before * after < 0) values.push_back(fmt::format("{:.6g}", branch.points[k].parameter));
  }
  values.push_back(fmt::format("{:.6g}", branch.points[last].parameter));
  return fmt::format("{}", fmt::join(values, " to "));
}

}  // namespace

std::string DescribeStability(const Branch& branch) {
  std::vector<std::string> stretches;
  std::size_t from = 0;
  for (std::size_t i = 1; i <= branch.points.size(); ++i) {
    if (i < branch.points.size() &&
        branch.points[i].orbit.stable == branch.points[from].orbit.stable) {
      continue;
    }
    stretches.push_back(fmt::format("{} {}",
                                    branch.points[from].orbit.stable ? "stable" : "unstable",
                                    ParameterPath(branch, from, i - 1)));
    from = i;
  }
  return fmt::format("{} {}", FamilyName(branch), fmt::join(stretches, ", "));
}

std::vector<std::string> BranchColumns(const Branch& branch) {
  std::vector<std::string> columns = {branch.parameter, "arclength"};
  if (branch.section == OrbitSection::kRelease) {
    for (const char* name : {"stick_phase", "release_phase", "stuck"}) {
      for (int i = 1; i <= branch.releases; ++i) columns.push_back(fmt::format("{}{}", name, i));
    }
  }
  // A sticking orbit's first impact after each release.
  const int impacts = branch.section == OrbitSection::kRelease ? branch.releases : branch.p;
  for (int i = 1; i <= impacts; ++i) columns.push_back(fmt::format("phase{}", i));
  for (int i = 1; i <= impacts; ++i) columns.push_back(fmt::format("v{}", i));
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

/// FILE.csv for the main branch, FILE.<label>.csv for the others.
std::string BranchPath(const std::string& path, const std::string& label) {
  if (label == "main") return path;
  const std::size_t dot = path.rfind('.');
  const bool has_extension = dot != std::string::npos && path.find('/', dot) == std::string::npos;
  return has_extension ? path.substr(0, dot) + "." + label + path.substr(dot) : path + "." + label;
}

nlohmann::json BranchJson(const TracedBranch& traced) {
  const Branch& b = traced.branch;
  nlohmann::json j = {{"label", traced.label},
                      {"origin", traced.origin},
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
  return j;
}

namespace {

/// The title and gnuplot pointtype of a special point type's marks: 4
/// square, 6 circle, 8 triangle, 10 down triangle, 12 diamond, 3 star, 14
/// pentagon, 2 cross, 1 plus. A switch with no default, so that a type
/// added to the library without a mark here is a compiler warning (-Wswitch).
std::pair<const char*, int> MarkStyle(SpecialPointType type) {
  switch (type) {
    case SpecialPointType::kFold:
      return {"fold", 4};
    case SpecialPointType::kPeriodDoubling:
      return {"period doubling", 6};
    case SpecialPointType::kNeimarkSacker:
      return {"Neimark-Sacker", 12};
    case SpecialPointType::kGrazing:
      return {"grazing", 8};
    case SpecialPointType::kSticking:
      return {"sticking onset", 10};
    case SpecialPointType::kBranchPoint:
      return {"branch point", 3};
    case SpecialPointType::kPitchfork:
      return {"pitchfork", 14};
    case SpecialPointType::kNoSticking:
      return {"no sticking", 2};
    case SpecialPointType::kEarlyRelease:
      return {"early release", 1};
  }
  return {"special point", 7};  // not reached: every type has its case
}

}  // namespace

Curve SpecialPointMarks(SpecialPointType type) {
  // Black, so that no branch colour hides them; open, so that they hide no
  // branch through them; the shape tells the type.
  const auto [title, point_type] = MarkStyle(type);
  Curve marks;
  marks.title = title;
  marks.color = "#000000";
  marks.points = true;
  marks.point_type = point_type;
  marks.point_size = 1.4;
  return marks;
}

std::vector<Curve> StabilityKey(const std::string& color) {
  Curve stable, unstable;
  stable.title = "stable";
  unstable.title = "unstable";
  stable.color = unstable.color = color;
  unstable.dashed = true;
  return {stable, unstable};
}

namespace {

/// The curves of one branch in `color`, without titles: one per impact
/// and stretch of equal stability, so that the pieces join.
void AddBranchLines(const Branch& b, const std::string& color, LineChart& chart) {
  const int impacts = b.section == OrbitSection::kRelease ? b.releases : b.p;
  for (int i = 0; i < impacts; ++i) {
    std::size_t from = 0;
    while (from + 1 < b.points.size()) {
      std::size_t to = from + 1;
      while (to + 1 < b.points.size() && b.points[to].orbit.stable == b.points[from].orbit.stable)
        ++to;
      Curve curve;
      curve.color = color;
      curve.dashed = !b.points[from].orbit.stable;
      for (std::size_t n = from; n <= to; ++n) {
        curve.x.push_back(b.points[n].parameter);
        curve.y.push_back(LeadingImpacts(b.points[n].orbit)[i].velocity);
      }
      chart.curves.push_back(std::move(curve));
      from = to;
    }
  }
}

}  // namespace

LineChart BranchChart(const std::vector<TracedBranch>& branches) {
  LineChart chart;
  chart.title = "Continued branches: impact velocities";
  chart.x_label = ParameterLabel(branches.front().branch.parameter);
  chart.y_label = "impact velocity";
  chart.curves = StabilityKey();
  // Key entries first, in branch order: the key lists the branches whatever
  // the order of the lines drawn after them.
  std::vector<std::size_t> entry_of(branches.size());  // a branch's key entry in chart.curves
  std::vector<std::size_t> drawn;                      // the branches drawn, by index
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const Branch& b = branches[k].branch;
    const auto covering = std::find_if(drawn.begin(), drawn.end(), [&](std::size_t j) {
      return CoveredBy(b, branches[j].branch);
    });
    if (covering != drawn.end()) {
      chart.curves[entry_of[*covering]].title += " = " + branches[k].label;
      continue;
    }
    Curve entry;
    entry.title = fmt::format("{} {}", FamilyName(b), branches[k].label);
    entry.color = DistinctColor(drawn.size());
    entry_of[k] = chart.curves.size();
    chart.curves.push_back(std::move(entry));
    drawn.push_back(k);
  }
  for (std::size_t k : drawn) {
    // A copy: AddBranchLines appends to chart.curves, which may reallocate.
    const std::string color = chart.curves[entry_of[k]].color;
    AddBranchLines(branches[k].branch, color, chart);
  }
  std::map<SpecialPointType, Curve> marks;
  for (const TracedBranch& traced : branches) {
    for (const SpecialPoint& s : traced.branch.special_points) {
      auto [it, added] = marks.try_emplace(s.type, SpecialPointMarks(s.type));
      for (const OrbitImpact& i : LeadingImpacts(s.point.orbit)) {
        it->second.x.push_back(s.parameter);
        it->second.y.push_back(i.velocity);
      }
    }
  }
  for (auto& [type, mark] : marks) chart.curves.push_back(std::move(mark));
  return chart;
}

void PrintBranch(const TracedBranch& traced) {
  const Branch& b = traced.branch;
  fmt::print("branch {}:  {} {}, {} points, {} from {:.10g} to {:.10g} ({:.3g} s)\n", traced.label,
             FamilyName(b), traced.origin, b.points.size(), b.parameter, b.points.front().parameter,
             b.points.back().parameter, b.seconds);
  if (b.begin) fmt::print("  begins: {} ({})\n", ToString(*b.begin), b.begin_message);
  for (const SpecialPoint& s : b.special_points) fmt::print("  {}\n", s.Describe(b.parameter));
  fmt::print("  ends:   {} ({})\n", ToString(b.end), b.end_message);
}

}  // namespace impactkit::cli
