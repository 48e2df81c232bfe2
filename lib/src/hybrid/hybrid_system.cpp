#include "impactkit/hybrid/hybrid_system.hpp"

#include <cmath>

#include "dynamics/subsystem.hpp"
#include "model/stuck_subsystem.hpp"

namespace impactkit {
namespace {

LinearFlow StuckFlowOf(const System& s) {
  const detail::StuckSubsystem stuck = detail::StuckSubsystemOf(s);
  try {
    return LinearFlow(stuck.mass, stuck.damping, stuck.stiffness, stuck.forcing,
                      stuck.constant_force, s.omega);
  } catch (const InvalidInput& e) {
    throw InvalidInput(detail::StuckSubsystemError(s, e.what()));
  }
}

}  // namespace

HybridSystem::HybridSystem(const System& system) : system_(system), stop_(system) {
  // Validate() would decompose both flows only to check them; they are
  // decomposed here once, and their constructors reject the resonances.
  ValidateParameters(system_);
  const int n = system_.Dof();
  free_flow_ = LinearFlow(system_.mass, system_.damping, system_.stiffness, system_.forcing,
                          Eigen::VectorXd::Zero(n), system_.omega);
  stuck_flow_ = StuckFlowOf(system_);
  gap_ = free_flow_.Prepare(stop_.Gap(n).output);
  release_ = stuck_flow_.Prepare(stop_.Release(system_).output);
  contact_force_ = stop_.ContactForce(system_);
  inverse_mass_ = system_.mass.inverse();
  inverse_mass_row_ = inverse_mass_.row(stop_.Dof());
  time_scale_ = free_flow_.ShortestPeriod();
}

Eigen::VectorXd HybridSystem::Acceleration(double t, const Eigen::VectorXd& x,
                                           const Eigen::VectorXd& v) const {
  return inverse_mass_ * (system_.forcing * std::cos(system_.omega * t) - system_.damping * v -
                          system_.stiffness * x);
}

Eigen::VectorXd HybridSystem::VectorField(double t, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& v) const {
  Eigen::VectorXd f(2 * system_.Dof());
  f << v, Acceleration(t, x, v);
  return f;
}

double HybridSystem::ContactAcceleration(double t, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& v, double* rate,
                                         Eigen::VectorXd* force,
                                         Eigen::VectorXd* acceleration) const {
  // The same sum, in the same order, as Acceleration(): A cos Ωt − C v − K x.
  const double wt = system_.omega * t;
  *force = system_.forcing * std::cos(wt);
  force->noalias() -= system_.damping * v;
  force->noalias() -= system_.stiffness * x;
  acceleration->noalias() = inverse_mass_ * *force;
  // d/dt of the force: -A Ω sin Ωt - C a - K v.
  force->noalias() = -system_.damping * *acceleration;
  force->noalias() -= system_.stiffness * v;
  *force -= system_.forcing * (system_.omega * std::sin(wt));
  *rate = inverse_mass_row_.dot(*force);
  return (*acceleration)(stop_.Dof());
}

double HybridSystem::ContactForce(double t, const Eigen::VectorXd& x_held,
                                  const Eigen::VectorXd& v_held) const {
  return contact_force_.wx.dot(x_held) + contact_force_.wv.dot(v_held) +
         contact_force_.cos_amplitude * std::cos(system_.omega * t) + contact_force_.offset;
}

Eigen::VectorXd HybridSystem::Held(const Eigen::VectorXd& full) const {
  return WithoutIndex(full, stop_.Dof());
}

Eigen::VectorXd HybridSystem::Full(const Eigen::VectorXd& held, double value) const {
  return EmbedAtStop(held, stop_.Dof(), value);
}

}  // namespace impactkit
