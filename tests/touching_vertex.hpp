#pragma once
/// \file touching_vertex.hpp
/// Where a fold curve touches a grazing curve, from one-parameter branches:
/// at distance δ from the corner the fold lies gap(δ) from the grazing,
/// gap = a δ + b δ² + c δ³ + d δ⁴ through four (δ, gap) pairs, and the
/// curves touch where that parabola has its vertex, −a / (2b) (b > 0).

#include <Eigen/Dense>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>

namespace impactkit::testing {

/// Checks that the fit through (deltas, gaps) opens upwards and has its
/// vertex within `tolerance` of δ = 0, the corner.
inline void CheckTouchingAtCorner(const std::array<double, 4>& deltas, const Eigen::Vector4d& gaps,
                                  double tolerance) {
  Eigen::Matrix4d powers;
  for (int k = 0; k < 4; ++k) {
    const double d = deltas[k];
    powers.row(k) << d, d * d, d * d * d, d * d * d * d;
  }
  const Eigen::Vector4d fit = powers.fullPivLu().solve(gaps);
  INFO("gaps " << gaps.transpose() << ", fit " << fit.transpose());
  CHECK(fit(1) > 0.0);
  CHECK(std::abs(fit(0) / (2.0 * fit(1))) < tolerance);
}

}  // namespace impactkit::testing
