#pragma once
/// \file recomputed_special_point.hpp
/// A located fold, period doubling or Neimark–Sacker point recomputed
/// independently of the branch that located it (by bracketing its test
/// function along the branch).
///
/// Period doubling and Neimark–Sacker: a fresh FindOrbit at the point's μ
/// from its orbit, and the multiplier nearest the critical one.
///
/// Fold: a fresh solve at fixed μ is singular there — it finds η only to
/// about the square root of the map's rounding, and the multiplier of a
/// long orbit moves by 1e-3 with it (the N = 1 network's P(7,8)). The fold's
/// own defining system (U = 0 and σ(D P − I) = 0 in (η, μ)), regular at a
/// quadratic fold, is solved instead by the two-parameter curve code's
/// corrector (the start of a fold curve in a second parameter, held at its
/// value) from the located point: μ from it and the multiplier nearest +1
/// there (an eigenvalue of a fresh D P, not the σ the corrector zeroes).

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <string>

#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::testing {

inline std::complex<double> NearestMultiplier(const Eigen::VectorXcd& multipliers,
                                              std::complex<double> target) {
  std::complex<double> best = multipliers(0);
  for (const std::complex<double>& m : multipliers) {
    if (std::abs(m - target) < std::abs(best - target)) best = m;
  }
  return best;
}

/// A fresh FindOrbit of P(p, q) from `eta` in `system`, required to converge.
inline PeriodicOrbit RecomputedOrbit(const System& system, int p, int q,
                                     const Eigen::VectorXd& eta) {
  OrbitOptions options;
  options.p = p;
  options.q = q;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, eta, options, &orbit).termination == Termination::kConverged);
  return orbit;
}

/// The multiplier nearest `target` of RecomputedOrbit.
inline std::complex<double> RecomputedMultiplier(const System& system, int p, int q,
                                                 const Eigen::VectorXd& eta,
                                                 std::complex<double> target) {
  return NearestMultiplier(RecomputedOrbit(system, p, q, eta).multipliers, target);
}

struct RecomputedFold {
  double parameter = 0.0;
  Eigen::VectorXd eta;
  std::complex<double> multiplier;
};

/// The fold `fold` of a P(p, q) branch of `system` in `parameter`, solved
/// again from its located point (above).
inline RecomputedFold RecomputeFold(const System& system, const std::string& parameter,
                                    const SpecialPoint& fold) {
  CurveOptions options;
  options.parameter = parameter;
  options.parameter2 = std::string(parameter == "c" ? "k" : "c");
  const double mu = fold.point.parameter, mu2 = GetParameter(system, options.parameter2);
  options.from = mu - 0.01 * (1.0 + std::abs(mu));
  options.to = mu + 0.01 * (1.0 + std::abs(mu));
  options.from2 = mu2 - 1e-3;
  options.to2 = mu2 + 1e-3;
  options.max_points = 2;
  options.locate_codim2 = false;
  // From the located point Newton needs no line search, and on a long
  // orbit |U| reaches the map's rounding where a line search stalls.
  options.orbit.newton.line_search = false;
  const Curve curve = ContinueCurve({system, fold}, options);
  // The start is the point at μ2 itself; the others lie a step away.
  const CurvePoint* start = &curve.points.front();
  for (const CurvePoint& point : curve.points) {
    if (std::abs(point.parameter2 - mu2) < std::abs(start->parameter2 - mu2)) start = &point;
  }
  REQUIRE(std::abs(start->parameter2 - mu2) < 1e-12);
  return {start->parameter, start->orbit.eta, NearestMultiplier(start->orbit.multipliers, 1.0)};
}

}  // namespace impactkit::testing
