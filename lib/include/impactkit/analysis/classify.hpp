#pragma once
/// \file classify.hpp
/// The kind of a recorded steady motion, decided in this order:
///
///     no impact in the window                      -> kNonImpacting  (P(0, q) if it repeats)
///     DetectPeriod finds q <= max_q, chatter ends  -> kSticking      P(∞, q)
///     DetectPeriod finds q <= max_q                -> kPeriodic      P(p, q)
///     no period; impact-map Lyapunov exponent
///       λ_max > chaos_threshold (per unit time)    -> kChaotic
///     otherwise                                    -> kUnresolved
///
/// kUnresolved is what the first four cannot honestly claim: no period up to
/// max_q and an exponent that is not clearly positive (a period above max_q,
/// quasi-periodic motion, a transient not yet decayed near a bifurcation), or
/// an exponent that cannot be computed because the impact map stops at
/// chatter or grazing (the reason is in `lyapunov.message`).

#include <string>
#include <vector>

#include "impactkit/analysis/lyapunov.hpp"
#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

enum class MotionKind {
  kPeriodic,      ///< P(p, q), p >= 1 impacts in q forcing periods
  kSticking,      ///< P(∞, q): chatter ends at the stop within every period q
  kChaotic,       ///< no period, positive largest Lyapunov exponent
  kNonImpacting,  ///< no impact in the window
  kUnresolved,    ///< no period, exponent not positive or not computable
};

/// "periodic", "sticking", "chaotic", "non_impacting", "unresolved".
std::string ToString(MotionKind kind);

/// The motion's name in tables and predictions: "P(2,1)", "P(inf,1)",
/// "non-impacting", "chaotic", "unresolved" (p and q of a periodic or
/// sticking motion).
std::string MotionLabel(MotionKind kind, long p, int q);

struct ClassifyOptions {
  /// Period search: q up to max_q (64), stroboscopic points equal to a
  /// relative 1e-6.
  PeriodOptions period;
  /// The exponent is computed only when no period is found; its sign is
  /// all that matters here, so fewer impacts than the Lyapunov default do.
  LyapunovOptions lyapunov{1000, 100, {}};
  /// λ_max (per unit time) above which a motion without period is chaotic.
  /// Periodic attractors give clearly negative finite-time estimates and
  /// quasi-periodic ones |λ| of order 1/time_span; this margin keeps the
  /// latter out of kChaotic.
  double chaos_threshold = 1e-3;
  bool IsValid(std::string* error) const;
};

struct Classification {
  MotionKind kind = MotionKind::kUnresolved;
  MotionPeriod period;  ///< what DetectPeriod found
  /// Computed only when no period is found and the window has impacts.
  bool lyapunov_computed = false;
  LyapunovResult lyapunov;
  /// "P(2,1)", "P(inf,1)", "non-impacting", "chaotic (lambda = 0.031)",
  /// "unresolved: no period up to q = 64, lambda = -0.002".
  std::string ToString() const;
};

/// Classifies the motion recorded in a window: `strobe` once per forcing
/// period (StroboscopicRecorder), every impact and chatter end in the same
/// window. The exponent starts from the last impact. Throws InvalidInput for
/// invalid options or system.
Classification ClassifyMotion(const System& system, const SampleLog& strobe,
                              const ImpactLog& impacts,
                              const std::vector<double>& chatter_end_times,
                              const ClassifyOptions& options = {});

}  // namespace impactkit
