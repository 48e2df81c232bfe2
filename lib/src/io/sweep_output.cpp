#include "impactkit/io/sweep_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "impactkit/analysis/grid_cell.hpp"
#include "impactkit/io/grid_output.hpp"

namespace impactkit {
namespace {

/// The largest (or smallest) of `values`; NaN (an empty field) for none.
double Extreme(const std::vector<double>& values, bool largest) {
  if (values.empty()) return std::nan("");
  return largest ? *std::max_element(values.begin(), values.end())
                 : *std::min_element(values.begin(), values.end());
}

}  // namespace

std::vector<std::string> SweepSummaryColumns(const std::string& parameter) {
  return {parameter,
          "kind",
          "p",
          "q",
          "range_xN",
          "range_x1",
          "range_xN_min",
          "range_x1_min",
          "impacts",
          "velocity_min",
          "velocity_max",
          "lyapunov",
          "restarted"};
}

std::string SweepSummaryRow(const SweepPoint& point) {
  const Classification& c = point.classification;
  const PeriodLabels period = LabelsOf(CellOf(0, point));
  std::vector<double> speeds;
  for (const SweepImpact& i : point.impacts) speeds.push_back(i.velocity);
  const double lyapunov =
      c.lyapunov_computed && c.lyapunov.valid ? c.lyapunov.largest : std::nan("");
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", CsvField(point.value), period.kind,
                     period.p, period.q, CsvField(Extreme(point.range_contact, true)),
                     CsvField(Extreme(point.range_first, true)),
                     CsvField(Extreme(point.range_contact, false)),
                     CsvField(Extreme(point.range_first, false)), point.impacts.size(),
                     CsvField(Extreme(speeds, false)), CsvField(Extreme(speeds, true)),
                     CsvField(lyapunov), point.restarted ? 1 : 0);
}

std::vector<std::string> SweepImpactColumns(const std::string& parameter) {
  return {parameter, "t", "phase", "velocity", "stop"};
}

void WriteSweepImpactRows(CsvWriter& csv, const SweepResult& result) {
  for (const SweepPoint& point : result.points) {
    for (const SweepImpact& i : point.impacts) {
      const double row[] = {point.value, i.t, i.phase, i.velocity, i.stop + 1.0};
      csv.WriteRow(row);
    }
  }
}

}  // namespace impactkit
