#pragma once
/// \file oscillator_model.hpp
/// The impact oscillator restated for the reference integrators, from the
/// fields of impactkit::System only (nothing of the library's code is used,
/// so that agreement with it is evidence): the smooth vector field in
/// first-order form, and the impact law with its bookkeeping.

#include <Eigen/Dense>
#include <vector>

#include "impactkit/model/system.hpp"
#include "reference_run.hpp"

namespace impactkit::reference {

/// M x'' + C x' + K x = A cos(Ω t) + f0 as y' = F(t, y) with y = (x, v).
/// M is factored once; F then costs two matrix-vector products.
class LinearOscillator {
 public:
  LinearOscillator(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                   const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing,
                   const Eigen::VectorXd& constant_force, double omega);
  /// The free flight of the impact oscillator (f0 = 0).
  explicit LinearOscillator(const System& system);

  int Dof() const { return static_cast<int>(minv_stiffness_.rows()); }

  /// dy/dt at (t, y); y and dydt hold 2N doubles each and must not overlap.
  /// Allocation-free, so it may be called from C callbacks.
  void Derivative(double t, const double* y, double* dydt) const;

  /// The acceleration M^{-1}(A cos Ωt + f0 - C v - K x) at y = (x, v).
  Eigen::VectorXd Acceleration(double t, const Eigen::Ref<const Eigen::VectorXd>& y) const;

  /// dF/dy = [[0, I], [-M^{-1}K, -M^{-1}C]], constant since the system is linear.
  Eigen::MatrixXd Jacobian() const;

  /// y = (x, v), the layout both integrators use. Throws
  /// std::invalid_argument unless x and v have N entries each.
  Eigen::VectorXd StackState(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;

 private:
  Eigen::MatrixXd minv_damping_;
  Eigen::MatrixXd minv_stiffness_;
  Eigen::VectorXd minv_forcing_;
  Eigen::VectorXd minv_constant_force_;
  double omega_;
};

/// Applies the impact law v_c -> -r v_c at each stop, records the impacts,
/// and decides when to give up because impacts accumulate. States are
/// stacked y = (x, v). A stop limits x_c from above (s = +1: x_c <= xs) or
/// below (s = -1: x_c >= xs).
class ImpactSequence {
 public:
  /// position_tolerance: the integrator's absolute accuracy in x_c near the
  /// stop (atol + rtol |xs|); flights much shallower than it are not trusted.
  ImpactSequence(const System& system, const LinearOscillator& oscillator, long max_impacts,
                 double min_interimpact, double position_tolerance);

  /// Call once with the initial state. A start on the stop moving into it is
  /// an impact at t0; a start on it moving away or at rest may end the run at
  /// once, as after an impact. Returns false if the run must stop.
  bool Begin(double t0, Eigen::Ref<Eigen::VectorXd> y);

  /// Records the impact at `stop` at t (y: the state just before it) and
  /// applies the impact law to y. A root found moving away is a graze
  /// blurred by round-off: it is recorded with velocity 0 and leaves v_c =
  /// 0. Returns false if the run must stop: impacts accumulate or
  /// max_impacts is reached.
  bool Impact(double t, Eigen::Ref<Eigen::VectorXd> y, int stop);

  int StopCount() const { return static_cast<int>(stops_.size()); }
  /// The signed distance g = s (x_c - xs) of `stop` (< 0 in free flight).
  double Gap(int stop, const double* y) const {
    const StopLaw& law = stops_[stop];
    return law.sign * (y[law.dof] - law.position);
  }

  /// The run's result, ending at (t, y). Call once, at the end: it hands
  /// over the recorded impacts.
  ReferenceRun Finish(double t, const Eigen::Ref<const Eigen::VectorXd>& y, long rhs_evaluations);

 private:
  struct StopLaw {
    int dof;
    double sign;
    double position;
    double restitution;
    Eigen::VectorXd inverse_mass_column;  ///< M⁻¹ e_c: the direction of the stop's impulse
  };
  bool NextFlightUnresolvable(double t, const Eigen::Ref<const Eigen::VectorXd>& y, int stop) const;

  const LinearOscillator& oscillator_;
  std::vector<StopLaw> stops_;
  long max_impacts_;
  double min_interimpact_;
  double min_flight_depth_;
  std::vector<ReferenceImpact> impacts_;
  bool chatter_detected_ = false;
};

}  // namespace impactkit::reference
