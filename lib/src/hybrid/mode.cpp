#include "impactkit/hybrid/mode.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/symmetric_eigen.hpp"
#include "hybrid/stuck_subsystem.hpp"
#include "impactkit/dynamics/mode_clock.hpp"
#include "impactkit/hybrid/system_flows.hpp"

namespace impactkit {
namespace {

LinearFlow FlowOf(const System& s, StopSet held) {
  // Free flight as it always was: no constant force at all (−0 would
  // differ in the last bit of nothing, but nothing is simpler).
  if (held == 0) {
    return LinearFlow(s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(s.Dof()),
                      s.omega);
  }
  return HeldFlow(s, held);
}

}  // namespace

Mode::Mode(const System& system, const std::vector<Stop>& stops, StopSet held)
    : system_(&system),
      held_(held),
      moving_(detail::MovingDofs(system, held)),
      held_positions_(Eigen::VectorXd::Zero(system.Dof())),
      flow_(FlowOf(system, held)),
      witnesses_(stops.size()),
      contact_forces_(stops.size()),
      impulse_directions_(stops.size()) {
  for (std::size_t k = 0; k < stops.size(); ++k) {
    if (Holds(static_cast<int>(k))) held_positions_(stops[k].Dof()) = stops[k].Position();
  }
  auto prepare = [&](const impactkit::Witness& witness) {
    return PreparedWitness{flow_.Prepare(witness.output), witness.action};
  };
  for (std::size_t k = 0; k < stops.size(); ++k) {
    const Stop& stop = stops[k];
    const auto at = std::find(moving_.begin(), moving_.end(), stop.Dof());
    dof_index_.push_back(at == moving_.end() ? -1 : static_cast<int>(at - moving_.begin()));
    if (Holds(static_cast<int>(k))) {
      contact_forces_[k] = stop.ContactForce(system, moving_, held_positions_);
      witnesses_[k] = prepare(stop.Release(system, moving_, held_positions_));
    } else if (dof_index_.back() >= 0) {
      witnesses_[k] = prepare(stop.Gap(moving_));
      impulse_directions_[k] =
          held == 0 ? stop.ImpulseDirection() : stop.ImpulseDirection(system.mass, moving_);
    }
  }
  inverse_mass_ = detail::SymmetricInverse(system.mass(moving_, moving_));
  damping_rows_ = system.damping(moving_, Eigen::all);
  inverse_mass_rows_.resize(stops.size());
  damping_responses_.resize(stops.size());
  for (std::size_t k = 0; k < stops.size(); ++k) {
    if (dof_index_[k] < 0) continue;
    inverse_mass_rows_[k] = inverse_mass_.row(dof_index_[k]);
    damping_responses_[k] = inverse_mass_rows_[k] * damping_rows_;
  }
  stiffness_rows_ = system.stiffness(moving_, Eigen::all);
  forcing_ = system.forcing(moving_);
}

Eigen::VectorXd Mode::Reduced(const Eigen::VectorXd& full) const {
  if (held_ == 0) return full;
  return full(moving_);
}

void Mode::Expand(const Eigen::VectorXd& x_moving, const Eigen::VectorXd& v_moving,
                  Eigen::VectorXd* x, Eigen::VectorXd* v) const {
  if (held_ == 0) {
    *x = x_moving;
    *v = v_moving;
    return;
  }
  *x = held_positions_;
  *v = Eigen::VectorXd::Zero(held_positions_.size());
  (*x)(moving_) = x_moving;
  (*v)(moving_) = v_moving;
}

Eigen::VectorXd Mode::VectorField(double t, const Eigen::VectorXd& x_moving,
                                  const Eigen::VectorXd& v_moving) const {
  Eigen::VectorXd x, v;
  Expand(x_moving, v_moving, &x, &v);
  const Eigen::VectorXd force =
      forcing_ * ForcingRotor(system_->omega, t).real() - damping_rows_ * v - stiffness_rows_ * x;
  Eigen::VectorXd f(2 * moving_.size());
  f << v_moving, inverse_mass_ * force;
  return f;
}

double Mode::Acceleration(int stop, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                          double* rate, Eigen::VectorXd* force,
                          Eigen::VectorXd* acceleration) const {
  // A_F cos Ωt − C_F· v − K_F· x (the held masses' v = 0 and x = xs give
  // −K_FH xs_H), in the order of HybridSystem::Acceleration.
  const std::complex<double> rotor = ForcingRotor(system_->omega, t);  // cos Ωt, sin Ωt
  const int c = dof_index_[stop];
  *force = forcing_ * rotor.real();
  force->noalias() -= damping_rows_ * v;
  force->noalias() -= stiffness_rows_ * x;
  if (held_ == 0) {
    acceleration->noalias() = inverse_mass_ * *force;
  } else {
    acceleration->setZero();
    (*acceleration)(moving_) = inverse_mass_ * *force;
  }
  const double a_c = (*acceleration)(moving_[c]);
  // d/dt of the force: −A_F Ω sin Ωt − C_F· a − K_F· v.
  force->noalias() = -damping_rows_ * *acceleration;
  force->noalias() -= stiffness_rows_ * v;
  *force -= forcing_ * (system_->omega * rotor.imag());
  *rate = inverse_mass_rows_[stop].dot(*force);
  return a_c;
}

ContactResponse Mode::Contact(int stop) const {
  const int c = dof_index_[stop];
  const Eigen::VectorXd response = inverse_mass_ * stiffness_rows_.col(moving_[c]);
  double coupling = 0.0;
  for (Eigen::Index j = 0; j < response.size(); ++j) {
    if (j != c) coupling = std::max(coupling, std::abs(response(j)));
  }
  return {inverse_mass_rows_[stop](c), damping_responses_[stop](moving_[c]), response(c), coupling};
}

double Mode::ContactForce(int stop, double t, const Eigen::VectorXd& x_moving,
                          const Eigen::VectorXd& v_moving) const {
  const LinearOutput& f = *contact_forces_[stop];
  return f.wx.dot(x_moving) + f.wv.dot(v_moving) + f.cos_amplitude * std::cos(system_->omega * t) +
         f.offset;
}

}  // namespace impactkit
