#pragma once
/// \file lyapunov.hpp
/// Lyapunov exponents of the impact map P_I (impact_map.hpp).
///
/// From an impact state η_0 the map is applied `transient_impacts` times,
/// then `impacts` more times, each with its analytic Jacobian
/// J_j = D P_I(η_j). The transient impacts align the orthonormal frame but
/// their logarithms are not counted.
/// The product J_{n-1} … J_0 is kept orthonormal by QR (Benettin et al.;
/// Eckmann & Ruelle):
///
///     Q_0 = I;   J_j Q_j = Q_{j+1} R_{j+1}   (Householder QR, diag R made >= 0)
///     λ_i = Σ_j log R_{j+1,ii} / (τ_n - τ_0)
///
/// All 2N exponents are normalised PER UNIT TIME: the sums of logarithms are
/// divided by the time elapsed over the counted impacts (τ_n - τ_0), not by
/// the number of impacts, so they are the exponents of the flow (less its
/// zero exponent along time) and comparable with the growth rate of the
/// separation of two simulated trajectories. Per impact, multiply by the mean
/// time between impacts, time_span / impacts_used.
///
/// The map only describes impacting motion: chatter, a grazing impact or a
/// lost impact ends the computation with valid = false and the reason in
/// `message` (never NaN exponents).

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "impactkit/model/system.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {

struct LyapunovOptions {
  /// Impacts whose Jacobians are multiplied (>= 1).
  int impacts = 2000;
  /// Impacts followed first without counting, to reach the attractor (>= 0).
  int transient_impacts = 200;
  /// The map's own options (lost-impact horizon, grazing speed).
  ImpactMapOptions map;
  bool IsValid(std::string* error) const;
};

struct LyapunovResult {
  /// The 2N exponents, descending, per unit time (see the file comment).
  std::vector<double> exponents;
  /// exponents.front() when valid, else 0.
  double largest = 0;
  /// Impacts whose Jacobians entered the product.
  int impacts_used = 0;
  /// τ_n - τ_0: the time over which the exponents are averaged.
  double time_span = 0;
  /// False when the map failed (chatter, grazing, lost impact); then
  /// `exponents` is empty.
  bool valid = false;
  std::string message;
};

/// Exponents of the impact map from the impact state `eta` (an η as in
/// impact_map.hpp: v_c > 0). Throws InvalidInput for an invalid system,
/// options or η; a failure of the map is reported in the result.
LyapunovResult ImpactMapLyapunov(const System& system, const Eigen::VectorXd& eta,
                                 const LyapunovOptions& options = {});

}  // namespace impactkit
