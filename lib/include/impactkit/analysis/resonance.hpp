#pragma once
/// \file resonance.hpp
/// Resonance curves of the system WITHOUT its stop (the paper's Fig. 2): the
/// steady response of the linear chain to A cos(Ω t) in closed form,
///
///     (K - Ω² M + i Ω C) X = A,     x(t) = Re(X e^{iΩt}),
///
/// so the max-min displacement of mass i over a period is 2 |X_i|. The stop,
/// xs and r play no part. An undamped system has no bounded response at its
/// natural frequencies; there the solve fails and InvalidInput is thrown.

#include <Eigen/Dense>
#include <vector>

#include "impactkit/model/system.hpp"

namespace impactkit {

/// The complex amplitudes X(Ω) of the steady non-impacting response.
/// Throws InvalidInput for Ω <= 0 or a singular K - Ω²M + iΩC.
Eigen::VectorXcd SteadyResponse(const System& system, double omega);

struct ResonancePoint {
  double omega = 0.0;
  Eigen::VectorXd range;  ///< max - min of x_i over a period: 2 |X_i(Ω)|
  Eigen::VectorXd phase;  ///< arg X_i(Ω): x_i(t) = |X_i| cos(Ω t + phase_i)
};

/// The curve at `steps` values of Ω evenly spaced over [from, to] (steps = 1:
/// `from` only). Throws InvalidInput for from <= 0, to < from, steps < 1, or
/// from = to with steps > 1.
std::vector<ResonancePoint> ResonanceCurve(const System& system, double from, double to, int steps);

struct ResonancePeak {
  int dof = 0;         ///< the mass (0-based)
  double omega = 0.0;  ///< where 2|X_dof| has a local maximum
  double range = 0.0;  ///< 2|X_dof| there
};

/// The local maxima of each 2|X_i| inside (from, to): bracketed on the
/// curve's grid, then located by golden-section search to 1e-10 relative in
/// Ω. Maxima at the ends of the interval are not peaks and are left out.
/// Sorted by dof, then Ω.
std::vector<ResonancePeak> ResonancePeaks(const System& system,
                                          const std::vector<ResonancePoint>& curve);

}  // namespace impactkit
