#pragma once
/// \file orbit_shooting.hpp
/// P(p, q) as p flights between impacts at known stops, each flight
/// evaluated at its (unknown) end time rather than stopped by an event
/// search: unknowns z = (η_0, …, η_{p−1}), η_k at stop s_k, and residual
///
///     W_k(z) = y_k(τ_{k+1}) − y(η_{k+1}),   k = 0 … p−1,
///
/// y_k the free flight after the impact η_k (restitution applied at τ_k),
/// y(η) the state (x, v) η describes (x_c = xs), τ_p = τ_0 + qT, η_p = η_0.
///
/// Why: near a grazing impact the impact map P_I is a square root of the
/// flight's excess over the stop (D P_I ~ 1/v); Newton on P_I^p(η) − η
/// steps outside its domain (an iterate without the impact, or with v < 0)
/// and its residual cannot fall below the map's rounding, ε ‖D P_I‖. W is
/// the flow at fixed times: smooth in z for any sign of the speeds, its
/// Jacobian bounded as v → 0 (the formulation of Ghosh & Simpson 2025's
/// VIVID, regular at grazing). What W ignores, the stops between impacts,
/// is checked afterwards on the map (orbit.cpp), as is v > 0 at every impact.

#include <Eigen/Dense>
#include <vector>

#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

class ShootingProblem {
 public:
  /// `stops`: s_0 … s_{p−1}, s_0 the section's. `map` must be on `hybrid`.
  ShootingProblem(const HybridSystem& hybrid, const ImpactMap& map, std::vector<int> stops, int q);

  int Impacts() const { return static_cast<int>(stops_.size()); }
  int Stop(int k) const { return stops_[k]; }
  /// η_k from z, and z from η_0 … η_{p−1}.
  Eigen::VectorXd Eta(const Eigen::VectorXd& z, int k) const;
  Eigen::VectorXd Pack(const std::vector<Eigen::VectorXd>& etas) const;
  /// z with every τ_k moved by the same multiple of T, τ_0 into [0, T).
  Eigen::VectorXd WithPhase(Eigen::VectorXd z) const;

  /// W(z) into *w; false if it is not finite.
  bool Residual(const Eigen::VectorXd& z, Eigen::VectorXd* w) const;
  /// ∂W/∂z into *jacobian; false if it is not finite.
  bool Jacobian(const Eigen::VectorXd& z, Eigen::MatrixXd* jacobian) const;
  /// Newton on W = 0 from *z (SolveNewton), then, once converged, Newton
  /// steps beyond the solver's tolerance while max |W| falls: W is
  /// regular, so its zero is determined to W's rounding, ~ε‖y‖, and a map
  /// check magnifies what a tolerance leaves (1e-11 in W, ~1e-14 in v) by
  /// ‖D P_I‖ (~1/v). residual_norm is max |W| at the returned *z.
  SolveSummary Solve(const NewtonOptions& options, Eigen::VectorXd* z) const;
  /// D P_I^p at η_0 along the impacts of z (at their known times, where an
  /// event search at speeds ~ε‖x‖ could not place them): per flight the
  /// saltation of impact_map.hpp, dt' = −e_cᵀ G dη / v_c, dy = G + f dt'.
  Eigen::MatrixXd MapJacobian(const Eigen::VectorXd& z) const;

 private:
  /// The flight after η_k up to τ_{k+1}: its end state, ∂y(τ_{k+1})/∂η_k at
  /// that fixed time (G) and the vector field there (f).
  struct Flight {
    HybridState end;
    Eigen::MatrixXd g;
    Eigen::VectorXd f;
  };
  Flight Fly(const Eigen::VectorXd& z, int k, bool with_derivatives) const;
  /// τ_{k+1}: the next impact's time, τ_0 + qT after the last.
  double EndTime(const Eigen::VectorXd& z, int k) const;

  const HybridSystem& hybrid_;
  const ImpactMap& map_;
  std::vector<int> stops_;
  int q_;
  int n_;  ///< degrees of freedom; each η has 2 n_ entries
};

}  // namespace impactkit
