#pragma once
/// \file branch_point.hpp
/// One corrected point of a branch of periodic orbits.

#include <Eigen/Dense>
#include <array>

#include "impactkit/continuation/test_functions.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit {

struct BranchPoint {
  double parameter = 0.0;
  double arclength = 0.0;  ///< from the start point, signed by direction
  PeriodicOrbit orbit;     ///< at this parameter value
  /// The bifurcation test functions here, in BifurcationTests() order.
  std::array<double, kBifurcationTestCount> test_values{};
  Eigen::VectorXd tangent;  ///< unit tangent (η, μ) here
  /// For P(p, q) with a common prime divisor d of p and q: the orbit's
  /// failure to repeat after p/d impacts, P_I^{p/d}(η) − η − (q/d) T e_τ.
  /// Zero where the orbit is a P(p/d, q/d) orbit traversed d times; its
  /// sign flips where the branch passes through that point. Empty when p
  /// and q have no common divisor.
  Eigen::VectorXd repeat_gap;
};

}  // namespace impactkit
