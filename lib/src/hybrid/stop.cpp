#include "impactkit/hybrid/stop.hpp"

#include <cmath>
#include <limits>

#include "dynamics/subsystem.hpp"

namespace impactkit {

Stop::Stop(const System& system)
    : dof_(system.contact_dof), position_(system.stop), restitution_(system.restitution) {
  const Eigen::VectorXd column =
      system.mass.partialPivLu().solve(Eigen::VectorXd::Unit(system.Dof(), dof_));
  impulse_direction_ = column / column(dof_);
  impulse_direction_(dof_) = 1.0;
}

void Stop::Reset(Eigen::VectorXd& v, double restitution) const {
  // v_c is set directly rather than as v_c + Δ: −r v_c, the paper's law to
  // the last bit; the others move with the impulse (not at all for a
  // diagonal M, whose impulse direction is exactly e_c).
  const double change = -(1.0 + restitution) * v(dof_);
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    if (j != dof_) v(j) += change * impulse_direction_(j);
  }
  v(dof_) = -restitution * v(dof_);
}

Witness Stop::Gap(int dofs) const {
  return {"the contact mass reaches the stop (an impact)",
          {Eigen::RowVectorXd::Unit(dofs, dof_), Eigen::RowVectorXd::Zero(dofs), 0.0, -position_}};
}

/// Fs = row c of (A cos Ωt - C v - K x - M a) with x_c = xs, v_c = a_c = 0 and
/// a the accelerations of the stuck subsystem: linear in its state.
LinearOutput Stop::ContactForce(const System& s) const {
  const int c = dof_;
  const Eigen::MatrixXd ms = WithoutIndex(s.mass, c);
  const Eigen::RowVectorXd coupling =
      WithoutIndex(Eigen::VectorXd(s.mass.row(c).transpose()), c).transpose() * ms.inverse();
  auto row = [&](const Eigen::MatrixXd& m) {
    return Eigen::RowVectorXd(WithoutIndex(Eigen::VectorXd(m.row(c).transpose()), c).transpose());
  };
  auto column = [&](const Eigen::MatrixXd& m) {
    return WithoutIndex(Eigen::VectorXd(m.col(c)), c);
  };
  LinearOutput f;
  f.wx = -row(s.stiffness) + coupling * WithoutIndex(s.stiffness, c);
  f.wv = -row(s.damping) + coupling * WithoutIndex(s.damping, c);
  f.cos_amplitude = s.forcing(c) - coupling.dot(WithoutIndex(s.forcing, c));
  f.offset = (-s.stiffness(c, c) + coupling.dot(column(s.stiffness))) * position_;
  return f;
}

Witness Stop::Release(const System& system) const {
  LinearOutput minus = ContactForce(system);
  minus.wx = -minus.wx;
  minus.wv = -minus.wv;
  minus.cos_amplitude = -minus.cos_amplitude;
  minus.offset = -minus.offset;
  return {"the stop's force on the held mass falls through zero (a release)", minus};
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
