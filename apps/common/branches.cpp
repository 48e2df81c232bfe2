#include "common/branches.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "impactkit/io/csv.hpp"

namespace impactkit::cli {
namespace {}  // namespace

nlohmann::json BranchJson(const TracedBranch& traced) {
  return nlohmann::json::parse(impactkit::BranchJson(traced.branch, traced.label, traced.origin));
}

std::vector<TracedBranch> LabelBranches(const Diagram& diagram) {
  std::vector<TracedBranch> labelled;
  for (std::size_t k = 0; k < diagram.branches.size(); ++k) {
    const DiagramBranch& b = diagram.branches[k];
    labelled.push_back({BranchLabel(diagram, k), b.origin, b.branch});
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

/// FILE.csv for the main branch, FILE.<label>.csv for the others.
std::string BranchPath(const std::string& path, const std::string& label) {
  if (label == "main") return path;
  const std::size_t dot = path.rfind('.');
  const bool has_extension = dot != std::string::npos && path.find('/', dot) == std::string::npos;
  return has_extension ? path.substr(0, dot) + "." + label + path.substr(dot) : path + "." + label;
}

namespace {

/// The title and gnuplot pointtype of a special point type's marks: 4
/// square, 6 circle, 8 triangle, 10 down triangle, 12 diamond, 3 star, 14
/// pentagon, 2 cross, 1 plus, 13 filled diamond. A switch with no default, so that a type
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
    case SpecialPointType::kUserTest:
      return {"user test", 13};
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
  for (const SpecialPoint& s : b.special_points) {
    fmt::print("  {}\n", s.Describe(b.parameter));
    if (s.normal_form) fmt::print("    {}\n", s.normal_form->Describe());
    if (s.normal_form && s.normal_form->prediction) {
      fmt::print("    {}\n", s.normal_form->prediction->Describe());
    }
    if (!s.normal_form_note.empty()) fmt::print("    no normal form: {}\n", s.normal_form_note);
  }
  for (const UnlocatedZero& u : b.unlocated) fmt::print("  {}\n", u.Describe(b.parameter));
  fmt::print("  ends:   {} ({})\n", ToString(b.end), b.end_message);
}

}  // namespace impactkit::cli
