#pragma once
/// \file chatter_recorder.hpp
/// The times at which chatter sequences ended at the stop, as DetectPeriod
/// wants them (recorders.hpp has impacts and sticking intervals, not these).

#include <vector>

#include "impactkit/simulate.hpp"

namespace impactkit::cli {

class ChatterRecorder : public Observer {
 public:
  void OnChatter(double /*t_first*/, double t_end) override { end_times_.push_back(t_end); }
  const std::vector<double>& EndTimes() const { return end_times_; }

 private:
  std::vector<double> end_times_;
};

}  // namespace impactkit::cli
