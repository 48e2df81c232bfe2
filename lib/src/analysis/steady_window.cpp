#include "impactkit/analysis/steady_window.hpp"

namespace impactkit {

SteadyWindowRecorder::SteadyWindowRecorder(double period) : strobe_(period) {
  recorders_.Add(impacts_);
  recorders_.Add(strobe_);
  recorders_.Add(chatter_);
}

MotionPeriod SteadyWindowRecorder::Period(const PeriodOptions& options) const {
  std::vector<double> times;
  times.reserve(Impacts().size());
  for (const ImpactView impact : Impacts()) times.push_back(impact.t);
  return DetectPeriod(Strobe(), times, ChatterEnds(), options);
}

}  // namespace impactkit
