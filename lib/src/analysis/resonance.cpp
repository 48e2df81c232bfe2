#include "impactkit/analysis/resonance.hpp"

#include <fmt/format.h>

#include <cmath>
#include <complex>

#include "impactkit/core/parameter_grid.hpp"

namespace impactkit {

Eigen::VectorXcd SteadyResponse(const System& system, double omega) {
  if (!(omega > 0.0) || !std::isfinite(omega)) {
    throw InvalidInput(fmt::format("omega must be > 0 and finite, got {}", omega));
  }
  const std::complex<double> i(0.0, 1.0);
  const Eigen::MatrixXcd dynamic = system.stiffness.cast<std::complex<double>>() -
                                   omega * omega * system.mass.cast<std::complex<double>>() +
                                   i * omega * system.damping.cast<std::complex<double>>();
  const Eigen::FullPivLU<Eigen::MatrixXcd> lu(dynamic);
  if (!lu.isInvertible()) {
    throw InvalidInput(fmt::format(
        "omega = {} is a natural frequency of the undamped system: no bounded response", omega));
  }
  return lu.solve(system.forcing.cast<std::complex<double>>());
}

std::vector<ResonancePoint> ResonanceCurve(const System& system, double from, double to,
                                           int steps) {
  if (steps < 1) throw InvalidInput(fmt::format("steps must be >= 1, got {}", steps));
  if (!(from > 0.0) || !std::isfinite(from) || !std::isfinite(to) || to < from) {
    throw InvalidInput(
        fmt::format("need 0 < from <= to (finite), got from = {}, to = {}", from, to));
  }
  if (from == to && steps > 1) {
    throw InvalidInput(fmt::format("from = to = {} with steps = {} > 1", from, steps));
  }
  std::vector<ResonancePoint> curve;
  curve.reserve(steps);
  for (int k = 0; k < steps; ++k) {
    ResonancePoint point;
    point.omega = GridValue(from, to, steps, k);
    const Eigen::VectorXcd x = SteadyResponse(system, point.omega);
    point.range = 2.0 * x.cwiseAbs();
    point.phase = x.unaryExpr([](std::complex<double> z) { return std::arg(z); }).real();
    curve.push_back(point);
  }
  return curve;
}

std::vector<ResonancePeak> ResonancePeaks(const System& system,
                                          const std::vector<ResonancePoint>& curve) {
  std::vector<ResonancePeak> peaks;
  const int n = system.Dof();
  for (int dof = 0; dof < n; ++dof) {
    const auto range = [&](double omega) {
      return 2.0 * std::abs(SteadyResponse(system, omega)(dof));
    };
    for (std::size_t k = 1; k + 1 < curve.size(); ++k) {
      const double here = curve[k].range(dof);
      if (!(here > curve[k - 1].range(dof) && here >= curve[k + 1].range(dof))) continue;
      // Golden-section search on [Ω_{k-1}, Ω_{k+1}], which brackets the
      // maximum: a few lines, and no one-dimensional maximiser in the stack.
      const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
      double a = curve[k - 1].omega, b = curve[k + 1].omega;
      double c = b - golden * (b - a), d = a + golden * (b - a);
      double fc = range(c), fd = range(d);
      while (b - a > 1e-10 * b) {
        if (fc > fd) {
          b = d, d = c, fd = fc;
          c = b - golden * (b - a), fc = range(c);
        } else {
          a = c, c = d, fc = fd;
          d = a + golden * (b - a), fd = range(d);
        }
      }
      const double omega = (a + b) / 2.0;
      peaks.push_back({dof, omega, range(omega)});
    }
  }
  return peaks;
}

}  // namespace impactkit
