#include "impactkit/io/grid_output.hpp"

#include <fmt/format.h>

#include "impactkit/io/csv.hpp"

namespace impactkit {

PeriodLabels LabelsOf(const GridCell& cell) {
  PeriodLabels labels{ToString(cell.kind), "", ""};
  if (cell.q > 0) {
    labels.p = std::to_string(cell.p);
    labels.q = std::to_string(cell.q);
  }
  return labels;
}

std::string CellFields(const GridCell& cell) {
  const PeriodLabels labels = LabelsOf(cell);
  return fmt::format("{},{},{},{},{},{}", labels.kind, labels.p, labels.q, CsvField(cell.max_v),
                     CsvField(cell.range_xN), CsvField(cell.lyapunov));
}

std::string MotionLabel(const GridCell& cell) { return MotionLabel(cell.kind, cell.p, cell.q); }

}  // namespace impactkit
