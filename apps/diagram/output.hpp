#pragma once
/// \file diagram/output.hpp
/// A traced diagram (impactkit/analysis/swept_diagram.hpp) as `impactkit
/// diagram` shows it: branches and special points in parameter order on
/// stdout, the graph as JSON, the picture over the brute-force points.

#include <string>
#include <vector>

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

/// The diagram's figure: the whole range, the branches coloured by family
/// (period; the 24 shortest periods, the others grey), stable stretches solid and unstable dashed,
/// special points as open markers by type, the sweep's points (in the same axis) underneath, its
/// title saying how many branches from how many seeds and whether the network was cut short. A
/// dense diagram (more than 12 branches) gets a second panel, the window an eighth of the range
/// wide that holds the most special points. Render with RenderDiagram.
std::vector<LineChart> DiagramFigure(const SweptDiagram& swept, DiagramAxis axis);

/// The figure's panels stacked in one `format` image. Throws PlotError.
std::string RenderDiagram(const std::vector<LineChart>& panels, ImageFormat format);

}  // namespace impactkit::cli
