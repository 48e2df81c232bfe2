#pragma once
/// \file cvode_flight_top.hpp
/// The highest interior point of the contact mass over one free flight,
/// integrated by CVODE with no impact code (reference/cvode_impacts.hpp):
/// the independent recomputation of a clearance (xs minus it) that tests of
/// grazing points use.

#include <Eigen/Dense>
#include <cmath>
#include <optional>

#include "cvode_impacts.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::testing {

/// max x_c over (t0, t1) of the free flight from (x0, v0) at t0: 200
/// samples, then golden-section search around the highest. Empty when the
/// highest point lies within 1e-6 of either end (the flight has no
/// interior maximum there).
inline std::optional<double> CvodeFlightTop(const System& system, double t0,
                                            const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                                            double t1) {
  const int c = system.stops[0].dof;
  auto height = [&](double t) {
    if (t - t0 < 1e-9) return x0(c);  // CVODE needs an interval
    Eigen::VectorXd x = x0, v = v0;
    reference::CvodeLinearFlow(system.mass, system.damping, system.stiffness, system.forcing,
                               Eigen::VectorXd::Zero(system.Dof()), system.omega, t0, x, v, t);
    return x(c);
  };
  const double duration = t1 - t0;
  const int samples = 200;
  int best = 1;
  for (int i = 2; i < samples; ++i) {
    if (height(t0 + duration * i / samples) > height(t0 + duration * best / samples)) best = i;
  }
  double a = t0 + duration * (best - 1) / samples, b = t0 + duration * (best + 1) / samples;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int n = 0; n < 60; ++n) {
    const double m1 = b - g * (b - a), m2 = a + g * (b - a);
    (height(m1) > height(m2) ? b : a) = height(m1) > height(m2) ? m2 : m1;
  }
  const double top = 0.5 * (a + b);
  if (top - t0 <= 1e-6 || t1 - top <= 1e-6) return std::nullopt;
  return height(top);
}

}  // namespace impactkit::testing
