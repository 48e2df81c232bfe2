#pragma once
/// \file stop.hpp
/// A rigid stop limiting one degree of freedom c at x_c = xs, as a component
/// of its own: what ends a flight or a held phase (its witnesses), what an
/// impact does (its reset map and the reset's Jacobian) and when the mass
/// stays held (its sticking rule). The simulator and the impact map take all
/// of these from here (Drake's split of witness functions and reset maps).
///
///     free       while g = x_c − xs < 0; an impact when g reaches 0 upwards
///     impact     v(t+) = v(t−) + λ M⁻¹ e_c, the stop's impulse λ such that
///                v_c(t+) = −r v_c(t−): λ = −(1 + r) v_c(t−) / (M⁻¹)_cc.
///                With a diagonal M only v_c changes (the paper's law); with
///                masses coupled through M the impulse moves the others too,
///                and kinetic energy drops by (1 − r²) v_c² / (2 (M⁻¹)_cc)
///                (changing v_c alone could create energy there).
///     held       x_c = xs, v_c = 0 while Fs > 0, Fs the force pressing the
///                mass into the stop (the stop's reaction: the c-th row of
///                M x'' = A cos Ωt − C v − K x − Fs e_c with the held mass's
///                acceleration zero); released when Fs falls through 0, i.e.
///                when −Fs crosses 0 upwards.

#include <Eigen/Dense>
#include <string_view>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// An event as data: w(t) = l_x·x + l_v·v + α cos Ωt + β evaluated on a
/// flow's exact motion; the event is w crossing 0 upwards.
struct Witness {
  std::string_view description;  ///< what the crossing means
  LinearOutput output;           ///< w, over the coordinates of the mode it watches
};

class Stop {
 public:
  /// The stop of `system`: its contact DOF, position xs and restitution r.
  explicit Stop(const System& system);

  int Dof() const { return dof_; }
  double Position() const { return position_; }
  double Restitution() const { return restitution_; }

  /// The witness of the free mode (N coordinates): g = x_c − xs.
  Witness Gap(int dofs) const;
  /// The witness of the held mode (the N − 1 coordinates of the stuck
  /// subsystem, x_c = xs and v_c = a_c = 0 implied): −Fs.
  Witness Release(const System& system) const;
  /// Fs itself, the held mode's contact force (positive: pushed into the stop).
  LinearOutput ContactForce(const System& system) const;

  /// The impact law on the velocities just before impact (v_c > 0).
  void Reset(Eigen::VectorXd& v) const { Reset(v, restitution_); }
  /// A landing: the impact law with r = 0 (v_c becomes 0, the others move
  /// with the impulse, so a full M loses energy rather than gaining it).
  void Absorb(Eigen::VectorXd& v) const { Reset(v, 0.0); }
  /// ∂(x, v)(t+) / ∂(x, v)(t−), 2N x 2N: the identity except the column of
  /// v_c, which is −(1 + r) M⁻¹e_c / (M⁻¹)_cc + e_c (−r at v_c itself).
  Eigen::MatrixXd ResetJacobian(int dofs) const { return ResetJacobian(dofs, restitution_); }
  /// The same for a landing (r = 0).
  Eigen::MatrixXd AbsorbJacobian(int dofs) const { return ResetJacobian(dofs, 0.0); }

  /// The sticking rule: the mass stays held while the stop pushes on it.
  static bool Holds(double contact_force) { return contact_force > 0; }
  /// The same rule on the release witness w = −Fs of a held phase from t,
  /// where Fs may be zero to rounding (a mass landing at rest, the forcing
  /// just turning): held if w < 0 beyond its rounding, or w is zero to
  /// rounding and its first derivative that is not sends it below 0 — the
  /// judgement the release search starts with (SurfaceSign), so that a
  /// mass held here is not released at once. Holds(Fs) alone would let a
  /// mass pushed ever harder into the stop leave and land again at every
  /// rounding error.
  static bool Holds(const Signal& release, double t, const EventOptions& search) {
    return SurfaceSign(release, t, search) < 0;
  }

 private:
  int dof_;
  double position_;
  double restitution_;
  /// M⁻¹ e_c / (M⁻¹)_cc: how the impulse moves each velocity per unit
  /// change of v_c (exactly e_c for a diagonal M).
  Eigen::VectorXd impulse_direction_;

  void Reset(Eigen::VectorXd& v, double restitution) const;
  Eigen::MatrixXd ResetJacobian(int dofs, double restitution) const;
};

}  // namespace impactkit
