#pragma once
/// \file continuation.hpp
/// Pseudo-arclength continuation of periodic orbits P(p, q) in one named
/// parameter μ (any of ParameterNames: omega, xs, r, A1…, m, k, c).
///
/// The unknowns are X = (η, μ), size 2N + 1, on the curve
///
///     U(η, μ) = P_I^p(η; μ) - η - q T(μ) e_τ = 0.
///
/// From a point X_k with unit tangent t_k (the null vector of
/// [U_η U_μ], oriented to continue the previous one), the predictor is
/// X_k + s t_k and the corrector solves, by KINSOL Newton, the bordered
/// system
///
///     U(X) = 0,   t_k · (X - X_k) = s,
///
/// whose Jacobian [U_η U_μ; t_kᵀ] stays regular through folds, so the
/// branch turns round them. U_η is the impact map's analytic Jacobian;
/// U_μ is a central difference in μ (the map has no closed-form parameter
/// derivative here; Newton needs only an approximate one).
///
/// Along the branch, the test functions of test_functions.hpp (fold,
/// period doubling, Neimark–Sacker) are evaluated at every point and each
/// sign change is located by the Illinois method on s (each trial point
/// corrected onto the branch); Neimark–Sacker zeros at a real pair of
/// multipliers (neutral saddles) are discarded.
/// Grazing and sticking onset (orbit_contacts.hpp) end the branch: past them
/// the orbit would pass through the stop, so they are approached from the
/// branch side — the monitor is extrapolated linearly in s and its zero
/// located by safeguarded secant steps — and the branch stops there.
///
/// A family of sticking orbits (a start on the release section,
/// sticking_orbit.hpp) is the same curve on the release map, followed by
/// the same march with the same test functions (on D P_R^k: its exact
/// zero multiplier changes only their sign). Its ends differ: past them
/// the release map still converges, onto another motion, so points beyond
/// are recognised and refused and the end is located by bisection in μ to
/// end_tolerance (the chatter stops ending in sticking, a new or vanishing
/// impact, an early release: continuation/sticking_end.hpp).

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/continuation/branch_point.hpp"
#include "impactkit/continuation/test_functions.hpp"
#include "impactkit/core/run_control.hpp"
#include "impactkit/core/termination.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/grazing_normal_form.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_map.hpp"

namespace impactkit {

enum class ContinuationDirection { kIncreasing, kDecreasing, kBoth };

/// A test function of the user's: a scalar of the orbit (the greatest x_c
/// minus a level, an impact's phase minus a value, ...) whose sign changes
/// along a branch are located like a bifurcation's, by the same Illinois
/// method on arclength, and reported as special points of type kUserTest
/// named `name`. It must be continuous along a branch (a quantity of the
/// orbit, not of its numbering) and is called from the tracing threads.
struct UserTest {
  std::string name;
  std::function<double(const PeriodicOrbit& orbit)> value;
};

struct ContinuationOptions {
  std::string parameter = "omega";
  /// The ends of the parameter's range, in either order, as every range of
  /// the library (SweepOptions, CurveOptions): the branch stays within it
  /// and ends on reaching an end.
  double from = 0.0;
  double to = 0.0;
  double Lower() const { return std::min(from, to); }
  double Upper() const { return std::max(from, to); }
  /// Initial sense of μ from the start; kBoth follows the branch both ways.
  ContinuationDirection direction = ContinuationDirection::kIncreasing;
  /// Arclength steps in (η, μ) space: start, floor and ceiling.
  double initial_step = 0.01;
  double min_step = 1e-7;
  double max_step = 0.02;
  int max_points = 10000;  ///< per direction
  /// Newton iterations allowed to the corrector before the step is halved.
  int corrector_iterations = 8;
  /// A corrected point may lie at most this fraction of the step from its
  /// prediction; farther means the corrector jumped (to another branch).
  double max_correction = 0.5;
  /// Locate fold, period doubling and Neimark–Sacker points (grazing and
  /// sticking are always watched: they end the branch).
  bool locate_bifurcations = true;
  /// p, q, tolerances and the maps' options. The analytic Jacobian is used
  /// whatever orbit.jacobian says (the finite-difference one costs 4N maps).
  /// A family's section and stop are its start orbit's, and so are a
  /// sticking family's releases and q.
  OrbitOptions orbit;
  /// A sticking family's end is located by bisection in μ to this.
  double end_tolerance = 1e-9;
  /// The user's test functions, watched and located along every branch
  /// (and so along every branch of a diagram), whatever
  /// locate_bifurcations says.
  std::vector<UserTest> user_tests;
  bool IsValid(std::string* error) const;
};

struct SpecialPoint {
  SpecialPointType type = SpecialPointType::kFold;
  BranchPoint point;  ///< the located point
  /// The parameter value of the special point. It is point.parameter except
  /// where an impact vanishes: there the branch's last point stops short
  /// (its multipliers grow like 1/v) and the value comes from the reduced
  /// orbit's defining equation, its flight maximum at the stop.
  double parameter = 0.0;
  /// The critical multiplier (fold, period doubling, Neimark–Sacker), and
  /// for a period doubling the real eigenvector of D P for it (for a
  /// pitchfork, for +1).
  std::complex<double> multiplier{0.0, 0.0};
  Eigen::VectorXd eigenvector;
  /// The monitor at the located point: the test function, or for grazing
  /// and sticking the clearance or depth of orbit_contacts.hpp.
  double monitor = 0.0;
  /// Grazing/sticking: which impact vanishes (-1 for a new contact).
  int vanishing_impact = -1;
  /// A user test's zero: the test's name (UserTest::name).
  std::string user_test;
  /// A grazing: the local map there (grazing_normal_form.hpp), unfolded in
  /// the branch's parameter. Empty for other types, or where the grazing
  /// orbit could not be resolved (normal_form_note says why).
  std::optional<GrazingNormalForm> normal_form;
  std::string normal_form_note;
  /// One line: "period doubling at omega = 1.6123 (multiplier -1.000000)".
  std::string Describe(const std::string& parameter_name) const;
};

/// A step of a branch over which a fold or period-doubling test function
/// changes sign and neither a located zero nor a multiplier passing through
/// infinity accounts for it (docs/theory.md §6): a fold or period doubling
/// may lie in the step and is missing from the branch's special points.
struct UnlocatedZero {
  /// The test function that changed sign: kFold (det(D P − I)) or
  /// kPeriodDoubling (det(D P + I)). In a step where a multiplier also
  /// passes through infinity, the missing point may be of the other kind.
  SpecialPointType type = SpecialPointType::kPeriodDoubling;
  double from = 0.0;  ///< the parameter at the step's ends, in order along the branch
  double to = 0.0;
  /// One line: "period doubling not located between omega = 1.706015032
  /// and 1.706015014".
  std::string Describe(const std::string& parameter_name) const;
};

struct Branch {
  std::string parameter;
  /// The section of its orbits: impacting P(p, q), or sticking with
  /// `releases` sticking phases in q periods (then p is 0: the impacts of
  /// its orbits vary along it, PeriodicOrbit::p).
  OrbitSection section = OrbitSection::kImpact;
  int p = 0;
  int q = 0;
  int releases = 0;
  /// The stop of the section, whose impacts (or releases) the points' η
  /// describe: the start orbit's.
  int stop = 0;
  /// In order along the branch; with kBoth, from the decreasing end to the
  /// increasing end.
  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> special_points;  ///< in order along the branch
  /// Sign changes of the fold and period-doubling tests the locator could
  /// not account for, in order along the branch; empty on most branches.
  std::vector<UnlocatedZero> unlocated;
  Termination end =
      Termination::kMaxPoints;  ///< why the last point is the last (see ContinueBranch)
  std::string end_message;
  /// With kBoth: why the first point is the first.
  std::optional<Termination> begin;
  std::string begin_message;
  double seconds = 0.0;
};

/// "P(p,q)", or for a sticking family "P(inf,q)" (with k > 1 sticking
/// phases, "P(inf,q) k=2").
std::string FamilyName(const Branch& branch);

/// Where a branch starts: a converged orbit of `system` (whose parameter
/// value is the start), impacting or sticking, and optionally the initial
/// direction in (η, μ) (the section's size + 1; otherwise from
/// options.direction).
struct BranchStart {
  System system;
  PeriodicOrbit orbit;
  Eigen::VectorXd direction;
};

/// Follows the branch through `start`. Throws InvalidInput for bad
/// options, a parameter name the system lacks, bounds not valid for the
/// system or not holding the start, or a start that is not an orbit (its
/// residual above 1e3 times the tolerance). A start that is a shorter orbit
/// traversed several times (PrimitivePeriod) is followed as that orbit:
/// Branch::p and q say which. Ends (Branch::end, and begin with kBoth)
/// are kParameterBound, kGrazing, kSticking, kBranchPoint, kMaxPoints,
/// kCorrectorFailed, kStopped (`control` cancelled), and for a sticking
/// family kNoSticking or kEarlyRelease. Progress: stage "branch", points
/// accepted.
Branch ContinueBranch(const BranchStart& start, const ContinuationOptions& options,
                      const RunControl& control = {});

/// A first point on the P(2p, 2q) branch born at the period doubling `pd`
/// of `branch`, displaced from it by `offset` (arclength) along the flip
/// eigenvector, with the direction leading away from the period doubling;
/// by −`offset` (the mirror half: the same orbits) where the corrector does
/// not converge on that side, or converges to the single orbit. Where
/// neither side gives a doubled orbit that leaves the single one (its
/// repeat gap growing along the direction), the offset is cut tenfold, and
/// again: deep in a cascade the doubled branch's stretch to its own period
/// doubling is shorter than `offset`. Failing that, the first doubled orbit
/// found; empty if none is found.
std::optional<BranchStart> DoubledBranchStart(const System& system, const Branch& branch,
                                              const SpecialPoint& pd,
                                              const ContinuationOptions& options,
                                              double offset = 1e-3);

/// A first point on the branch that crosses `branch` at its pitchfork
/// `pitchfork` (the same P(p, q): in a symmetric system an asymmetric
/// orbit), displaced by `offset` along the eigenvector of the multiplier
/// +1; the other sign of `offset` gives the other half (the mirror image).
/// Empty if the corrector does not converge off `branch`.
std::optional<BranchStart> PitchforkBranchStart(const System& system, const Branch& branch,
                                                const SpecialPoint& pitchfork,
                                                const ContinuationOptions& options,
                                                double offset = 1e-3);

/// Seeds at the grazing (or sticking) point `graze` of `branch` for the
/// orbit with one impact more (a new contact) or one fewer (a vanishing
/// impact), at the parameter `offset` to either side of it: which side
/// such an orbit lives on depends on the grazing. Not yet orbits: refine
/// each with FindOrbit (p and q in `orbit`). None when p would drop to 0.
/// A sticking family's grazing (an impact appearing or vanishing before a
/// chatter) leaves the release map continuous: its seeds are the grazing
/// orbit's own release state, the same k releases in q periods, and the
/// orbit refined beyond the grazing has the impact more or fewer.
struct GrazingSeed {
  System system;       ///< at the seed's parameter value
  OrbitOptions orbit;  ///< p ± 1 (or the k releases of a sticking family), q
  Eigen::VectorXd eta;
};
/// The grazing orbit at the grazing point `graze` of `branch`, touching
/// its stop: at a new contact the located orbit itself; where an impact
/// vanishes the orbit without it — P(p − 1, q), found at the located
/// parameter, or for p = 1 the non-impacting response. On a sticking
/// family (with its family's release state and smooth side,
/// StickingGrazing): at a new contact the located orbit; where an
/// approach impact vanishes, the neighbouring family's (without it) at the
/// zero of its clearance. Throws InvalidInput for another type of point,
/// or a reduced or neighbouring orbit that cannot be found or does not
/// touch.
GrazingOrbit GrazingOrbitAt(const System& system, const Branch& branch, const SpecialPoint& graze,
                            const ContinuationOptions& options);

std::vector<GrazingSeed> SeedsAtGrazing(const System& system, const Branch& branch,
                                        const SpecialPoint& graze,
                                        const ContinuationOptions& options, double offset = 1e-3);

}  // namespace impactkit
