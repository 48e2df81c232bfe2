#include "diagram/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>

#include "common/branches.hpp"
#include "impactkit/io/class_colors.hpp"

namespace impactkit::cli {
namespace {

/// The indices of `items` sorted by `parameter(item)`.
template <class T, class F>
std::vector<std::size_t> ByParameter(const std::vector<T>& items, F parameter) {
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return parameter(items[a]) < parameter(items[b]);
  });
  return order;
}

/// The chart's y values of one orbit.
std::vector<double> AxisValues(const PeriodicOrbit& orbit, DiagramAxis axis) {
  if (axis == DiagramAxis::kRange) return {orbit.contacts.Range()};
  std::vector<double> v;
  for (const OrbitImpact& impact : LeadingImpacts(orbit)) v.push_back(impact.velocity);
  return v;
}

/// The sweep's points in the chart's axis, pale and small: underneath the
/// branches, which they must not hide.
Curve BruteForcePoints(const SweptDiagram& swept, DiagramAxis axis) {
  Curve brute;
  brute.points = true;
  brute.color = "#c8c8c8";
  brute.point_size = 0.15;
  brute.title = "brute force";
  for (const SweepPoint& p : swept.sweep.points) {
    if (axis == DiagramAxis::kRange) {
      for (double r : p.range_contact) {
        brute.x.push_back(p.value);
        brute.y.push_back(r);
      }
    } else {
      for (const SweepImpact& i : p.impacts) {
        brute.x.push_back(p.value);
        brute.y.push_back(i.velocity);
      }
    }
  }
  return brute;
}

/// Families with a colour and a key entry of their own; the others share
/// one grey entry, so that the key stays one column beside the plot.
constexpr std::size_t kKeyFamilies = 24;

/// The colour of each family, the branches of one period P(p,q), by (q, p)
/// (p = 0: the sticking P(inf,q), a sticking branch's p):
/// the colour of that class in every figure (ClassColor: a P(2,1) branch is
/// the colour of the P(2,1) cells of a map) for the kKeyFamilies shortest
/// periods, the ones a reader follows; the maps' "other periods" grey for
/// the long ones at the ends of period-doubling cascades.
std::map<std::pair<int, int>, std::string> FamilyColors(const Diagram& diagram) {
  std::map<std::pair<int, int>, std::string> colors;
  for (const DiagramBranch& b : diagram.branches) colors[{b.branch.q, b.branch.p}];
  std::size_t k = 0;
  for (auto& [family, color] : colors) {
    const MotionKind kind = family.second == 0 ? MotionKind::kSticking : MotionKind::kPeriodic;
    color = k++ < kKeyFamilies ? ClassColor(kind, family.second, family.first) : kOtherClassesColor;
  }
  return colors;
}

/// The key entries of the families, in order of q, then p, then one for
/// the families drawn grey.
std::vector<Curve> FamilyKeys(const std::map<std::pair<int, int>, std::string>& colors) {
  std::vector<Curve> keys;
  int others = 0;
  for (const auto& [family, color] : colors) {
    if (color == kOtherClassesColor) {
      ++others;
      continue;
    }
    Curve key;
    key.title = family.second == 0 ? fmt::format("P(inf,{})", family.first)
                                   : fmt::format("P({},{})", family.second, family.first);
    key.color = color;
    keys.push_back(std::move(key));
  }
  if (others > 0) {
    Curve key;
    key.title = fmt::format("{} other periods", others);
    key.color = kOtherClassesColor;
    keys.push_back(std::move(key));
  }
  return keys;
}

/// The lines of one edge in `color`: one curve per impact and stretch of
/// one stability, so that the pieces join.
void AddEdgeLines(const Diagram& diagram, const DiagramEdge& edge, DiagramAxis axis,
                  const std::string& color, LineChart& chart) {
  const Branch& b = diagram.branches[edge.branch].branch;
  const std::size_t lines = AxisValues(b.points[edge.first].orbit, axis).size();
  for (std::size_t line = 0; line < lines; ++line) {
    std::size_t from = edge.first;
    while (from < edge.last) {
      std::size_t to = from + 1;
      while (to < edge.last && b.points[to].orbit.stable == b.points[from].orbit.stable) ++to;
      Curve curve;
      curve.color = color;
      curve.dashed = !b.points[from].orbit.stable;
      for (std::size_t n = from; n <= to; ++n) {
        curve.x.push_back(b.points[n].parameter);
        curve.y.push_back(AxisValues(b.points[n].orbit, axis)[line]);
      }
      chart.curves.push_back(std::move(curve));
      from = to;
    }
  }
}

/// "76 branches from 40 seeds", and why the network was cut short if it
/// was: two diagrams of one range say which is which.
std::string DiagramTitle(const SweptDiagram& swept) {
  const Diagram& diagram = swept.diagram;
  return fmt::format("Connected bifurcation diagram: {} branches from {} seeds{}",
                     diagram.branches.size(), swept.seeds.size(),
                     diagram.termination == Termination::kCompleted
                         ? ""
                         : " (incomplete: " + diagram.message + ")");
}

/// The whole range: the sweep's points underneath, the branches coloured by
/// family (stable solid, unstable dashed), special points as open markers
/// that leave the branches through them visible.
LineChart WholeDiagram(const SweptDiagram& swept, DiagramAxis axis) {
  const Diagram& diagram = swept.diagram;
  LineChart chart;
  chart.title = DiagramTitle(swept);
  chart.x_label = ParameterLabel(diagram.parameter);
  chart.y_label = axis == DiagramAxis::kRange ? "max - min of x_N" : "impact velocity";
  chart.key_outside = true;
  Curve brute = BruteForcePoints(swept, axis);
  if (!brute.x.empty()) chart.curves.push_back(std::move(brute));
  for (Curve& key : StabilityKey()) chart.curves.push_back(std::move(key));
  const std::map<std::pair<int, int>, std::string> colors = FamilyColors(diagram);
  for (Curve& key : FamilyKeys(colors)) chart.curves.push_back(std::move(key));
  for (const DiagramEdge& edge : diagram.edges) {
    const Branch& b = diagram.branches[edge.branch].branch;
    AddEdgeLines(diagram, edge, axis, colors.at({b.q, b.p}), chart);
  }
  std::map<SpecialPointType, Curve> marks;
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind != DiagramNodeKind::kSpecialPoint) continue;
    Curve& mark = marks.try_emplace(node.special, SpecialPointMarks(node.special)).first->second;
    for (double y : AxisValues(node.point.orbit, axis)) {
      mark.x.push_back(node.parameter);
      mark.y.push_back(y);
    }
  }
  for (auto& [type, mark] : marks) {
    mark.point_size = 0.6;  // many, close together: small open shapes
    chart.curves.push_back(std::move(mark));
  }
  return chart;
}

/// A diagram with more branches than this gets a second panel.
constexpr std::size_t kDenseBranches = 12;

/// Of a dense diagram, the window an eighth of its range wide that holds
/// the most special points (where the markers and branches pile up);
/// nothing when the diagram is sparse enough to read whole.
std::optional<std::array<double, 2>> DensestWindow(const Diagram& diagram) {
  std::vector<double> at;
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind == DiagramNodeKind::kSpecialPoint) at.push_back(node.parameter);
  }
  if (diagram.branches.size() <= kDenseBranches || at.size() < 2) return std::nullopt;
  std::sort(at.begin(), at.end());
  const double width = (at.back() - at.front()) / 8;
  if (!(width > 0)) return std::nullopt;
  std::size_t best = 0, most = 0;
  for (std::size_t i = 0, j = 0; i < at.size(); ++i) {
    while (j < at.size() && at[j] <= at[i] + width) ++j;
    if (j - i > most) std::tie(best, most) = std::pair{i, j - i};
  }
  const double margin = 0.05 * width;
  return std::array{at[best] - margin, at[best] + width + margin};
}

/// The steps where a branch's fold or period-doubling test changed sign
/// unaccounted for (Branch::unlocated), if any branch has one.
void PrintUnlocated(const std::vector<TracedBranch>& labelled) {
  bool any = false;
  for (const TracedBranch& traced : labelled) {
    for (const UnlocatedZero& u : traced.branch.unlocated) {
      if (!any) {
        fmt::print(
            "not located (a fold or period doubling may lie in these steps, missing above; "
            "docs/continuation.md, Known limits):\n");
      }
      any = true;
      fmt::print("  {:<8} {}: {}\n", traced.label, FamilyName(traced.branch),
                 u.Describe(traced.branch.parameter));
    }
  }
}

}  // namespace

void PrintDiagram(const Diagram& diagram) {
  const std::vector<TracedBranch> labelled = LabelBranches(diagram);
  fmt::print("diagram:    {}\n", diagram.BriefReport());
  if (diagram.failed_starts > 0) {
    // The library's count, read for the user: what a seed is here, and that
    // most of them failing is expected.
    fmt::print(
        "            ({} seeds not converged: starts tried at special points that found no "
        "orbit; both sides of every grazing are tried and usually one side has none, so most "
        "are expected; a branch missing here can be followed with `impactkit continue` from "
        "an orbit on it)\n",
        diagram.failed_starts);
  }
  fmt::print("branches (by the lowest {} they reach):\n", diagram.parameter);
  const auto lowest = [](const TracedBranch& b) {
    return std::min(b.branch.points.front().parameter, b.branch.points.back().parameter);
  };
  for (std::size_t k : ByParameter(labelled, lowest)) {
    const Branch& b = labelled[k].branch;
    const auto [lo, hi] = std::minmax_element(
        b.points.begin(), b.points.end(),
        [](const BranchPoint& x, const BranchPoint& y) { return x.parameter < y.parameter; });
    fmt::print("  {:<8} {} from {:.8g} to {:.8g}: {} ({})\n", labelled[k].label, FamilyName(b),
               lo->parameter, hi->parameter, DescribeStability(b), labelled[k].origin);
  }
  fmt::print("special points (in {} order):\n", diagram.parameter);
  const auto at = [](const DiagramNode& n) { return n.parameter; };
  for (std::size_t k : ByParameter(diagram.nodes, at)) {
    const DiagramNode& n = diagram.nodes[k];
    if (n.kind != DiagramNodeKind::kSpecialPoint) continue;
    std::string what =
        fmt::format("{} at {} = {:.10g} on {}", n.Name(), diagram.parameter, n.parameter,
                    n.p == 0 ? fmt::format("P(inf,{})", n.q) : fmt::format("P({},{})", n.p, n.q));
    if (n.special == SpecialPointType::kFold || n.special == SpecialPointType::kPeriodDoubling ||
        n.special == SpecialPointType::kNeimarkSacker ||
        n.special == SpecialPointType::kPitchfork) {
      what += fmt::format(" (multiplier {:.6f}{:+.6f}i)", n.multiplier.real(), n.multiplier.imag());
    } else if (n.special == SpecialPointType::kGrazing ||
               n.special == SpecialPointType::kSticking) {
      what += n.vanishing_impact < 0 ? " (a new contact)"
                                     : fmt::format(" (impact {} vanishes)", n.vanishing_impact + 1);
    }
    fmt::print("  {}\n", what);
    if (n.normal_form && n.normal_form->prediction) {
      fmt::print("    {}\n", n.normal_form->prediction->Describe());
    }
  }
  PrintUnlocated(labelled);
}

std::vector<LineChart> DiagramFigure(const SweptDiagram& swept, DiagramAxis axis) {
  LineChart chart = WholeDiagram(swept, axis);
  const std::optional<std::array<double, 2>> window = DensestWindow(swept.diagram);
  if (!window) return {chart};
  LineChart zoom = chart;
  chart.title = "(a) " + chart.title;
  zoom.title = fmt::format("(b) the densest window, {} = {:.4g} to {:.4g}",
                           ParameterLabel(swept.diagram.parameter), (*window)[0], (*window)[1]);
  zoom.x_range = window;
  return {chart, zoom};
}

std::string RenderDiagram(const std::vector<LineChart>& panels, ImageFormat format) {
  return RenderStacked(panels, 1100, panels.size() == 1 ? 650 : 1200, format);
}

}  // namespace impactkit::cli
