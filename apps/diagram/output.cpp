#include "diagram/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <numeric>

#include "common/branches.hpp"

namespace impactkit::cli {
namespace {

std::vector<double> Complex(std::complex<double> z) { return {z.real(), z.imag()}; }

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

nlohmann::json NodeJson(const DiagramNode& node, std::size_t id) {
  nlohmann::json multipliers = nlohmann::json::array();
  for (const std::complex<double>& m : node.multipliers) multipliers.push_back(Complex(m));
  const Eigen::VectorXd& eta = node.point.orbit.eta;
  nlohmann::json j = {{"id", id},
                      {"type", node.Name()},
                      {"param", node.parameter},
                      {"p", node.p},
                      {"q", node.q},
                      {"branch", node.branch},
                      {"multiplier", Complex(node.multiplier)},
                      {"multipliers", multipliers},
                      {"monitor", node.monitor},
                      {"eta", std::vector<double>(eta.data(), eta.data() + eta.size())}};
  if (node.special == SpecialPointType::kGrazing || node.special == SpecialPointType::kSticking) {
    j["vanishing_impact"] = node.vanishing_impact < 0 ? nlohmann::json(nullptr)
                                                      : nlohmann::json(node.vanishing_impact + 1);
  }
  return j;
}

nlohmann::json EdgeJson(const Diagram& diagram, const DiagramEdge& edge) {
  const Branch& branch = diagram.branches[edge.branch].branch;
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = edge.first; i <= edge.last; ++i) {
    const PeriodicOrbit& orbit = branch.points[i].orbit;
    std::vector<double> v;
    for (const OrbitImpact& impact : orbit.impacts) v.push_back(impact.velocity);
    points.push_back({{"param", branch.points[i].parameter},
                      {"stable", orbit.stable},
                      {"v", v},
                      {"range_xN", orbit.contacts.Range()}});
  }
  return {{"from", edge.from}, {"to", edge.to}, {"branch", edge.branch},
          {"p", branch.p},     {"q", branch.q}, {"points", points}};
}

/// The chart's y values of one orbit.
std::vector<double> AxisValues(const PeriodicOrbit& orbit, DiagramAxis axis) {
  if (axis == DiagramAxis::kRange) return {orbit.contacts.Range()};
  std::vector<double> v;
  for (const OrbitImpact& impact : orbit.impacts) v.push_back(impact.velocity);
  return v;
}

}  // namespace

void PrintDiagram(const Diagram& diagram) {
  const std::vector<TracedBranch> labelled = LabelBranches(diagram);
  fmt::print("diagram:    {}\n", diagram.BriefReport());
  fmt::print("branches (by the lowest {} they reach):\n", diagram.parameter);
  const auto lowest = [](const TracedBranch& b) {
    return std::min(b.branch.points.front().parameter, b.branch.points.back().parameter);
  };
  for (std::size_t k : ByParameter(labelled, lowest)) {
    const Branch& b = labelled[k].branch;
    const auto [lo, hi] = std::minmax_element(
        b.points.begin(), b.points.end(),
        [](const BranchPoint& x, const BranchPoint& y) { return x.parameter < y.parameter; });
    fmt::print("  {:<8} {} from {:.8g} to {:.8g}: {} ({})\n", labelled[k].label,
               fmt::format("P({},{})", b.p, b.q), lo->parameter, hi->parameter,
               DescribeStability(b), labelled[k].origin);
  }
  fmt::print("special points (in {} order):\n", diagram.parameter);
  const auto at = [](const DiagramNode& n) { return n.parameter; };
  for (std::size_t k : ByParameter(diagram.nodes, at)) {
    const DiagramNode& n = diagram.nodes[k];
    if (n.kind != DiagramNodeKind::kSpecialPoint) continue;
    std::string what = fmt::format("{} at {} = {:.10g} on P({},{})", n.Name(), diagram.parameter,
                                   n.parameter, n.p, n.q);
    if (n.special == SpecialPointType::kFold || n.special == SpecialPointType::kPeriodDoubling ||
        n.special == SpecialPointType::kNeimarkSacker ||
        n.special == SpecialPointType::kPitchfork) {
      what += fmt::format(" (multiplier {:.6f}{:+.6f}i)", n.multiplier.real(), n.multiplier.imag());
    } else if (n.special != SpecialPointType::kBranchPoint) {
      what += n.vanishing_impact < 0 ? " (a new contact)"
                                     : fmt::format(" (impact {} vanishes)", n.vanishing_impact + 1);
    }
    fmt::print("  {}\n", what);
  }
}

nlohmann::json DiagramJson(const Diagram& diagram) {
  nlohmann::json j = {{"parameter", diagram.parameter},     {"complete", diagram.complete},
                      {"message", diagram.message},         {"seconds", diagram.seconds},
                      {"nodes", nlohmann::json::array()},   {"edges", nlohmann::json::array()},
                      {"branches", nlohmann::json::array()}};
  for (std::size_t k = 0; k < diagram.nodes.size(); ++k) {
    j["nodes"].push_back(NodeJson(diagram.nodes[k], k));
  }
  for (const DiagramEdge& edge : diagram.edges) j["edges"].push_back(EdgeJson(diagram, edge));
  for (const TracedBranch& b : LabelBranches(diagram)) j["branches"].push_back(BranchJson(b));
  return j;
}

LineChart DiagramChart(const SweptDiagram& swept, DiagramAxis axis) {
  const Diagram& diagram = swept.diagram;
  LineChart chart;
  chart.title = "Connected bifurcation diagram";
  chart.x_label = ParameterLabel(diagram.parameter);
  chart.y_label = axis == DiagramAxis::kRange ? "max - min of x_N" : "impact velocity";
  Curve brute;
  brute.points = true;
  brute.color = "#999999";
  brute.point_size = 0.3;
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
  if (!brute.x.empty()) chart.curves.push_back(std::move(brute));
  const std::string kBranchColor = "#1f77b4";
  for (Curve& key : StabilityKey(kBranchColor)) chart.curves.push_back(std::move(key));
  for (const DiagramEdge& edge : diagram.edges) {
    const Branch& b = diagram.branches[edge.branch].branch;
    const std::size_t lines = AxisValues(b.points[edge.first].orbit, axis).size();
    for (std::size_t line = 0; line < lines; ++line) {
      // One curve per stretch of one stability, so that the pieces join.
      std::size_t from = edge.first;
      while (from < edge.last) {
        std::size_t to = from + 1;
        while (to < edge.last && b.points[to].orbit.stable == b.points[from].orbit.stable) ++to;
        Curve curve;
        curve.color = kBranchColor;
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
  std::map<SpecialPointType, Curve> marks;
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind != DiagramNodeKind::kSpecialPoint) continue;
    Curve& mark = marks.try_emplace(node.special, SpecialPointMarks(node.special)).first->second;
    for (double y : AxisValues(node.point.orbit, axis)) {
      mark.x.push_back(node.parameter);
      mark.y.push_back(y);
    }
  }
  for (auto& [name, mark] : marks) chart.curves.push_back(std::move(mark));
  return chart;
}

}  // namespace impactkit::cli
