#pragma once
/// \file cvode_flight_top.hpp
/// The interior maxima of the contact mass over one free flight, integrated
/// by CVODE with no impact code (reference/cvode_impacts.hpp): the
/// independent recomputation of clearances (xs minus them) that tests of
/// grazing points use.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "cvode_impacts.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::testing {

/// Every interior local maximum of x_c over (t0, t1) of the free flight
/// from (x0, v0) at t0: 200 samples, then golden-section search around
/// each sample higher than its neighbours; a maximum within 1e-6 of either
/// end is the flight's end, not an interior one, and is left out.
inline std::vector<double> CvodeFlightTops(const System& system, double t0,
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
  std::vector<double> sampled(samples + 1);
  for (int i = 1; i < samples; ++i) sampled[i] = height(t0 + duration * i / samples);
  std::vector<double> tops;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 1; i < samples; ++i) {
    const bool left = i == 1 || sampled[i] >= sampled[i - 1];
    const bool right = i == samples - 1 || sampled[i] > sampled[i + 1];
    if (!left || !right) continue;
    double a = t0 + duration * (i - 1) / samples, b = t0 + duration * (i + 1) / samples;
    for (int n = 0; n < 60; ++n) {
      const double m1 = b - g * (b - a), m2 = a + g * (b - a);
      (height(m1) > height(m2) ? b : a) = height(m1) > height(m2) ? m2 : m1;
    }
    const double top = 0.5 * (a + b);
    if (top - t0 > 1e-6 && t1 - top > 1e-6) tops.push_back(height(top));
  }
  return tops;
}

/// The highest of them; empty when the flight has no interior maximum.
inline std::optional<double> CvodeFlightTop(const System& system, double t0,
                                            const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                                            double t1) {
  const std::vector<double> tops = CvodeFlightTops(system, t0, x0, v0, t1);
  if (tops.empty()) return std::nullopt;
  return *std::max_element(tops.begin(), tops.end());
}

}  // namespace impactkit::testing
