#pragma once
/// \file mode.hpp
/// One mode of the hybrid motion: the set H of stops holding their masses
/// (none: free flight), the exact flow of the masses F that move, and what
/// each stop watches for on it. A stop whose mass moves watches its gap (an
/// impact); a held stop watches −Fs (a release); a stop whose mass another
/// stop holds (the other side of a clearance) watches nothing.
///
/// The masses that move see the held ones as fixed at their stops:
/// M_FF x_F'' + C_FF x_F' + K_FF x_F = A_F cos Ωt − K_FH xs_H.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// How a stop's mass responds near its stop: at rest there its
/// acceleration towards the stop is `compliance` × Fs (compliance =
/// (M_FF⁻¹)_cc, the masses that move held to the constraint's reaction);
/// its own velocity v_c and displacement x_c − xs change that by
/// −`damping` v_c ((M_FF⁻¹ C_FF)_cc) and −`stiffness` (x_c − xs)
/// ((M_FF⁻¹ K_FF)_cc), and the others' accelerations by at most `coupling`
/// |x_c − xs| (max over j ≠ c of |(M_FF⁻¹ K_FF)_jc|). The chatter map
/// (hybrid/chatter_rule.hpp) needs them.
struct ContactResponse {
  double compliance = 1.0;
  double damping = 0.0;
  double stiffness = 0.0;
  double coupling = 0.0;
};

/// A stop's witness prepared on a mode's flow, with the action its
/// crossing triggers (Stop::Gap's arrival, Stop::Release's release).
struct PreparedWitness {
  PreparedOutput output;
  EventAction action = EventAction::kArrival;
};

class Mode {
 public:
  /// Throws InvalidInput if the masses that move have no bounded steady
  /// response (an undamped mode forced at its frequency).
  Mode(const System& system, const std::vector<Stop>& stops, StopSet held);

  StopSet Held() const { return held_; }
  bool Holds(int stop) const { return (held_ & StopBit(stop)) != 0; }
  const LinearFlow& Flow() const { return flow_; }
  /// The DOFs that move, in order: the flow's coordinates.
  const std::vector<int>& Moving() const { return moving_; }
  /// Stop `stop`'s witness prepared on the flow: its gap (an arrival), or
  /// −Fs when it holds its mass (a release); null when another stop holds
  /// its mass.
  const PreparedWitness* Witness(int stop) const {
    return witnesses_[stop] ? &*witnesses_[stop] : nullptr;
  }

  /// Size N: each held mass's stop position, 0 where a mass moves.
  const Eigen::VectorXd& HeldPositions() const { return held_positions_; }
  /// The moving coordinates of a full vector of positions or velocities.
  Eigen::VectorXd Reduced(const Eigen::VectorXd& full) const;
  /// The full positions and velocities: the held masses at their stops, at
  /// rest.
  void Expand(const Eigen::VectorXd& x_moving, const Eigen::VectorXd& v_moving, Eigen::VectorXd* x,
              Eigen::VectorXd* v) const;

  /// f = (v_F, a_F) of the masses that move, from their state:
  /// M_FF a_F = A_F cos Ωt − C_FF v_F − K_FF x_F − K_FH xs_H.
  Eigen::VectorXd VectorField(double t, const Eigen::VectorXd& x_moving,
                              const Eigen::VectorXd& v_moving) const;
  /// The impulse direction of an impact at a stop whose mass moves
  /// (Stop::ImpulseDirection of this mode's masses).
  const Eigen::VectorXd& ImpulseDirection(int stop) const { return impulse_directions_[stop]; }
  /// The acceleration of stop `stop`'s mass (moving) and, in *rate, its
  /// time derivative, from the full state; `force` (size |F|) and
  /// `acceleration` (size N) are scratch, so that no call allocates.
  double Acceleration(int stop, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                      double* rate, Eigen::VectorXd* force, Eigen::VectorXd* acceleration) const;
  /// The change of stop `stop`'s mass's acceleration when the velocities
  /// change by dv at one instant (an impact's reset): −(M_FF⁻¹ C_F·)_c dv.
  /// Any expression: the difference the simulator passes is not stored.
  template <class Derived>
  double AccelerationChange(int stop, const Eigen::MatrixBase<Derived>& dv) const {
    return -damping_responses_[stop].dot(dv);
  }
  /// Stop `stop`'s mass's response near its stop (the mass moving).
  ContactResponse Contact(int stop) const;
  /// Fs of a held stop at t, from the moving masses' state.
  double ContactForce(int stop, double t, const Eigen::VectorXd& x_moving,
                      const Eigen::VectorXd& v_moving) const;

 private:
  const System* system_;
  StopSet held_;
  std::vector<int> moving_;
  std::vector<int> dof_index_;      ///< per stop: its DOF among moving_, or -1
  Eigen::VectorXd held_positions_;  ///< size N: xs of the held masses, 0 elsewhere
  LinearFlow flow_;
  std::vector<std::optional<PreparedWitness>> witnesses_;
  std::vector<std::optional<LinearOutput>> contact_forces_;  ///< of held stops
  std::vector<Eigen::VectorXd> impulse_directions_;          ///< of stops whose mass moves
  Eigen::MatrixXd inverse_mass_;                             ///< M_FF⁻¹
  /// Per stop whose mass moves, its row of M_FF⁻¹, contiguous (a strided
  /// row's dot product would sum in another order).
  std::vector<Eigen::RowVectorXd> inverse_mass_rows_;
  std::vector<Eigen::RowVectorXd> damping_responses_;  ///< per such stop, (M_FF⁻¹ C_F·)_c
  Eigen::MatrixXd damping_rows_, stiffness_rows_;      ///< C_F·, K_F· (all columns)
  Eigen::VectorXd forcing_;                            ///< A_F
};

}  // namespace impactkit
