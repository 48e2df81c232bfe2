#include "sweep/chart.hpp"

#include <fmt/format.h>

namespace impactkit::cli {

std::vector<LineChart> SweepCharts(const System& system, const SweepOptions& options,
                                   const SweepResult& result) {
  const int c = system.contact_dof + 1;
  LineChart ranges, speeds;
  ranges.title = fmt::format("impactkit sweep: max - min of x{} in each recorded period", c);
  ranges.x_label = options.parameter;
  ranges.y_label = fmt::format("max - min x{}", c);
  speeds.title = fmt::format("impact velocity v{}(t-)", c);
  speeds.x_label = options.parameter;
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
