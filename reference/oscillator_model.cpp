#include "oscillator_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace impactkit::reference {
namespace {

// A flight off the stop is trusted if it reaches this many position
// tolerances away from it. With 1, the rule fired only two impacts before
// CVODE let the paper's system through the stop (Ω = 0.2); 100 leaves a wide
// margin.
constexpr double kResolvedDepthInTolerances = 100.0;

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("reference integrator: " + what);
}

}  // namespace

LinearOscillator::LinearOscillator(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                                   const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing,
                                   const Eigen::VectorXd& constant_force, double omega)
    : omega_(omega) {
  const Eigen::Index n = mass.rows();
  Require(n > 0 && mass.cols() == n, "M must be square, N x N with N >= 1");
  Require(damping.rows() == n && damping.cols() == n, "C must be N x N like M");
  Require(stiffness.rows() == n && stiffness.cols() == n, "K must be N x N like M");
  Require(forcing.size() == n, "A must have N entries");
  Require(constant_force.size() == n, "f0 must have N entries");
  const Eigen::LDLT<Eigen::MatrixXd> m(mass);  // M is symmetric positive definite
  Require(m.info() == Eigen::Success && m.isPositive(), "M must be positive definite");
  minv_damping_ = m.solve(damping);
  minv_stiffness_ = m.solve(stiffness);
  minv_forcing_ = m.solve(forcing);
  minv_constant_force_ = m.solve(constant_force);
}

LinearOscillator::LinearOscillator(const System& system)
    : LinearOscillator(system.mass, system.damping, system.stiffness, system.forcing,
                       Eigen::VectorXd::Zero(system.mass.rows()), system.omega) {}

void LinearOscillator::Derivative(double t, const double* y, double* dydt) const {
  const Eigen::Index n = Dof();
  const Eigen::Map<const Eigen::VectorXd> x(y, n);
  const Eigen::Map<const Eigen::VectorXd> v(y + n, n);
  Eigen::Map<Eigen::VectorXd> dx(dydt, n);
  Eigen::Map<Eigen::VectorXd> dv(dydt + n, n);
  dx = v;
  dv = minv_forcing_ * std::cos(omega_ * t) + minv_constant_force_;
  dv.noalias() -= minv_damping_ * v;
  dv.noalias() -= minv_stiffness_ * x;
}

Eigen::VectorXd LinearOscillator::Acceleration(double t,
                                               const Eigen::Ref<const Eigen::VectorXd>& y) const {
  Eigen::VectorXd dydt(y.size());
  Derivative(t, y.data(), dydt.data());
  return dydt.tail(Dof());
}

Eigen::MatrixXd LinearOscillator::Jacobian() const {
  const Eigen::Index n = Dof();
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  jacobian.topRightCorner(n, n).setIdentity();
  jacobian.bottomLeftCorner(n, n) = -minv_stiffness_;
  jacobian.bottomRightCorner(n, n) = -minv_damping_;
  return jacobian;
}

Eigen::VectorXd LinearOscillator::StackState(const Eigen::VectorXd& x,
                                             const Eigen::VectorXd& v) const {
  Require(x.size() == Dof() && v.size() == Dof(), "x and v must have N entries each");
  Eigen::VectorXd y(2 * Dof());
  y << x, v;
  return y;
}

ImpactSequence::ImpactSequence(const System& system, const LinearOscillator& oscillator,
                               long max_impacts, double min_interimpact, double position_tolerance)
    : oscillator_(oscillator),
      max_impacts_(max_impacts),
      min_interimpact_(min_interimpact),
      min_flight_depth_(kResolvedDepthInTolerances * position_tolerance) {
  const Eigen::MatrixXd inverse_mass = system.mass.inverse();
  for (const StopParameters& stop : system.stops) {
    Require(stop.dof >= 0 && stop.dof < oscillator.Dof(), "a stop's dof must be in [0, N)");
    stops_.push_back({stop.dof, stop.side == StopSide::kUpper ? 1.0 : -1.0, stop.position,
                      stop.restitution, inverse_mass.col(stop.dof)});
  }
}

bool ImpactSequence::Begin(double t0, Eigen::Ref<Eigen::VectorXd> y) {
  for (int k = 0; k < StopCount(); ++k) {
    if (Gap(k, y.data()) < 0.0) continue;
    if (stops_[k].sign * y[oscillator_.Dof() + stops_[k].dof] > 0.0) return Impact(t0, y, k);
    chatter_detected_ = NextFlightUnresolvable(t0, y, k);
    if (chatter_detected_) return false;
  }
  return true;
}

bool ImpactSequence::Impact(double t, Eigen::Ref<Eigen::VectorXd> y, int stop) {
  const StopLaw& law = stops_[stop];
  const int velocity_index = oscillator_.Dof() + law.dof;
  const bool too_soon =
      !impacts_.empty() && impacts_.back().stop == stop && t - impacts_.back().t < min_interimpact_;
  const double speed = std::max(law.sign * y[velocity_index], 0.0);
  impacts_.push_back({t, speed, stop});
  // Newton's law with the stop's impulse λ acting through the mass matrix:
  // v+ = v− + λ M⁻¹ e_c with v_c+ = −r v_c−.
  const double v_c = law.sign * speed;
  const double impulse = -(1.0 + law.restitution) * v_c / law.inverse_mass_column(law.dof);
  for (int j = 0; j < oscillator_.Dof(); ++j) {
    if (j != law.dof) y[oscillator_.Dof() + j] += impulse * law.inverse_mass_column(j);
  }
  y[velocity_index] = -law.restitution * v_c;
  chatter_detected_ = too_soon || static_cast<long>(impacts_.size()) >= max_impacts_ ||
                      NextFlightUnresolvable(t, y, stop);
  return !chatter_detected_;
}

// Leaving the stop at speed |v_c| against an acceleration a_c > 0 towards it,
// the mass is back after about 2|v_c|/a_c, having got v_c^2/(2 a_c) away.
// When that flight is shorter than min_interimpact, or shallower than the
// integrator resolves, the impacts accumulate (with r = 0 the mass is simply
// held) and following them would follow round-off: CVODE lets the mass
// through the stop, odeint keeps it bouncing at a noise-level speed for ever.
// Stop here instead, as an observed short interval would.
bool ImpactSequence::NextFlightUnresolvable(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                                            int stop) const {
  const StopLaw& law = stops_[stop];
  const double a_c = law.sign * oscillator_.Acceleration(t, y)[law.dof];
  if (a_c <= 0.0) return false;  // moving off, or at least not pushed back
  const double speed = std::abs(y[oscillator_.Dof() + law.dof]);
  return 2.0 * speed <= a_c * min_interimpact_ || speed * speed <= 2.0 * a_c * min_flight_depth_;
}

ReferenceRun ImpactSequence::Finish(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                                    long rhs_evaluations) {
  const Eigen::Index n = oscillator_.Dof();
  ReferenceRun run;
  run.impacts = std::move(impacts_);
  run.x = y.head(n);
  run.v = y.tail(n);
  run.t = t;
  run.chatter_detected = chatter_detected_;
  run.rhs_evaluations = rhs_evaluations;
  return run;
}

}  // namespace impactkit::reference
