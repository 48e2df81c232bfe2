#pragma once
/// \file settling.hpp
/// Early certainty for a brute-force cell (docs/theory.md §10): a transient
/// that has reached a stable periodic orbit is recognised, the orbit
/// confirmed by a Newton solve, and the number of forcing periods after
/// which the state is within a given distance of it estimated from its
/// multipliers. At the end of each probe window of the transient:
///
///     the window's stroboscopic points repeat, P(p, q) with impacts
///         (DetectPeriod, q <= the probe's max_q)
///     seed: its last impact η (P_I^p), or for sticking its last release s
///         with the releases k that repeat (P_R^k, ReleaseRecorder::Seed)
///     FindOrbit from the seed (Newton only, no fallback): converged, every
///         multiplier |λ| <= ρ < 1
///     d = |seed − orbit|, relative to 1 + max |seed entry|, time modulo T:
///         d <= the period tolerance (the seed is on the orbit's doorstep)
///     n = the least n >= 1 with ρ^n d <= accuracy (0 if d <= accuracy):
///         after n q more periods the state is within `accuracy` of the
///         orbit, to first order in d; they must fit before the run's end
///
/// The probe observes one uninterrupted run, so a transient that never
/// settles is simulated exactly as without it (the same bits: splitting a
/// run at whole periods would round differently, and a chaotic transient
/// would then go elsewhere).

#include <memory>
#include <optional>

#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// A confirmed stable orbit and how far the transient still has to go.
struct Settling {
  MotionPeriod period;  ///< what the probe window showed
  int q = 1;            ///< forcing periods of the orbit: the clock may move by multiples
  int periods = 0;      ///< forcing periods (a multiple of q) to run before it is within accuracy
};

struct ProbeOptions {
  /// The window's period search: max_q (the window is 2 max_q + 1 periods
  /// long) and the tolerance, also the bound on d.
  PeriodOptions period;
  /// The distance to settle to (relative): the whole run's state is as
  /// close to the orbit at the same point, so what follows agrees to it.
  double accuracy = 1e-10;
  /// Newton solves that may fail before the probe gives up: each costs one,
  /// and a cell that keeps failing (an orbit too weakly stable for the
  /// periods left, a grazing one) would only pay them again.
  int attempts = 3;
  int end = 0;  ///< the run's last period: settling must be done by then
};

/// Watches a transient run from t = 0 and stops it (ShouldStop, after the
/// next event) once a window's orbit is confirmed.
class TransientProbe : public Observer {
 public:
  /// `period`: the forcing period T.
  TransientProbe(const System& system, double period, const ProbeOptions& options);

  void OnSegment(const Segment& segment) override;
  void OnImpact(const Impact& impact) override;
  void OnChatter(const ChatterEnd& chatter) override;
  void OnRelease(const Release& release) override;
  bool ShouldStop() const override { return settling_.has_value(); }

  /// The confirmed orbit, once the probe has stopped the run.
  const std::optional<Settling>& Settled() const { return settling_; }

 private:
  /// One probe window's record.
  struct Window {
    explicit Window(const System& system, double period);
    SteadyWindowRecorder steady;
    ReleaseRecorder releases;
    ObserverList observers;
  };
  /// At a window's end: confirm its orbit, or start the next window.
  void Check(double t);
  std::optional<Settling> Settle(const MotionPeriod& period) const;

  const System& system_;
  double period_;
  ProbeOptions options_;
  std::unique_ptr<Window> window_;  ///< none once the probe has given up or settled
  double window_end_ = 0.0;
  int attempts_left_ = 0;
  std::optional<Settling> settling_;
};

}  // namespace impactkit
