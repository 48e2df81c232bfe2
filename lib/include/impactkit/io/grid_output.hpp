#pragma once
/// \file grid_output.hpp
/// The one schema of a classified motion in every table (sweep --summary,
/// map, basins, paper's fig3-sweep.csv): its kind by name, its period, and
/// a cell's measured columns (docs/cli.md, "Motion kinds").

#include <string>

#include "impactkit/analysis/grid_cell.hpp"

namespace impactkit {

/// The kind by name ("periodic", "sticking", ...), p the impacts per q
/// forcing periods (0 when sticking: GridCell::p), both empty where the
/// motion does not repeat.
struct PeriodLabels {
  std::string kind, p, q;
};
PeriodLabels LabelsOf(const GridCell& cell);

/// The CSV columns of a cell after its coordinates (kind, p and q as
/// LabelsOf), and its fields.
inline constexpr const char* kCellColumns = "kind,p,q,max_velocity,range_xN,lyapunov";
std::string CellFields(const GridCell& cell);

/// "P(2,1)", "P(inf,1)", "non-impacting", "chaotic", "unresolved".
std::string MotionLabel(const GridCell& cell);

}  // namespace impactkit
