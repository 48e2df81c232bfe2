#pragma once
/// \file hybrid_system.hpp
/// A system with its stops, decomposed once per parameter value: the stops
/// (stop.hpp), and the modes of the motion (mode.hpp) — free flight, and
/// each set of stops holding their masses — with their exact flows and the
/// stops' witnesses prepared on them. The simulator and the impact map are
/// built on one; share it (std::shared_ptr) to decompose a parameter
/// value's flows once.
///
/// The free mode is decomposed at construction; a mode with held stops
/// when it is first asked for, thread-safely. Most users of a parameter
/// value never hold a mass (the impact map, continuation's maps at μ ± h),
/// and decomposing the held modes eagerly was 10 % of a connected
/// diagram's CPU time (docs/performance.md).

#include <Eigen/Dense>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/mode.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

class HybridSystem {
 public:
  /// Throws InvalidInput for an invalid system, or one whose free mode has
  /// no bounded steady response (an undamped mode forced at its frequency).
  explicit HybridSystem(const System& system);
  HybridSystem(const HybridSystem&) = delete;
  HybridSystem& operator=(const HybridSystem&) = delete;

  const System& GetSystem() const { return system_; }
  int StopCount() const { return static_cast<int>(stops_.size()); }
  const Stop& GetStop(int stop) const { return stops_[stop]; }

  /// Free flight: every mass moves.
  const Mode& Free() const { return *free_; }
  /// The mode in which the stops in `held` hold their masses. Throws
  /// InvalidInput if its moving masses have no bounded steady response.
  const Mode& Holding(StopSet held) const;
  /// Decomposes every mode in which one stop holds its mass, so that one
  /// without a bounded steady response is rejected now rather than where a
  /// motion first sticks (the simulator's constructor asks for this).
  void PrepareHeldModes() const;

  const LinearFlow& FreeFlow() const { return free_->Flow(); }
  /// Stop `stop`'s gap on the free flow.
  const PreparedOutput& Gap(int stop) const { return free_->Witness(stop)->output; }
  /// The flow while stop `stop` alone holds its mass, and −Fs on it.
  const LinearFlow& StuckFlow(int stop) const { return Holding(StopBit(stop)).Flow(); }
  const PreparedOutput& Release(int stop) const {
    return Holding(StopBit(stop)).Witness(stop)->output;
  }
  /// The shortest time scale of the free motion (event search, chatter).
  double TimeScale() const { return time_scale_; }

  /// M⁻¹ (A cos Ωt − C v − K x): the free mode's accelerations.
  Eigen::VectorXd Acceleration(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// f(t, y) = (v, a) of the free mode, y = (x, v).
  Eigen::VectorXd VectorField(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// The acceleration of stop `stop`'s mass in free flight and, in *rate,
  /// its time derivative, using `force` and `acceleration` (size N) as
  /// scratch: no allocation per call.
  double ContactAcceleration(int stop, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                             double* rate, Eigen::VectorXd* force,
                             Eigen::VectorXd* acceleration) const {
    return free_->Acceleration(stop, t, x, v, rate, force, acceleration);
  }
  /// Fs of stop `stop` holding its mass alone, from the moving masses' state.
  double ContactForce(int stop, double t, const Eigen::VectorXd& x_held,
                      const Eigen::VectorXd& v_held) const {
    return Holding(StopBit(stop)).ContactForce(stop, t, x_held, v_held);
  }

  /// The coordinates that move while stop `stop` holds its mass alone (its
  /// DOF removed), and back (`value` at its DOF).
  Eigen::VectorXd Held(int stop, const Eigen::VectorXd& full) const;
  Eigen::VectorXd Full(int stop, const Eigen::VectorXd& held, double value) const;

 private:
  System system_;
  std::vector<Stop> stops_;
  std::unique_ptr<const Mode> free_;
  /// A mode built on first use: std::call_once keeps the simulator's
  /// lookups at every sticking segment free of a lock.
  struct LazyMode {
    std::once_flag once;
    std::unique_ptr<const Mode> mode;
  };
  std::unique_ptr<LazyMode[]> held_;  ///< per stop: that stop alone holding
  /// Modes of several held stops.
  mutable std::map<StopSet, std::unique_ptr<const Mode>> combined_;
  mutable std::mutex combined_mutex_;
  Eigen::MatrixXd inverse_mass_;
  double time_scale_ = 1.0;
};

}  // namespace impactkit
