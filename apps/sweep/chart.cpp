#include "sweep/chart.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/system_options.hpp"

namespace impactkit::cli {

std::vector<LineChart> SweepCharts(const System& system, const SweepOptions& options,
                                   const SweepResult& result) {
  const int c = system.stops[0].dof + 1;
  LineChart ranges, speeds;
  // Panel letters as the paper's Fig. 3 has them; no tool name in a title
  // that goes into a paper.
  ranges.title = fmt::format("(a) max - min of x{} in each recorded period", c);
  // Both panels span the whole sweep, also where one of them has no data
  // (no impacts above the last impacting value).
  std::optional<std::array<double, 2>> range;
  if (options.from != options.to) {
    range = std::array{std::min(options.from, options.to), std::max(options.from, options.to)};
  }
  ranges.x_label = ParameterLabel(options.parameter);
  ranges.x_range = range;
  ranges.y_from_zero = true;
  ranges.y_label = fmt::format("max - min x{}", c);
  speeds.title = "(b) " + ImpactSpeedLabel(system);
  speeds.x_label = ParameterLabel(options.parameter);
  speeds.x_range = range;
  speeds.y_label = "impact velocity";
  Curve range_points{fmt::format("x{}", c), {}, {}, false, "#1f77b4", true};
  Curve speed_points{"impacts", {}, {}, false, "#000000", true};
  for (const SweepPoint& point : result.points) {
    for (double r : point.range_contact) {
      range_points.x.push_back(point.value);
      range_points.y.push_back(r);
    }
    for (const SweepImpact& i : point.impacts) {
      speed_points.x.push_back(point.value);
      speed_points.y.push_back(i.velocity);
    }
  }
  ranges.curves.push_back(std::move(range_points));
  speeds.curves.push_back(std::move(speed_points));
  return {ranges, speeds};
}

}  // namespace impactkit::cli
