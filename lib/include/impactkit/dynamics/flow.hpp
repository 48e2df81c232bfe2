#pragma once
/// \file flow.hpp
/// The exact flow of one linear regime (free flight, or the stuck subsystem):
///
///     y' = S y + b cos(Ω t) + d,     y = (x, v),
///     S = [[0, I], [-M⁻¹K, -M⁻¹C]],  b = (0, M⁻¹A),  d = (0, M⁻¹f0).
///
/// y(t) = y_p(t) + e^{S (t - t0)} (y(t0) - y_p(t0)), y_p the steady response.
/// S is split into 2 x 2 real blocks (one per mode): for each block the
/// spectral projection P_j, and with B_j its restriction, a_j = -tr(B_j)/2 and
/// β_j² = det(B_j) - a_j², Cayley–Hamilton gives exactly
///
///     e^{B_j τ} = e^{-a_j τ} [ C_j(τ) I + S_j(τ) (B_j + a_j I) ],
///     C_j = cos β_j τ, S_j = sin(β_j τ)/β_j   (cosh, sinh/|β| when β² < 0;
///                                              1, τ when β = 0)
///
/// which covers under-, critically and over-damped modes alike. Classically
/// damped systems (C M⁻¹ K = K M⁻¹ C) use the real normal modes, so exact
/// critical damping is fine; otherwise the blocks come from the complex
/// eigenvectors of S (pairs of conjugate or real eigenvalues). From 16
/// degrees of freedom on, normal modes are kept as Φ alone (V = Φ ⊗ I₂,
/// V⁻¹ = Φᵀ M ⊗ I₂): a change of basis is two n x n products instead of
/// one 2n x 2n, and nothing is inverted; a chain's Φ comes from its
/// tridiagonal eigenproblem in O(n²) (docs/theory.md, "Long chains").
///
/// Any linear output w = l_x·x + l_v·v + α cos Ωt + β along a flight is then an
/// exponential sum (Signal) whose derivatives of every order have the same
/// form, with computable bounds: the basis of event detection (events.hpp).

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "impactkit/dynamics/mode_clock.hpp"

namespace impactkit {

/// w(t) = Σ_j e^{-a_j τ}(α_j C_j(τ) + γ_j S_j(τ)) + Re(P e^{iΩτ}) + R,  τ = t - t0
/// (made by LinearFlow::Output).
class Signal {
 public:
  friend class LinearFlow;
  Signal() = default;

  double Value(double t) const;
  /// w(t) and w'(t) in one pass (they share the transcendental calls).
  void ValueAndSlope(double t, double* value, double* slope) const;
  /// w(t), w'(t), w''(t) in one pass.
  void ValueSlopeCurvature(double t, double* value, double* slope, double* curvature) const;
  /// The same with w from the anchor where one is declared (AnchorAt):
  /// for the root refinement, where w's rounding places the crossing. The
  /// rest of an event search decides on bounds far above that rounding,
  /// and the anchored sums cost ~40 % more per evaluation.
  void PreciseValueSlopeCurvature(double t, double* value, double* slope, double* curvature) const;
  /// The derivative of the given order as a Signal.
  Signal Derivative(int order = 1) const;
  /// sup |w^(order)(t)| over t >= t_from (t_from >= t0): a bound, not the value.
  double DerivativeBound(int order, double t_from) const;
  static constexpr int kMaxBoundOrder = 6;
  /// bounds[k] = DerivativeBound(k, t_from) for k = 0..max_order (<= 6), in
  /// one pass over the modes.
  void DerivativeBounds(double t_from, int max_order, double* bounds) const;
  /// -w.
  Signal Negated() const;
  /// Declares w(t0) = `value` and w'(t0) = `slope` exactly (the gap at an
  /// impact is 0 and its slope the rebound velocity): w is then evaluated
  /// as value + slope τ plus each term's remainder past the first order,
  /// e^{λτ} − 1 − λτ (ModeClock), whose rounding is relative to that
  /// remainder, not to the terms' size. A slow bounce's return (a crossing
  /// at speed u after a flight of duration s) is then placed to ~ε L ρ² s² / u
  /// instead of ε L / u (docs/theory.md §4), by PreciseValueSlopeCurvature,
  /// within ρ s <= 1 (ModeClock::AnchoredSpan; ρ the fastest rate), beyond
  /// which the plain sum rounds less.
  void AnchorAt(double value, double slope) {
    anchored_ = true;
    anchor_ = value;
    anchor_slope_ = slope;
  }
  /// The sum of the coefficients' magnitudes: a cheap scale for rounding
  /// noise in w (no transcendental calls).
  double Scale() const;
  /// R, the constant term.
  double Constant() const { return constant_; }
  double Omega() const { return omega_; }

 private:
  /// One mode's coefficients (α, γ) of w, w' and w'' (ModeBasis::Differentiate),
  /// kept side by side: an evaluation, some ten per flight, then
  /// differentiates nothing.
  struct ModeTerms {
    double alpha[3];
    double gamma[3];
    /// From w's coefficients.
    void Set(const ModeBasis& mode, double alpha0, double gamma0);
  };

  const ModeClock* clock_ = nullptr;
  double omega_ = 0.0;
  double t0_ = 0.0;
  std::vector<ModeTerms> terms_;
  std::complex<double> forced_{0.0, 0.0};  ///< P: the forced part at t0
  /// |P|, kept with P: the bounds and the scale of every flight's search
  /// need it, and each std::abs is a hypot call.
  double forced_magnitude_ = 0.0;
  double constant_ = 0.0;
  bool anchored_ = false;
  double anchor_ = 0.0;        ///< w(t0) where anchored
  double anchor_slope_ = 0.0;  ///< w'(t0) where anchored
};

/// A linear output l_x·x + l_v·v + α cos Ωt + β of a flow's state.
struct LinearOutput {
  Eigen::RowVectorXd wx;  ///< l_x (size N)
  Eigen::RowVectorXd wv;  ///< l_v (size N)
  double cos_amplitude = 0.0;
  double offset = 0.0;
};

/// A LinearOutput expressed in a flow's modal coordinates, ready to be
/// turned into a Signal for any flight at O(n) cost.
struct PreparedOutput {
  Eigen::RowVectorXd modal_weights;       ///< l^T V
  std::complex<double> forced{0.0, 0.0};  ///< l^T V Z + α
  double constant = 0.0;                  ///< l^T V z_c + β
};

/// The closed-form flow of one linear regime, decomposed once.
class LinearFlow {
 public:
  LinearFlow() = default;
  /// M, C, K (n x n), force amplitude A and constant force f0 (size n).
  /// Throws InvalidInput where no bounded steady response exists (undamped
  /// mode forced at its frequency) or the damping is non-classical with a
  /// defective (repeated) eigenvalue.
  LinearFlow(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
             const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing,
             const Eigen::VectorXd& constant_force, double omega);

  int Dof() const { return dof_; }
  double Omega() const { return omega_; }
  /// The shortest time scale of the motion: min(2π/Ω, 2π/ρ), ρ the largest
  /// |eigenvalue| of S (the fastest rate in the flow).
  double ShortestPeriod() const;

  /// Modal coordinates of the transient y(t) - y_p(t).
  Eigen::VectorXd Transient(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// The same into *z (no allocation once *z has its size: once per impact
  /// in the simulator).
  void Transient(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                 Eigen::VectorXd* z) const;
  /// The state at t of the flight that had transient z0 at t0 (no
  /// allocation once *x and *v have their sizes).
  void State(double t0, const Eigen::VectorXd& z0, double t, Eigen::VectorXd* x,
             Eigen::VectorXd* v) const;
  /// The same for the flight from (x0, v0) at t0 (z0 its transient), as
  /// (x0, v0) plus the flight's increment: each modal term's e^{Bτ} − I and
  /// the forcing's e^{iΩτ} − 1 without cancellation (ModeClock), so that
  /// the change over a short flight, a slow bounce's, carries rounding
  /// relative to itself rather than to the state's size (docs/theory.md §4).
  /// *x, *v may be x0, v0.
  void StateFrom(double t0, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                 const Eigen::VectorXd& z0, double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const;
  /// The steady (particular) response y_p(t).
  void SteadyState(double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const;
  PreparedOutput Prepare(const LinearOutput& output) const;
  /// An output along the flight that had transient z0 at t0.
  Signal Output(const PreparedOutput& output, double t0, const Eigen::VectorXd& z0) const;
  /// Same, reusing the storage of `signal` (no allocation in the event loop).
  void Output(const PreparedOutput& output, double t0, const Eigen::VectorXd& z0,
              Signal* signal) const;
  /// e^{S τ}, the state transition matrix (2n x 2n) in y = (x, v).
  Eigen::MatrixXd Transition(double tau) const;
  /// S, the first-order system matrix.
  const Eigen::MatrixXd& SystemMatrix() const { return system_matrix_; }

 private:
  /// z = V⁻¹ (x, v) and (x, v) = V z, in either form of V.
  void ToModal(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd* z) const;
  void FromModal(const Eigen::VectorXd& z, Eigen::VectorXd* x, Eigen::VectorXd* v) const;
  /// V (of basis_) or V⁻¹ (of inverse_basis_) as a 2n x 2n matrix.
  Eigen::MatrixXd DenseBasis(const Eigen::MatrixXd& half) const;

  int dof_ = 0;
  double omega_ = 0.0;
  double fastest_rate_ = 0.0;
  ModeClock clock_;
  /// The modal form: basis_ is Φ and inverse_basis_ Φᵀ M (n x n), the
  /// modal coordinates interleaving q_j and q_j'.
  bool modal_ = false;
  Eigen::MatrixXd basis_;           ///< V: y = V z, columns in pairs per mode
  Eigen::MatrixXd inverse_basis_;   ///< W = V⁻¹
  Eigen::MatrixXd shifted_blocks_;  ///< 2 x 2n: per mode, B_j + a_j I
  Eigen::VectorXcd steady_forced_;  ///< Z: z_p(t) = Re(Z e^{iΩt}) + z_c
  Eigen::VectorXd steady_constant_;
  Eigen::MatrixXd system_matrix_;
};

}  // namespace impactkit
