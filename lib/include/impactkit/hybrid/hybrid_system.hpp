#pragma once
/// \file hybrid_system.hpp
/// A system with its stop, decomposed once per parameter value: the exact
/// flow of each mode — free (N coordinates) and held at the stop (the N − 1
/// of the stuck subsystem) — the stop's witnesses prepared on them, and the
/// free vector field. The simulator and the impact map are built on one;
/// share it (std::shared_ptr) to decompose a parameter value's flows once.

#include <Eigen/Dense>
#include <memory>

#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

class HybridSystem {
 public:
  /// Throws InvalidInput for an invalid system, or one whose free or held
  /// mode has no bounded steady response (an undamped mode forced at its
  /// frequency).
  explicit HybridSystem(const System& system);

  const System& GetSystem() const { return system_; }
  const Stop& GetStop() const { return stop_; }
  const LinearFlow& FreeFlow() const { return free_flow_; }
  const LinearFlow& StuckFlow() const { return stuck_flow_; }
  /// The stop's witnesses, prepared: the gap on the free flow, −Fs on the
  /// stuck flow.
  const PreparedOutput& Gap() const { return gap_; }
  const PreparedOutput& Release() const { return release_; }
  /// The shortest time scale of the free motion (event search, chatter).
  double TimeScale() const { return time_scale_; }

  /// M⁻¹ (A cos Ωt − C v − K x): the free mode's accelerations.
  Eigen::VectorXd Acceleration(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// f(t, y) = (v, a) of the free mode, y = (x, v).
  Eigen::VectorXd VectorField(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// a_c and, in *rate, da_c/dt of the free mode, using `force` and
  /// `acceleration` (size N) as scratch: no allocation per call.
  double ContactAcceleration(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                             double* rate, Eigen::VectorXd* force,
                             Eigen::VectorXd* acceleration) const;
  /// Fs of the held mode at t, from the stuck subsystem's state.
  double ContactForce(double t, const Eigen::VectorXd& x_held, const Eigen::VectorXd& v_held) const;

  /// The held mode's coordinates of a full vector (the contact DOF removed),
  /// and back (`value` at the contact DOF).
  Eigen::VectorXd Held(const Eigen::VectorXd& full) const;
  Eigen::VectorXd Full(const Eigen::VectorXd& held, double value) const;

 private:
  System system_;
  Stop stop_;
  LinearFlow free_flow_;
  LinearFlow stuck_flow_;
  PreparedOutput gap_;
  PreparedOutput release_;
  LinearOutput contact_force_;
  Eigen::MatrixXd inverse_mass_;
  Eigen::RowVectorXd inverse_mass_row_;  ///< e_cᵀ M⁻¹
  double time_scale_ = 1.0;
};

}  // namespace impactkit
