#pragma once
/// \file sticking_map.hpp
/// The release map P_R of sticking motions: from one release of the contact
/// mass c from its stop (any of the system's stops, StickingMapOptions::stop)
/// to the next release, from whichever stop (below). Its Poincaré section is
/// the release (x_c = xs, v_c = 0, the contact force Fs falling through 0),
/// with coordinates
///
///     s = (x_j for j != c, v_j for j != c, t)            (size 2N − 1)
///
/// t the absolute release time. One application follows, as the simulator
/// does (hybrid/simulator.hpp):
///
///     free flight from (s, x_c = xs, v_c = 0), impacts at any stop one by
///     one (by each stop's law), until the simulator's chatter rule ends a
///     sequence at this stop at an impact te (the accumulation point t*
///     predicted from it);
///     the other masses follow the stuck subsystem from te (through the
///     chatter tail and the stuck phase alike); sticking needs Fs(t*) > 0;
///     the next release: Fs falling through 0 after t*.
///
/// The chatter tail and the stuck phase run on the same stuck flow, so the
/// next release state depends on (te, y(te+)) only, not on t*: the
/// accumulation time enters the motion's description (the stick phase, the
/// stuck duration) but not the map.
///
/// Analytic Jacobian: with the time carried as a coordinate, every piece is
/// a flight to an event w(t, y) = 0 (w = l·y + α cos Ωt + β): with
/// G = e^{S(t' − t0)} (dy0 − f(t0, y0) dt0) the state at fixed t',
/// dt' = −l G / ẇ(t') and dy(t') = G + f(t', y(t')) dt' (the saltation at
/// the event). Impacts apply the reset's Jacobian; at te the contact
/// coordinates are dropped (chatter collapses them); the last event is the
/// release, w = −Fs on the stuck flow. The image of P_R lies on the release
/// surface Fs = 0, a hypersurface of the section coordinates, so D P_R has
/// one exact zero multiplier besides those of the 2N − 2 dimensional
/// release section (sticking_orbit.hpp).
///
/// With several stops, a cycle may impact any of them and stick at any of
/// them: it ends at the next release from whichever stop its chatter
/// sticks at (StickingCycle::stop), in that stop's coordinates s (its DOF
/// left out), and the next cycle starts there. P_R^k is a map of the
/// section when its k-th release is from the section's stop (else
/// kOtherStop), as the impact map's p-th impact must be at its stop: a
/// motion that sticks at an upper and a lower stop in turn is a fixed point
/// of P_R^2. One stop holds a mass at a time: a mass reaching its stop while
/// another holds one ends the map (kMetWhileHeld).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/core/termination.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/section_map.hpp"

namespace impactkit {

struct StickingMapOptions {
  /// The stop whose releases are the section (an index into System::stops).
  int stop = 0;
  /// The chatter rule (method, span or threshold) and the event tolerance:
  /// the map ends chatter exactly as the simulator with these options does.
  SimulationOptions simulation;
  /// Impacting for this many forcing periods after a release without a
  /// chatter sequence accumulating: the motion does not stick (kNoChatter).
  double max_free_periods = 64.0;
  /// A stuck phase longer than this many forcing periods counts as endless.
  double max_stuck_periods = 64.0;
  /// Impacts between two releases before the map gives up (kNoChatter).
  int max_impacts = 100000;
  bool IsValid(std::string* error) const;
};

/// One impact between two releases.
struct StickingImpact {
  int stop = 0;  ///< the stop hit (an index into System::stops)
  double t = 0.0;
  double velocity = 0.0;  ///< the speed towards the stop just before, > 0
};

/// One application of the map: from a release to the next.
struct StickingCycle {
  double release = 0.0;                 ///< the release it starts from
  int stop = 0;                         ///< the stop it sticks at, and the next release's
  std::vector<StickingImpact> impacts;  ///< simulated impacts at every stop, the last one te
  double accumulation = 0.0;            ///< t*: the chatter's end, sticking begins
  double contact_force = 0.0;           ///< Fs(t*) > 0
  double next_release = 0.0;            ///< the release it ends at
  /// The least distance from its stop of any stop's mass at an interior
  /// turn towards that stop in the cycle's free flights: > 0 while no
  /// flight comes back to a stop before its impact (0 at a grazing, a new
  /// impact); infinity when no flight has such a turn. Measured only when
  /// Apply is asked for contacts.
  double clearance = std::numeric_limits<double>::infinity();
  double clearance_time = 0.0;  ///< when that turn is
  int clearance_stop = 0;       ///< the stop it turns towards
  /// The least interior minimum of Fs during the stuck phase (t*, release):
  /// > 0 while the stop holds the mass throughout (0: Fs touches 0 before
  /// the release, an early release); infinity when Fs has no interior
  /// minimum. Measured only when Apply is asked for contacts.
  double hold_margin = std::numeric_limits<double>::infinity();
  /// The least and greatest position of the section stop's mass over the
  /// cycle (its flights' turns and the stop). Measured only when Apply is
  /// asked for contacts.
  double contact_min = 0.0;
  double contact_max = 0.0;
};

/// The result of P_R^k(s).
struct StickingMapResult {
  /// kCompleted (every release followed: the result is valid),
  /// kNotReleased, kNoImpact (within max_free_periods of a release),
  /// kNoChatter, kNoSticking, kNoRelease (within max_stuck_periods),
  /// kOtherStop or kMetWhileHeld.
  Termination termination = Termination::kCompleted;
  int cycles_done = 0;                ///< releases followed before the status
  Eigen::VectorXd state;              ///< P_R^k(s) (valid when kOk)
  Eigen::MatrixXd jacobian;           ///< D(P_R^k)(s), when asked and kOk
  std::vector<StickingCycle> cycles;  ///< what each application did
};

/// The motion from a state to a fixed time (StickingMap::Follow).
struct StickingFlight {
  /// kCompleted (the motion reached the time: the result is valid), or why
  /// it stopped, as StickingMapResult's.
  Termination termination = Termination::kCompleted;
  HybridState state;  ///< at that time (a held mass at its stop, at rest)
  /// ∂(x, v)(until) / ∂(x, v)(from), 2N × 2N, both at their fixed times,
  /// when asked and kCompleted.
  Eigen::MatrixXd jacobian;
  /// The cycles it went through, from the start (the first one's
  /// `release`) to the last release, and then the part cut off at the
  /// time (its impacts only).
  std::vector<StickingCycle> cycles;
};

class StickingMap : public SectionMap {
 public:
  /// Throws InvalidInput for an invalid system or options (a stop the
  /// system lacks included).
  explicit StickingMap(const System& system, const StickingMapOptions& options = {});
  /// On a hybrid system already decomposed. Throws InvalidInput for invalid options.
  StickingMap(std::shared_ptr<const HybridSystem> hybrid, const StickingMapOptions& options = {});

  /// P_R^k(s) and, if `with_jacobian`, its analytic Jacobian; with
  /// `with_contacts` also each cycle's clearance and hold margin (an
  /// event search per flight and per stuck phase). Throws InvalidInput if s has the wrong size or a
  /// non-finite entry, or k < 1.
  StickingMapResult Apply(const Eigen::VectorXd& s, int k, bool with_jacobian,
                          bool with_contacts = false) const;

  /// The motion from `from` to the time `until` (>= from.t), through the
  /// impacts, chatter, sticking and releases the map follows, and if asked
  /// its Jacobian: the monodromy of a sticking orbit on a stroboscopic
  /// section. `from` is a free state (its first flight searched for
  /// arrivals from its time on), or with `released` a release from that
  /// stop (ToState of a section state: its first flight starts as P_R's).
  /// The contact monitors are not measured. Throws InvalidInput for a
  /// state of the wrong size or with a non-finite entry, or `until` before
  /// its time.
  StickingFlight Follow(const HybridState& from, double until, bool with_jacobian,
                        std::optional<int> released = std::nullopt) const;

  /// SectionMap: P_R^k as Apply, its failures (a state of the wrong size
  /// or with a non-finite entry included) as SectionImage::failure.
  SectionImage Iterate(const Eigen::VectorXd& s, int k, bool with_jacobian) const override;
  /// 1e-6, below the impact map's: a perturbed cycle must end its chatter
  /// at the same impact as the unperturbed one (a step across a threshold
  /// of the chatter rule would difference two branches of the map).
  double FiniteDifferenceStep() const override { return 1e-6; }
  /// 1e-6 / (1 + ‖D P‖)²: ParameterRate differences the whole map at a
  /// fixed state, which varies in μ on a scale that shrinks as D P grows —
  /// near an impact of speed v before the chatter, D P ~ 1/v while that
  /// impact vanishes within a change of μ ~ v², and a central difference
  /// errs by (δ / v²)². On paper-mass1-stop's sticking family at v = 4e-4
  /// the step 1e-6 left the rate 25 % wrong and the continuation's
  /// corrector linear; at v = 4e-5, 1e-6 / (1 + ‖D P‖) still left it at a
  /// rate 0.84. Rounding adds ε |P| / δ; δ stops at 1e-12, where that is
  /// ~1e-3 of |P| while the rate is ~‖D P‖ ≥ 1e3.
  double ParameterStep(const Eigen::MatrixXd& jacobian) const override {
    return std::max(1e-6 / std::pow(1.0 + jacobian.norm(), 2), 1e-12);
  }

  /// The hybrid state (free, x_c = xs, v_c = 0) of a section state.
  HybridState ToState(const Eigen::VectorXd& s) const;
  /// Fs at the section state: 0 on the release surface.
  double ContactForce(const Eigen::VectorXd& s) const;
  /// ∂Fs/∂s, the normal of the release surface (size 2N − 1).
  Eigen::RowVectorXd ContactForceGradient(const Eigen::VectorXd& s) const;

  /// Index of t in s (2N − 2) and the size of s (2N − 1).
  int TimeIndex() const override { return 2 * (GetSystem().Dof() - 1); }
  int Size() const override { return 2 * GetSystem().Dof() - 1; }
  const System& GetSystem() const override { return hybrid_->GetSystem(); }
  /// The section's stop.
  int SectionStop() const override { return options_.stop; }

  /// Throws InvalidInput naming the problem if s is no section state.
  void ValidateSection(const Eigen::VectorXd& s) const;

 private:
  class Cycle;  ///< one application, with its Jacobian (sticking_map.cpp)

  std::shared_ptr<const HybridSystem> hybrid_;
  StickingMapOptions options_;
};

}  // namespace impactkit
