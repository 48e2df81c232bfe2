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
  static constexpr long kReservedImpactsPerPeriod = 2;
  static constexpr long kMaxReserved = long{1} << 24;

  /// `period`: the forcing period T (stroboscopic sampling interval).
  explicit SteadyWindowRecorder(double period);
  SteadyWindowRecorder(const SteadyWindowRecorder&) = delete;
  SteadyWindowRecorder& operator=(const SteadyWindowRecorder&) = delete;

  void OnSegment(const Segment& segment) override { recorders_.OnSegment(segment); }
  void OnImpact(const Impact& impact) override { recorders_.OnImpact(impact); }
  void OnChatter(const ChatterEnd& chatter) override { recorders_.OnChatter(chatter); }

  /// Room for a window of `periods` forcing periods: its stroboscopic
  /// points and impacts at up to kReservedImpactsPerPeriod a period (each
  /// log at most kMaxReserved records). Room never written costs address
  /// space only; a log that does not regrow faults each page in once,
  /// where growing by doubling faults in about twice its size (3 % of a
  /// 10^5-period `impactkit simulate`, docs/performance.md).
  void Reserve(long periods);
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
