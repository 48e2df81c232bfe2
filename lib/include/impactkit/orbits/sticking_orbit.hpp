#pragma once
/// \file sticking_orbit.hpp
/// Periodic sticking orbits P(∞, q): k sticking phases in q forcing periods,
/// each reached through complete chatter, as fixed points of the release
/// map (sticking_map.hpp):
///
///     U(s) = P_R^k(s) − s − q T e_t = 0,
///
/// solved by Newton–Raphson through KINSOL with the analytic Jacobian.
///
/// Stability. The image of P_R lies on the release surface Fs(s) = 0, so
/// D P_R^k maps every direction into its tangent space: the direction off
/// the surface has multiplier exactly 0. The multipliers of the orbit are
/// those of D P_R^k restricted to the tangent space (2N − 2 of them):
/// Bᵀ D P_R^k B with B an orthonormal basis of ker ∇Fs. Sticking collapses
/// the contact mass's position and velocity (x_c = xs, v_c = 0 whatever
/// came before), which is why the section has 2N − 2 dimensions where a
/// smooth flow's would have 2N − 1 and why the stroboscopic map of the same
/// motion has two zero multipliers besides these.

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

struct StickingOrbitOptions {
  int releases = 1;  ///< sticking phases (releases) per orbit, k >= 1
  int q = 1;         ///< forcing periods per orbit (>= 1)
  /// Tolerances of the Newton solve; residual_tolerance is max |U|.
  NewtonOptions newton;
  StickingMapOptions map;
  bool IsValid(std::string* error) const;
};

struct StickingOrbit {
  int stop = 0;  ///< the stop it sticks at, whose releases are its section (System::stops)
  int releases = 0;
  int q = 0;
  double omega = 0.0;
  Eigen::VectorXd state;                ///< the fixed point, t in [0, T)
  std::vector<StickingCycle> cycles;    ///< the k cycles from `state` on, in time order
  std::vector<double> stick_phases;     ///< t* mod T of each sticking phase
  std::vector<double> release_phases;   ///< release time mod T of each (the one ending it)
  std::vector<double> stuck_durations;  ///< release − t* of each
  Eigen::MatrixXd jacobian;             ///< D P_R^k at state (2N − 1 square)
  Eigen::VectorXcd multipliers;         ///< on the release section, by decreasing modulus
  bool stable = false;                  ///< every |multiplier| < 1
  double residual = 0.0;                ///< max |U(state)|
  /// The monitors of what ends a sticking family: the least Fs(t*) of its
  /// cycles (0: the chatter no longer ends in sticking) and the least
  /// clearance of its free flights (0: a flight reaches the stop, a new
  /// impact), as StickingCycle defines them.
  double contact_margin = 0.0;
  double clearance = 0.0;
  /// The least hold margin of its stuck phases (0: Fs touches 0 before
  /// the release, an early release), as StickingCycle defines it.
  double hold_margin = 0.0;
};

/// The sticking orbit through the fixed point s of P_R^k: cycles, phases,
/// Jacobian, section multipliers, stability, residual. Throws InvalidInput
/// if the map cannot follow k releases from s.
StickingOrbit DescribeStickingOrbit(const StickingMap& map, const Eigen::VectorXd& s, int releases,
                                    int q);

/// The multipliers of D P_R^k at s on the release section (see above).
Eigen::VectorXcd SectionMultipliers(const StickingMap& map, const Eigen::VectorXd& s,
                                    const Eigen::MatrixXd& jacobian);

struct StickingOrbitSummary : Summary {
  double residual = 0.0;  ///< max |U| at the returned point
  std::string BriefReport() const;
};

/// Solves U(s) = 0 from `guess`, a section state, by the fixed-point solve
/// FindOrbit makes on the impact map. Throws InvalidInput for bad options,
/// system or guess (the wrong size, a non-finite entry, or a state the stop
/// still pushes on: no release). A guess from which the map cannot follow
/// k releases (it does not stick again) is kFailure, the message saying
/// after how many releases and why, as FindOrbit's for a lost impact.
StickingOrbitSummary FindStickingOrbit(const System& system, const Eigen::VectorXd& guess,
                                       const StickingOrbitOptions& options, StickingOrbit* orbit);

}  // namespace impactkit
