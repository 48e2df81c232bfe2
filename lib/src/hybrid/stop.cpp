#include "impactkit/hybrid/stop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/symmetric_eigen.hpp"

namespace impactkit {
namespace {

/// The position of DOF `dof` among `moving`.
int IndexAmong(const std::vector<int>& moving, int dof) {
  return static_cast<int>(std::find(moving.begin(), moving.end(), dof) - moving.begin());
}

std::vector<int> AllDofs(int n) {
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  return all;
}

}  // namespace

Stop::Stop(const System& system, int index)
    : dof_(system.stops[index].dof),
      sign_(system.stops[index].Sign()),
      position_(system.stops[index].position),
      restitution_(system.stops[index].restitution),
      impulse_direction_(ImpulseDirection(system.mass, AllDofs(system.Dof()))) {}

Eigen::VectorXd Stop::ImpulseDirection(const Eigen::MatrixXd& mass,
                                       const std::vector<int>& moving) const {
  // A diagonal M moves no other mass (e_c), and needs no O(N³) solve.
  if (detail::IsDiagonal(mass)) return Eigen::VectorXd::Unit(mass.rows(), dof_);
  const int c = IndexAmong(moving, dof_);
  const auto m = static_cast<int>(moving.size());
  const Eigen::VectorXd column =
      Eigen::MatrixXd(mass(moving, moving)).partialPivLu().solve(Eigen::VectorXd::Unit(m, c));
  Eigen::VectorXd direction = Eigen::VectorXd::Zero(mass.rows());
  direction(moving) = column / column(c);
  direction(dof_) = 1.0;
  return direction;
}

void Stop::Reset(Eigen::VectorXd& v, const Eigen::VectorXd& direction, double restitution) const {
  // v_c is set directly rather than as v_c + Δ: −r v_c, the paper's law to
  // the last bit; the others move with the impulse (not at all for a
  // diagonal M, whose impulse direction is exactly e_c).
  const double change = -(1.0 + restitution) * v(dof_);
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    if (j != dof_) v(j) += change * direction(j);
  }
  v(dof_) = -restitution * v(dof_);
}

Witness Stop::Gap(const std::vector<int>& moving) const {
  const auto m = static_cast<int>(moving.size());
  return {"a mass reaches its stop (an impact or a landing)",
          {sign_ * Eigen::RowVectorXd::Unit(m, IndexAmong(moving, dof_)),
           Eigen::RowVectorXd::Zero(m), 0.0, -sign_ * position_},
          EventAction::kArrival};
}

/// Fs = s × row c of (A cos Ωt − C v − K x − M a), with the held masses at
/// their stops (v = a = 0 there) and a the accelerations of the masses F
/// that move, M_FF a_F = A_F cos Ωt − C_FF v_F − K_FF x_F − K_FH xs_H: linear
/// in their state.
LinearOutput Stop::ContactForce(const System& s, const std::vector<int>& moving,
                                const Eigen::VectorXd& held_positions) const {
  const int c = dof_;
  const Eigen::MatrixXd ms = s.mass(moving, moving);
  const Eigen::RowVectorXd coupling = s.mass(c, moving) * detail::SymmetricInverse(ms);
  LinearOutput f;
  f.wx = -s.stiffness(c, moving) + coupling * s.stiffness(moving, moving);
  f.wv = -s.damping(c, moving) + coupling * s.damping(moving, moving);
  f.cos_amplitude = s.forcing(c) - coupling.dot(s.forcing(moving));
  f.offset = 0.0;
  for (int h = 0; h < s.Dof(); ++h) {
    // A mass that moves, or one held at 0, adds nothing.
    if (held_positions(h) == 0.0) continue;
    const Eigen::VectorXd column = s.stiffness(moving, h);
    f.offset += (-s.stiffness(c, h) + coupling.dot(column)) * held_positions(h);
  }
  if (sign_ < 0) {
    f.wx = -f.wx;
    f.wv = -f.wv;
    f.cos_amplitude = -f.cos_amplitude;
    f.offset = -f.offset;
  }
  return f;
}

Witness Stop::Release(const System& system, const std::vector<int>& moving,
                      const Eigen::VectorXd& held_positions) const {
  LinearOutput minus = ContactForce(system, moving, held_positions);
  minus.wx = -minus.wx;
  minus.wv = -minus.wv;
  minus.cos_amplitude = -minus.cos_amplitude;
  minus.offset = -minus.offset;
  return {"the stop's force on the held mass falls through zero (a release)", minus,
          EventAction::kRelease};
}

Eigen::MatrixXd Stop::ResetJacobian(int dofs, double restitution) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Identity(2 * dofs, 2 * dofs);
  for (int j = 0; j < dofs; ++j) {
    // Zero directions are left as they are (+0): a diagonal M's Jacobian
    // is the paper's to the last bit.
    if (j != dof_ && impulse_direction_(j) != 0.0) {
      jacobian(dofs + j, dofs + dof_) = -(1.0 + restitution) * impulse_direction_(j);
    }
  }
  jacobian(dofs + dof_, dofs + dof_) = -restitution;
  return jacobian;
}

}  // namespace impactkit
