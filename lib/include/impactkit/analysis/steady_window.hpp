#pragma once
/// \file steady_window.hpp
/// The window every steady-state analysis records after its transient: the
/// impacts, the stroboscopic points (t = kT) and the ends of chatter, from
/// which the period P(p, q) follows (periodicity.hpp). Seeding an orbit,
/// classifying a sweep value and summarising `impactkit simulate` all
/// record this same window.

#include <vector>

#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/hybrid/recorders.hpp"

namespace impactkit {

class SteadyWindowRecorder : public Observer {
 public:
  /// `period`: the forcing period T (stroboscopic sampling interval).
  explicit SteadyWindowRecorder(double period);
  SteadyWindowRecorder(const SteadyWindowRecorder&) = delete;
  SteadyWindowRecorder& operator=(const SteadyWindowRecorder&) = delete;

  void OnSegment(const Segment& segment) override { recorders_.OnSegment(segment); }
  void OnImpact(const Impact& impact) override { recorders_.OnImpact(impact); }
  void OnChatter(const ChatterEnd& chatter) override { recorders_.OnChatter(chatter); }

  const ImpactLog& Impacts() const { return impacts_.Impacts(); }
  const SampleLog& Strobe() const { return strobe_.Points(); }
  const std::vector<double>& ChatterEnds() const { return chatter_.EndTimes(); }
  /// The period of the recorded motion (DetectPeriod over this window).
  MotionPeriod Period(const PeriodOptions& options = {}) const;

 private:
  ImpactRecorder impacts_;
  StroboscopicRecorder strobe_;
  ChatterRecorder chatter_;
  ObserverList recorders_;
};

}  // namespace impactkit
