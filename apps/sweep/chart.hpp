#pragma once
/// \file sweep/chart.hpp
/// The two panels of the paper's Fig. 3 from a sweep, shared by `impactkit
/// sweep --plot` and `impactkit paper`.

#include <vector>

#include "common/plot.hpp"
#include "impactkit/analysis/sweep.hpp"

namespace impactkit::cli {

/// (a) per-period max - min of the contact mass, (b) impact speeds, against
/// the swept parameter: every recorded period and impact a dot.
std::vector<LineChart> SweepCharts(const System& system, const SweepOptions& options,
                                   const SweepResult& result);

}  // namespace impactkit::cli
