#pragma once
/// \file periodicity.hpp
/// The period of a recorded steady motion: P(p, q) means p impacts in q
/// forcing periods; sticking motions (chatter ended at the stop) are P(∞, q).

#include <string>
#include <vector>

#include "impactkit/hybrid/recorders.hpp"

namespace impactkit {

struct MotionPeriod {
  bool periodic = false;  ///< a period q <= max_q was found
  int q = 0;              ///< forcing periods
  long p = 0;             ///< impacts in q periods (before chatter ends, if sticking)
  bool sticking = false;  ///< chatter ends at the stop within the period: P(∞, q)
  double mismatch = 0.0;  ///< max |y(t + qT) - y(t)| over the window, relative
  /// The largest q tried: min(max_q, (points - 1) / 2), since a period q is
  /// confirmed by 2q + 1 points. Below max_q, "not periodic" only means
  /// "no period up to searched_q".
  int searched_q = 0;
  /// "P(2,1)", "P(inf,1)", or "no period up to q = 64".
  std::string ToString() const;
};

struct PeriodOptions {
  int max_q = 64;
  /// Stroboscopic points repeat when they agree to this, relative to the
  /// largest state component seen (at least 1e-3 absolute).
  double tolerance = 1e-6;
};

/// Looks for the smallest q with s_{k+q} = s_k for every stroboscopic point
/// of the window (which must hold at least 2q + 1 points). Impacts and
/// chatter ends are counted in the last q periods.
MotionPeriod DetectPeriod(const SampleLog& strobe, const std::vector<double>& impact_times,
                          const std::vector<double>& chatter_end_times,
                          const PeriodOptions& options = {});

}  // namespace impactkit
