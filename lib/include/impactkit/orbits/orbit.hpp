#pragma once
/// \file orbit.hpp
/// Periodic impacting orbits P(p, q) — p impacts in q forcing periods — as
/// fixed points of the impact map (impact_map.hpp):
///
///     U(η) = P_I^p(η) - η - q T e_τ = 0,
///
/// solved by Newton–Raphson through KINSOL with the analytic (or the paper's
/// finite-difference) Jacobian, falling back on Levenberg–Marquardt through
/// Ceres from poor seeds. Near grazing (an impact's speed v → 0, D P_I ~
/// 1/v) neither can converge: U has a square root's domain and cannot be
/// evaluated below its rounding ε ‖D P_I‖. There the orbit is solved as p
/// flights between impacts at fixed times (multiple shooting, regular at
/// grazing, docs/theory.md §5b) and accepted when U at it is within that
/// rounding floor; the summary says so. Stability: the eigenvalues of
/// D P_I^p at the fixed point (the multipliers); the orbit is stable when
/// all lie inside the unit circle. Unstable orbits are found as readily as
/// stable ones.

#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit_contacts.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

enum class JacobianMethod {
  kAnalytic,          ///< saltation matrices and flow sensitivities (default)
  kFiniteDifference,  ///< central differences of the map (the paper's method)
};

std::string ToString(JacobianMethod method);

/// The Poincaré section an orbit's fixed point lies on (section_map.hpp).
enum class OrbitSection {
  kImpact,   ///< an impact: the impact map P_I (impact_map.hpp), η
  kRelease,  ///< a release from sticking: the release map P_R (sticking_map.hpp), s
};

/// What FindOrbit looks for and how: an impacting orbit P(p, q) on the
/// impact section, or (releases >= 1) a sticking orbit P(∞, q) on the
/// release section.
struct OrbitOptions {
  int p = 1;  ///< impacts per orbit (>= 1); on the release section what the orbit finds
  int q = 1;  ///< forcing periods per orbit (>= 1)
  /// Sticking phases per orbit: 0 for an impacting orbit, a fixed point of
  /// P_I^p; k >= 1 for a sticking orbit, a fixed point of P_R^k
  /// (sticking_orbit.hpp), whose impacts are counted, not asked for.
  int releases = 0;
  JacobianMethod jacobian = JacobianMethod::kAnalytic;
  /// Tolerances of the Newton solve; residual_tolerance is max |U| at the
  /// solution (default 1e-11).
  NewtonOptions newton;
  /// Try Levenberg–Marquardt (Ceres) when Newton does not converge.
  bool least_squares_fallback = true;
  /// Then (impact section) try the fixed-time formulation (regular where an
  /// impact's speed vanishes), with the impacts' stops of the guess (for
  /// p > 1 the map must follow p impacts from the guess).
  bool shooting_fallback = true;
  ImpactMapOptions map;            ///< the impact map's, on the impact section
  StickingMapOptions release_map;  ///< the release map's, on the release section
  OrbitSection Section() const {
    return releases > 0 ? OrbitSection::kRelease : OrbitSection::kImpact;
  }
  /// The section's stop: map.stop or release_map.stop.
  int SectionStop() const { return releases > 0 ? release_map.stop : map.stop; }
  bool IsValid(std::string* error) const;
};

/// "impact", "release".
std::string ToString(OrbitSection section);

/// `values` sorted by decreasing modulus: multipliers as orbits list them.
Eigen::VectorXcd SortedByModulus(Eigen::VectorXcd values);

/// One impact of the orbit.
struct OrbitImpact {
  double t = 0.0;
  double phase = 0.0;     ///< t mod T, in [0, T)
  double velocity = 0.0;  ///< impact speed s v_c(t-) towards the stop
  int stop = 0;           ///< which stop (an index into System::stops)
};

/// One sticking phase of an orbit: the contact mass held at `stop` from the
/// accumulation point of the chatter that leads to it to its release.
struct StuckPhase {
  int stop = 0;                ///< which stop holds the mass (an index into System::stops)
  double stick = 0.0;          ///< t*, the chatter's accumulation point: sticking begins
  double stick_phase = 0.0;    ///< t* mod T, in [0, T)
  double release = 0.0;        ///< the release that ends it
  double release_phase = 0.0;  ///< release mod T, in [0, T)
  double contact_force = 0.0;  ///< Fs(t*) > 0: the stop's hold on the mass as it sticks
  /// The least interior minimum of Fs on (t*, release): 0 where Fs touches
  /// 0 before the release (an early release); infinity when it has none.
  double hold_margin = 0.0;
  /// Impacts simulated since the previous release, the chatter's included
  /// (its tail beyond them, summed by the chatter rule, is not counted).
  int impacts = 0;
  double Duration() const { return release - stick; }
};

/// A periodic orbit: a fixed point of a section map, iterated k times in q
/// forcing periods. On the impact section it is P(p, q), p = k impacts; on
/// the release section a sticking orbit P(∞, q) with k = `releases`
/// sticking phases, each reached through chatter (sticking_orbit.hpp).
struct PeriodicOrbit {
  OrbitSection section = OrbitSection::kImpact;
  /// Impacts per orbit: the impact map's iterations; on the release section
  /// the impacts simulated before its accumulations (impacts.size()).
  int p = 0;
  int q = 0;
  /// Sticking phases per orbit: the release map's iterations (0 on the
  /// impact section).
  int releases = 0;
  double omega = 0.0;
  /// The fixed point in the section's coordinates, its time in [0, T): η
  /// (impact_map.hpp) or s (sticking_map.hpp).
  Eigen::VectorXd eta;
  int stop = 0;  ///< the stop of the section (each event of the section map is at it)
  /// The impacts from eta on, in time order: the p impacts of P(p, q); of
  /// a sticking orbit, every simulated impact of its flights and chatter.
  std::vector<OrbitImpact> impacts;
  std::vector<StuckPhase> stuck;  ///< the sticking phases in time order (release section)
  Eigen::MatrixXd jacobian;       ///< D P^k at eta: the section map's k iterations
  /// By decreasing modulus: the eigenvalues of `jacobian` on the impact
  /// section; on the release section those restricted to the release
  /// surface (2N − 2 of them: `jacobian` has one more, exactly 0).
  Eigen::VectorXcd multipliers;
  bool stable = false;     ///< every |multiplier| < 1
  double residual = 0.0;   ///< max |U(eta)|
  OrbitContacts contacts;  ///< extent in x_c and the monitors of the orbit's end
  bool Sticks() const { return section == OrbitSection::kRelease; }
  /// The section map's iterations per orbit: p, or `releases`.
  int SectionEvents() const { return Sticks() ? releases : p; }
};

/// "P(p,q)", or "P(inf,q)" for a sticking orbit.
std::string OrbitName(const PeriodicOrbit& orbit);

/// The impacts of a sticking orbit's k-th cycle, from the release before
/// its k-th stuck phase to that phase's accumulation point, in time order.
std::span<const OrbitImpact> CycleImpacts(const PeriodicOrbit& orbit, std::size_t k);

/// The impacts that stand for the orbit in a table or a figure: its p
/// impacts, or of a sticking orbit the first after each release (its
/// chatter's impacts are too many and too slow to show), in time order.
std::vector<OrbitImpact> LeadingImpacts(const PeriodicOrbit& orbit);

/// The orbit P(p, q) through the fixed point `eta` of P_I^p: impacts,
/// Jacobian (by `method`), multipliers, stability, residual and contacts.
/// Throws InvalidInput if the map cannot follow p impacts from eta, or
/// (finite differences) a perturbed map cannot.
PeriodicOrbit DescribeOrbit(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            JacobianMethod method = JacobianMethod::kAnalytic);

/// The analytic Jacobian of P_I^p at η beside the finite-difference one (the
/// paper's method): how far apart they are, entry by entry.
struct JacobianComparison {
  double max_difference = 0.0;  ///< max |J_analytic − J_fd|
  /// The same relative to max |J_analytic| (at least 1).
  double max_relative_difference = 0.0;
};
/// Throws InvalidInput if the map or a perturbed map cannot follow p impacts.
JacobianComparison CompareJacobians(const ImpactMap& map, const Eigen::VectorXd& eta, int p);

/// The least period of the orbit P(p, q) through η: (p/d, q/d) for the
/// largest d dividing both with P_I^{p/d}(η) = η + (q/d) T e_τ to
/// `tolerance` (relative to 1 + max|η|). A P(2,2) that is P(1,1)
/// traversed twice has the primitive period (1, 1). Throws InvalidInput if
/// the map cannot follow p impacts from η.
struct OrbitPeriod {
  int p = 1;
  int q = 1;
};
OrbitPeriod PrimitivePeriod(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            double tolerance = 1e-8);

/// What max |U| cannot fall below at an impact state η exact to rounding,
/// D P_I^p = `jacobian` (~1/v near grazing): the map carries each entry of
/// η, rounded, through D P_I^p, plus its event times' own rounding:
/// 8 ε ‖jacobian‖∞ max(1, ‖η‖∞) (docs/theory.md §5b).
double ResidualFloor(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& eta);

/// Summary::iterations counts Newton iterations plus LM and fixed-time
/// Newton iterations if used.
struct OrbitSummary : Summary {
  bool used_fallback = false;  ///< Levenberg–Marquardt was needed
  double residual = 0.0;       ///< max |U| at the returned point
  /// The fixed-time formulation found the orbit; then `residual` is
  /// accepted up to `residual_floor` instead of newton.residual_tolerance.
  bool used_shooting = false;
  double shooting_residual = 0.0;  ///< max |W| of the fixed-time equations, when used
  /// max(residual_tolerance, 8 ε ‖D P_I^p‖∞ max(1, ‖η‖∞)): U's rounding
  /// when η is exact to rounding (docs/theory.md §5b), when used.
  double residual_floor = 0.0;
  /// Impacts of the orbit (found by the fixed-time formulation) whose
  /// height u²/(2|a|) is below the arrival rule's resolution: a simulation
  /// or the map sees a grazing touch (or a landing) there, not an impact,
  /// and cannot follow the orbit, so `residual` is max |W| instead
  /// (docs/theory.md §5b).
  int unresolved_impacts = 0;
  std::string BriefReport() const;
};

/// Solves U = 0 on the options' section from `guess`: an impact state η
/// (v_c > 0), or with options.releases >= 1 a release state s
/// (sticking_map.hpp). Throws InvalidInput for bad options, system or
/// guess (of a release state: the wrong size, a non-finite entry, or a
/// state the stop still pushes on). A solution where the map fails (an
/// impact slower than options.map.min_speed: a grazing orbit) is no orbit,
/// and so is a guess from which the release map cannot follow k releases:
/// kFailure, with the reason (after how many impacts or releases, and why)
/// in the summary's message.
OrbitSummary FindOrbit(const System& system, const Eigen::VectorXd& guess,
                       const OrbitOptions& options, PeriodicOrbit* orbit);

}  // namespace impactkit
