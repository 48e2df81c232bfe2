#pragma once
/// \file stop.hpp
/// A rigid stop limiting one degree of freedom c at x_c = xs from one side,
/// as a component of its own: what ends a flight or a held phase (its
/// witnesses), what an impact does (its reset map and the reset's Jacobian)
/// and when the mass stays held (its sticking rule). The simulator and the
/// impact map take all of these from here (Drake's split of witness
/// functions and reset maps). With s = +1 for an upper stop (x_c <= xs) and
/// s = −1 for a lower one (x_c >= xs):
///
///     free       while g = s (x_c − xs) < 0; an impact when g reaches 0
///                upwards
///     impact     v(t+) = v(t−) + λ M⁻¹ e_c, the stop's impulse λ such that
///                v_c(t+) = −r v_c(t−): λ = −(1 + r) v_c(t−) / (M⁻¹)_cc.
///                With a diagonal M only v_c changes (the paper's law); with
///                masses coupled through M the impulse moves the others too,
///                and kinetic energy drops by (1 − r²) v_c² / (2 (M⁻¹)_cc)
///                (changing v_c alone could create energy there). While
///                other stops hold their masses, M is that of the masses
///                that move.
///     held       x_c = xs, v_c = 0 while Fs > 0, Fs the force pressing the
///                mass into the stop (s times the c-th row of
///                M x'' = A cos Ωt − C v − K x with the held masses'
///                accelerations zero: the stop's reaction); released when Fs
///                falls through 0, i.e. when −Fs crosses 0 upwards.

#include <Eigen/Dense>
#include <string_view>
#include <vector>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// What a witness's crossing triggers (Drake's event beside its witness
/// function): the simulator and the section maps act on this, not on the
/// mode the crossing happened in.
enum class EventAction {
  /// The mass reaches its stop: an impact by the stop's reset, or a landing
  /// where its chatter rule cannot resolve the bounce (then held if the stop
  /// pushes on it).
  kArrival,
  /// The stop stops pushing on the mass it holds: the mass moves again.
  kRelease,
};

/// An event as data: w(t) = l_x·x + l_v·v + α cos Ωt + β evaluated on a
/// flow's exact motion; the event is w crossing 0 upwards, and `action` what
/// it does.
struct Witness {
  std::string_view description;  ///< what the crossing means
  LinearOutput output;           ///< w, over the coordinates of the mode it watches
  EventAction action = EventAction::kArrival;
};

class Stop {
 public:
  /// Stop `index` of `system`: its DOF, side, position xs and restitution r.
  Stop(const System& system, int index);

  int Dof() const { return dof_; }
  double Position() const { return position_; }
  double Restitution() const { return restitution_; }
  /// +1 for an upper stop, −1 for a lower one.
  double Sign() const { return sign_; }
  /// The speed towards the stop of a mass moving with velocity v_c.
  double SpeedTowards(double v_c) const { return sign_ * v_c; }
  /// The gap s (x_c − xs) of the positions x (all N): exactly 0 at an impact.
  double GapOf(const Eigen::VectorXd& x) const { return sign_ * (x(dof_) - position_); }

  /// The witness over the coordinates `moving` (the free mode's N, or those
  /// of the masses that move while other stops hold theirs; this stop's DOF
  /// among them): g = s (x_c − xs).
  Witness Gap(const std::vector<int>& moving) const;
  /// The witness of a held mode (the coordinates `moving`, this stop among
  /// the holding ones: x_c = xs and v_c = a_c = 0 implied): −Fs.
  Witness Release(const System& system, const std::vector<int>& moving,
                  const Eigen::VectorXd& held_positions) const;
  /// Fs itself (positive: pushed into the stop), over the coordinates of
  /// the masses `moving`; the others are held at their stops' positions,
  /// given in `held_positions` (size N, zero where a mass moves).
  LinearOutput ContactForce(const System& system, const std::vector<int>& moving,
                            const Eigen::VectorXd& held_positions) const;

  /// The impact law on the velocities just before impact (moving towards
  /// the stop), all masses free.
  void Reset(Eigen::VectorXd& v) const { Reset(v, impulse_direction_, restitution_); }
  /// The same while other stops hold their masses: `direction` is the
  /// impulse's (ImpulseDirection of the masses that move).
  void Reset(Eigen::VectorXd& v, const Eigen::VectorXd& direction) const {
    Reset(v, direction, restitution_);
  }
  /// A landing: the impact law with r = 0 (v_c becomes 0, the others move
  /// with the impulse, so a full M loses energy rather than gaining it).
  void Absorb(Eigen::VectorXd& v) const { Reset(v, impulse_direction_, 0.0); }
  void Absorb(Eigen::VectorXd& v, const Eigen::VectorXd& direction) const {
    Reset(v, direction, 0.0);
  }
  /// M_F⁻¹ e_c / (M_F⁻¹)_cc over all N velocities, zero outside the masses
  /// `moving` (F): how each velocity moves per unit change of v_c.
  Eigen::VectorXd ImpulseDirection(const Eigen::MatrixXd& mass,
                                   const std::vector<int>& moving) const;
  const Eigen::VectorXd& ImpulseDirection() const { return impulse_direction_; }
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
  double sign_;
  double position_;
  double restitution_;
  /// M⁻¹ e_c / (M⁻¹)_cc: how the impulse moves each velocity per unit
  /// change of v_c (exactly e_c for a diagonal M), all masses free.
  Eigen::VectorXd impulse_direction_;

  void Reset(Eigen::VectorXd& v, const Eigen::VectorXd& direction, double restitution) const;
  Eigen::MatrixXd ResetJacobian(int dofs, double restitution) const;
};

}  // namespace impactkit
