#pragma once
/// \file diagram_graph.hpp
/// A connected bifurcation diagram as plain data: a graph whose nodes are
/// special points (and the other places where a branch ends) and whose
/// edges are stretches of branches between consecutive nodes. Built by
/// TraceDiagram (diagram.hpp); nothing here computes.
///
/// Every traced branch is kept whole in Diagram::branches; an edge names its
/// branch and the range of that branch's points it covers, from one node to
/// the next along the branch. A node where branches meet (a period doubling
/// and the doubled branch's start, a grazing and the orbit with one impact
/// more, a branch point and the shorter orbit's period doubling) is one node
/// shared by their edges.

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/core/termination.hpp"

namespace impactkit {

enum class DiagramNodeKind {
  kSpecialPoint,  ///< a located special point (DiagramNode::special says which)
  kBranchEnd,     ///< where a branch stops for another reason (DiagramNode::end)
  kStart,         ///< the seed of a branch followed one way only
};

struct DiagramNode {
  DiagramNodeKind kind = DiagramNodeKind::kSpecialPoint;
  SpecialPointType special = SpecialPointType::kFold;  ///< kind == kSpecialPoint
  /// kind == kBranchEnd: kParameterBound, kMaxPoints or kCorrectorFailed.
  Termination end = Termination::kParameterBound;
  double parameter = 0.0;
  /// The critical multiplier (fold, period doubling, Neimark–Sacker; 0
  /// otherwise) and every multiplier of the orbit at the node.
  std::complex<double> multiplier{0.0, 0.0};
  Eigen::VectorXcd multipliers;
  /// The test function or grazing monitor at the located point (0 at ends).
  double monitor = 0.0;
  int vanishing_impact = -1;  ///< grazing/sticking: the impact that vanishes (-1: a new contact)
  std::string user_test;      ///< a user test's zero: the test's name
  /// A grazing's normal form, or why there is none (SpecialPoint's).
  std::optional<GrazingNormalForm> normal_form;
  std::string normal_form_note;
  int p = 0, q = 0;   ///< of the branch the node was first located on (p = 0: sticking, P(inf,q))
  int branch = 0;     ///< that branch (index into Diagram::branches)
  BranchPoint point;  ///< the located point on that branch
  /// "period_doubling", "grazing", ... or "parameter_bound", "max_points",
  /// "corrector_failed", or "start": the name outputs use.
  std::string Name() const;
};

/// A stretch of one branch between two consecutive nodes along it.
struct DiagramEdge {
  int from = 0;    ///< node index
  int to = 0;      ///< node index
  int branch = 0;  ///< index into Diagram::branches
  /// The points branches[branch].branch.points[first..last] (inclusive).
  std::size_t first = 0, last = 0;
};

/// A traced branch and how it was reached.
struct DiagramBranch {
  Branch branch;
  std::string origin;  ///< "seed 2", "period doubling at omega = 1.61", ...
  int depth = 0;       ///< switches from a seed (0 for a seed's branch)
  int parent = -1;     ///< the node it was started from (-1 for a seed)
};

/// Summary::termination: kCompleted (every start was followed), kMaxPoints
/// (a bound of DiagramOptions, depth or branches, cut the network short;
/// the message says which) or kStopped (cancelled); iterations counts the
/// branches traced.
struct Diagram : Summary {
  std::string parameter;
  std::vector<DiagramNode> nodes;
  std::vector<DiagramEdge> edges;
  std::vector<DiagramBranch> branches;
  /// Starts not traced because they lie on a branch traced already
  /// (recognised by the orbit), and seeds that did not converge.
  int duplicate_starts = 0;
  int failed_starts = 0;
  /// "7 branches, 15 nodes, 16 edges in 3.2 s (2 starts on traced branches)".
  std::string BriefReport() const;
};

}  // namespace impactkit
