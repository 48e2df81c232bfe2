#pragma once
/// \file grazing_corner.hpp (private)
/// Where a fold or period-doubling curve of P(p, q) reaches the curve on
/// which one of the orbit's impacts vanishes: a corner of the region where
/// the orbit exists, located on that grazing curve rather than approached
/// along the bifurcation curve (whose multipliers grow like 1/v there, so
/// that its corrector stops short: grazing_limit.hpp).
///
/// The grazing orbit is the orbit without that impact, touching the stop:
/// for p = 1 the non-impacting response (closed form: X = (μ1, μ2), the
/// equations |X_c| = xs and σ(K_λ) = 0), for p >= 2 P(p − 1, q) with a
/// flight maximum at the stop (X = (η, t*, μ1, μ2), the grazing curve's
/// equations of curve_problem.hpp and σ(K_λ) = 0). Either way a square
/// system, solved by Newton from the point where the depth extrapolates
/// to zero.

#include <optional>

#include "continuation/curve_problem.hpp"
#include "impactkit/continuation/curve.hpp"

namespace impactkit::detail {

/// A fold or period-doubling curve whose slowest impact is this shallow
/// (depth v² / 2|a|) and still falling is near its corner: the impact
/// map's rounding grows like 1/v, so the curve is not followed closer.
constexpr double kCornerDepth = 1e-4;

/// The corner ahead of b, the last of a curve's points a, b (in order), if
/// `problem` is a fold or period-doubling curve heading to an impact's
/// vanishing (depth below kCornerDepth and falling): the located corner as
/// the curve's end point (no orbit: the orbit stops existing there), with
/// residuals |σ(K_λ)| and |clearance|. Empty when b is not so near, or the
/// corner found is not where the depth extrapolates to zero (within twice
/// that distance in (μ1, μ2)).
std::optional<Codim2Point> GrazingCornerAhead(const CurveProblem& problem, SpecialPointType type,
                                              const CurvePoint& a, const CurvePoint& b);

}  // namespace impactkit::detail
