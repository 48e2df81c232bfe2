#pragma once
/// \file grazing_corner.hpp (private)
/// Where a fold or period-doubling curve of P(1, q) reaches the curve on
/// which the orbit's impact vanishes: a corner of the region where the
/// orbit exists, located on that grazing curve rather than approached
/// along the bifurcation curve (whose multipliers grow like 1/v there, so
/// that its corrector stops short: grazing_limit.hpp).

#include <optional>

#include "continuation/curve_problem.hpp"
#include "impactkit/continuation/curve.hpp"

namespace impactkit::detail {

struct GrazingCorner {
  double mu1 = 0.0, mu2 = 0.0;
  /// The non-impacting response's clearance there (zero on the grazing
  /// curve) and the grazing limit of the multiplier condition (zero at the
  /// corner): both residuals.
  double clearance = 0.0;
  double limit = 0.0;
};

/// The corner of the P(1, q) curve of `problem` for multiplier `lambda`
/// (+1 fold, −1 period doubling): Newton in (μ1, μ2) on the response's
/// clearance xs − |X_c| and SpeedSplitMonodromy::GrazingLimit(λ), from
/// (mu1, mu2); empty without convergence.
std::optional<GrazingCorner> LocateGrazingCorner(const CurveProblem& problem, int q, double lambda,
                                                 double mu1, double mu2);

/// A fold or period-doubling curve of P(1, q) whose slowest impact is this
/// shallow (depth v² / 2|a|) and still falling is near its corner: the
/// impact map's rounding grows like 1/v, so the curve is not followed closer.
constexpr double kCornerDepth = 1e-4;

/// The corner ahead of b, the last of a curve's points a, b (in order), if
/// the curve is a fold or period doubling of P(1, q) heading to its impact's
/// vanishing (depth below kCornerDepth and falling): the located corner as
/// the curve's end point (no orbit: the orbit stops existing there), with
/// residuals |limit| and |clearance|. Empty when b is not so near, or the
/// corner found is not where the depth extrapolates to zero (within twice
/// that distance in (μ1, μ2)).
std::optional<Codim2Point> GrazingCornerAhead(const CurveProblem& problem, SpecialPointType type,
                                              const CurvePoint& a, const CurvePoint& b);

}  // namespace impactkit::detail
