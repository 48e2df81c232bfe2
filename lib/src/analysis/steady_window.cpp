#include "impactkit/analysis/steady_window.hpp"

#include <algorithm>

namespace impactkit {

SteadyWindowRecorder::SteadyWindowRecorder(double period) : strobe_(period) {
  recorders_.Add(impacts_);
  recorders_.Add(strobe_);
  recorders_.Add(chatter_);
}

void SteadyWindowRecorder::Reserve(long periods) {
  const auto room = [](long records) {
    return static_cast<std::size_t>(std::clamp(records, long{0}, kMaxReserved));
  };
  strobe_.Reserve(room(periods + 1));
  impacts_.Reserve(room(kReservedImpactsPerPeriod * (periods + 1)));  // edges may add one
}

MotionPeriod SteadyWindowRecorder::Period(const PeriodOptions& options) const {
  std::vector<double> times;
  times.reserve(Impacts().size());
  for (const ImpactView impact : Impacts()) times.push_back(impact.t);
  return DetectPeriod(Strobe(), times, ChatterEnds(), options);
}

}  // namespace impactkit
