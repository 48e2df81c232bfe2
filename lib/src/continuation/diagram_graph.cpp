// The diagram's graph (diagram_graph.hpp) and its assembly from traced
// branches (diagram_builder.hpp).

#include "impactkit/continuation/diagram_graph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "continuation/diagram_builder.hpp"

namespace impactkit {

std::string DiagramNode::Name() const {
  switch (kind) {
    case DiagramNodeKind::kSpecialPoint:
      return ToString(special);
    case DiagramNodeKind::kBranchEnd:
      return ToString(end);
    case DiagramNodeKind::kStart:
      return "start";
  }
  return "unknown";
}

std::string Diagram::BriefReport() const {
  return fmt::format(
      "{} branches, {} nodes, {} edges in {:.3g} s ({} starts on traced branches, "
      "{} seeds not converged){}",
      branches.size(), nodes.size(), edges.size(), seconds, duplicate_starts, failed_starts,
      termination == Termination::kCompleted ? "" : "; incomplete: " + message);
}

namespace detail {
namespace {

/// Kinds of special point that one place in the diagram can show on two
/// branches: a period doubling is the doubled branch's branch point, a
/// grazing of one branch the grazing or sticking onset of the other.
int NodeClass(SpecialPointType type) {
  switch (type) {
    case SpecialPointType::kPeriodDoubling:
    case SpecialPointType::kBranchPoint:
      return 1;
    case SpecialPointType::kGrazing:
    case SpecialPointType::kSticking:
      return 2;
    default:
      return 0;  // folds and Neimark–Sacker points lie on one branch only
  }
}

/// The index of the branch point at `arclength` (a located special point is
/// one of the branch's points; the nearest one otherwise).
std::size_t PointIndex(const Branch& branch, double arclength) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < branch.points.size(); ++i) {
    if (std::abs(branch.points[i].arclength - arclength) <
        std::abs(branch.points[best].arclength - arclength)) {
      best = i;
    }
  }
  return best;
}

bool EndsAtSpecialPoint(Termination end) {
  return end == Termination::kGrazing || end == Termination::kSticking ||
         end == Termination::kBranchPoint || end == Termination::kNoSticking ||
         end == Termination::kEarlyRelease;
}

}  // namespace

bool DiagramBuilder::SameNode(const DiagramNode& node, SpecialPointType type, double parameter,
                              double range) const {
  if (node.kind != DiagramNodeKind::kSpecialPoint) return false;
  const int kind = NodeClass(type);
  if (kind == 0 || kind != NodeClass(node.special)) return false;
  const double node_range = node.point.orbit.contacts.Range();
  return std::abs(node.parameter - parameter) <=
             options_.node_tolerance * (1.0 + std::abs(parameter)) &&
         std::abs(node_range - range) <= options_.node_range_tolerance * (1.0 + std::abs(range));
}

int DiagramBuilder::SpecialNode(int index, const SpecialPoint& s) {
  const double range = s.point.orbit.contacts.Range();
  for (std::size_t n = 0; n < diagram_->nodes.size(); ++n) {
    if (SameNode(diagram_->nodes[n], s.type, s.parameter, range)) return static_cast<int>(n);
  }
  const Branch& branch = diagram_->branches[index].branch;
  DiagramNode node;
  node.kind = DiagramNodeKind::kSpecialPoint;
  node.special = s.type;
  node.parameter = s.parameter;
  node.multiplier = s.multiplier;
  node.multipliers = s.point.orbit.multipliers;
  node.monitor = s.monitor;
  node.vanishing_impact = s.vanishing_impact;
  node.user_test = s.user_test;
  node.normal_form = s.normal_form;
  node.normal_form_note = s.normal_form_note;
  node.p = branch.p;
  node.q = branch.q;
  node.branch = index;
  node.point = s.point;
  diagram_->nodes.push_back(std::move(node));
  return static_cast<int>(diagram_->nodes.size()) - 1;
}

int DiagramBuilder::EndNode(int index, std::optional<Termination> end, const BranchPoint& point) {
  const Branch& branch = diagram_->branches[index].branch;
  DiagramNode node;
  node.kind = end ? DiagramNodeKind::kBranchEnd : DiagramNodeKind::kStart;
  node.end = end.value_or(Termination::kParameterBound);
  node.parameter = point.parameter;
  node.multipliers = point.orbit.multipliers;
  node.p = branch.p;
  node.q = branch.q;
  node.branch = index;
  node.point = point;
  diagram_->nodes.push_back(std::move(node));
  return static_cast<int>(diagram_->nodes.size()) - 1;
}

std::vector<int> DiagramBuilder::AddBranch(int index) {
  const DiagramBranch& traced = diagram_->branches[index];
  const Branch& branch = traced.branch;
  // The nodes along the branch, each with the index of its point.
  std::vector<std::pair<int, std::size_t>> along;
  std::vector<int> specials;
  if (traced.parent >= 0 && !branch.begin) {
    along.emplace_back(traced.parent, 0);  // followed one way from the node it was born at
  } else if (!branch.begin || !EndsAtSpecialPoint(*branch.begin)) {
    along.emplace_back(EndNode(index, branch.begin, branch.points.front()), 0);
  }
  for (const SpecialPoint& s : branch.special_points) {
    specials.push_back(SpecialNode(index, s));
    along.emplace_back(specials.back(), PointIndex(branch, s.point.arclength));
  }
  if (!EndsAtSpecialPoint(branch.end)) {
    along.emplace_back(EndNode(index, branch.end, branch.points.back()), branch.points.size() - 1);
  }
  for (std::size_t k = 0; k + 1 < along.size(); ++k) {
    diagram_->edges.push_back(
        {along[k].first, along[k + 1].first, index, along[k].second, along[k + 1].second});
  }
  return specials;
}

}  // namespace detail
}  // namespace impactkit
