#pragma once
/// \file diagram/output.hpp
/// A traced diagram (impactkit/analysis/swept_diagram.hpp) as `impactkit
/// diagram` shows it: branches and special points in parameter order on
/// stdout, the graph as JSON, the picture over the brute-force points.

#include <nlohmann/json.hpp>
#include <string>

#include "common/plot.hpp"
#include "impactkit/analysis/swept_diagram.hpp"

namespace impactkit::cli {

/// What the diagram's picture shows against the parameter.
enum class DiagramAxis {
  kImpactVelocity,  ///< every impact speed of the orbit
  kRange,           ///< max − min of x_c (x_N for the chain) over the orbit
};

/// Every branch (P(p,q), range, stability) and every node, each list in
/// parameter order.
void PrintDiagram(const Diagram& diagram);

/// {parameter, nodes: [{id, type, param, p, q, multiplier, multipliers,
/// monitor, eta}], edges: [{from, to, branch, p, q, points: [{param,
/// stable, v, range_xN}]}], branches: [{label, origin, p, q, ...}]}.
nlohmann::json DiagramJson(const Diagram& diagram);

/// Stable stretches solid, unstable dashed, nodes marked by type, the
/// sweep's points (in the same axis) underneath.
LineChart DiagramChart(const SweptDiagram& swept, DiagramAxis axis);

}  // namespace impactkit::cli
