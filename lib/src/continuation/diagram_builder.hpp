#pragma once
/// \file diagram_builder.hpp (private)
/// Turns traced branches into the nodes and edges of a Diagram
/// (diagram_graph.hpp): each branch is cut at its special points, and a
/// special point met again on another branch (the period doubling where the
/// doubled branch's pitchfork lands, the grazing the orbit with one impact
/// more starts from) becomes the same node.

#include <optional>
#include <vector>

#include "impactkit/continuation/diagram.hpp"
#include "impactkit/continuation/diagram_graph.hpp"

namespace impactkit::detail {

class DiagramBuilder {
 public:
  DiagramBuilder(Diagram* diagram, const DiagramOptions& options)
      : diagram_(diagram), options_(options) {}

  /// Adds diagram->branches[index] as edges between its nodes; its start is
  /// the node `parent` when the branch was followed one way from there.
  /// Returns the node index of each of its special points, in order.
  std::vector<int> AddBranch(int index);

 private:
  /// The node of special point `s` of branch `index`: an existing one it
  /// coincides with, or a new one.
  int SpecialNode(int index, const SpecialPoint& s);
  /// A new node where branch `index` stops for the reason `end`, or (none)
  /// where a branch followed one way starts.
  int EndNode(int index, std::optional<Termination> end, const BranchPoint& point);
  bool SameNode(const DiagramNode& node, SpecialPointType type, double parameter,
                double range) const;

  Diagram* diagram_;
  const DiagramOptions& options_;
};

}  // namespace impactkit::detail
