#pragma once
/// \file curve.hpp
/// Two-parameter continuation of codimension-one points of a P(p, q) family:
/// fold, period-doubling, Neimark–Sacker and grazing curves in any two named
/// parameters (μ1, μ2), and the codimension-two points along them.
///
/// The unknowns are X = (η, [t*], μ1, μ2) on the curve F(X) = 0,
///
///     U(η; μ1, μ2) = P_I^p(η) − η − q T e_τ = 0          (2N equations)
///     fold             σ(D P − I) = 0      (σ relative to D P's size,
///     period doubling  σ(D P + I) = 0       docs/continuation.md)
///     Neimark–Sacker   Π_{i<j} (λ_i λ_j − 1) = det(D P ⊙ D P − I) = 0
///     grazing          s (x_c(t*) − xs) = −δ,  v_c(t*) = 0   (t* in one
///                      flight; δ = 1e-10 keeps the touch on the orbit's side)
///
/// (P(1,q)'s vanishing impact: X = (μ1, μ2) and s xs − |X_c| = 0 for the
/// non-impacting response X_c, see CurveStart.) With several stops η is at
/// the start orbit's section stop (PeriodicOrbit::stop) and the grazing
/// rows hold the stop touched (OrbitContacts::clearance_stop; for the
/// response, the stop it comes closest to): c its mass, xs its position, s
/// its side (+1 above, −1 below).
///
/// where σ(A) is the minimally augmented function of A (Govaerts): the last
/// component of the solution of [A b; cᵀ 0] (v, σ) = (0, 1) with borders b,
/// c the left and right singular vectors of A's least singular value at the
/// last accepted point (docs/continuation.md says why this and not det).
/// U's rows and columns are the one-parameter code's (analytic D P, U_μ by
/// the saltation relation, continuation.hpp); the defining rows' gradient is
/// a central difference (CompareCurveJacobian checks it).
///
/// The curve is followed by pseudo-arclength continuation exactly as a
/// branch is (tangent predictor, bordered corrector, adaptive step) within
/// bounds on both parameters. Along it, second test functions locate the
/// codimension-two points by the Illinois method on arclength; the grazing
/// and sticking monitors of orbit_contacts.hpp end it where the orbit stops
/// existing (a bifurcation curve meeting a grazing curve).

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/core/run_control.hpp"
#include "impactkit/core/termination.hpp"

namespace impactkit {

/// The codimension-two points met along a curve.
enum class Codim2Type {
  kFoldFlip,     ///< multipliers +1 and −1 at once (fold and PD curves meet)
  kCusp,         ///< a fold curve turns back in the parameter plane
  kResonance11,  ///< a double multiplier +1 (NS curve meets a fold curve)
  kResonance12,  ///< a double multiplier −1 (NS curve meets a PD curve)
  kResonance13,  ///< the NS pair at e^{±2πi/3}
  kResonance14,  ///< the NS pair at ±i
  kFoldGrazing,  ///< a fold meets a grazing (either curve's end or crossing)
  kPeriodDoublingGrazing,
  kNeimarkSackerGrazing,
  kDoubleGrazing,  ///< a grazing curve meets another grazing: a second contact
  /// A resonant grazing: on a grazing curve, where the square-root term
  /// drops out of the fixed-point equation of the orbit with the new
  /// impact, so that a fold curve of that orbit (P(p + 1, q)) leaves the
  /// grazing curve (the grazing orbit's GrazingLimit(+1) is zero,
  /// grazing_limit.hpp). For one mass at Ω = 2 ω_d q / j (Molenaar, de
  /// Weger & van de Water 2001; Simpson & Ghosh 2026).
  kResonantGrazingFold,
  /// The same with GrazingLimit(−1): a period-doubling curve of the orbit
  /// with the new impact leaves. For one mass the same point as the fold's;
  /// with several masses in general another.
  kResonantGrazingPeriodDoubling,
  kStickingOnset,  ///< an impact of the curve's orbit starts to chatter
  kUserTest,       ///< a user test's zero (CurveOptions::user_tests)
};

/// "fold_flip", "cusp", "resonance_1_1", …, "fold_grazing",
/// "period_doubling_grazing", "neimark_sacker_grazing", "double_grazing",
/// "resonant_grazing_fold", "resonant_grazing_period_doubling",
/// "sticking_onset", "user_test": the name outputs use.
std::string ToString(Codim2Type type);

struct CurveOptions {
  /// μ1 (the parameter of the branch the start point came from) and μ2.
  std::string parameter = "omega";
  std::string parameter2 = "r";
  /// The ends of the ranges of μ1 and μ2, each in either order: the curve
  /// stays within them and ends on reaching one.
  double from = 0.0, to = 0.0;
  double from2 = 0.0, to2 = 0.0;
  double Lower() const { return std::min(from, to); }
  double Upper() const { return std::max(from, to); }
  double Lower2() const { return std::min(from2, to2); }
  double Upper2() const { return std::max(from2, to2); }
  /// Arclength steps in X = (η, [t*], μ1, μ2): start, floor and ceiling.
  double initial_step = 0.01;
  double min_step = 1e-7;
  double max_step = 0.02;
  int max_points = 2000;  ///< per direction
  /// Newton iterations allowed to the corrector before the step is halved.
  int corrector_iterations = 8;
  /// A corrected point may lie at most this fraction of the step from its
  /// prediction; farther means the corrector jumped to another curve.
  double max_correction = 0.5;
  /// Locate codimension-two points (the curve's end is always located).
  bool locate_codim2 = true;
  /// p, q, tolerances and the map's options.
  OrbitOptions orbit;
  /// The user's test functions (continuation.hpp), located along the
  /// curve as codimension-two points of type kUserTest where the curve's
  /// orbit has them (not on the non-impacting response's grazing curve).
  std::vector<UserTest> user_tests;
  bool IsValid(std::string* error) const;
};

/// One corrected point of a curve.
struct CurvePoint {
  double parameter = 0.0;   ///< μ1
  double parameter2 = 0.0;  ///< μ2
  double arclength = 0.0;   ///< from the start, signed by direction
  PeriodicOrbit orbit;      ///< at (μ1, μ2)
  /// The defining functions here (one value; grazing: s (x_c(t*) − xs) + δ and
  /// v_c(t*)): zero to the corrector's tolerance.
  Eigen::VectorXd defining;
  double contact_time = 0.0;  ///< grazing: t*, the time of the touch
  /// Grazing: the grazing orbit's GrazingLimit(+1) and GrazingLimit(−1)
  /// (grazing_limit.hpp), zero at a resonant grazing; NaN on other curves.
  std::array<double, 2> grazing_limits{std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::quiet_NaN()};
  std::array<double, kBifurcationTestCount> test_values{};
  Eigen::VectorXd x;        ///< the unknowns X
  Eigen::VectorXd tangent;  ///< unit tangent in X
};

struct Codim2Point {
  Codim2Type type = Codim2Type::kFoldFlip;
  CurvePoint point;
  /// |defining function of the curve| and |second test function| there
  /// (a grazing monitor is a length: clearance or depth).
  double defining_residual = 0.0;
  double second_residual = 0.0;
  std::string user_test;  ///< a user test's zero: the test's name
  /// A point located on a grazing curve (its second tests): the grazing
  /// orbit's local map there (grazing_normal_form.hpp), unfolded in μ1 at
  /// the point's μ2. Empty elsewhere, or where it cannot be computed (at a
  /// fold the family does not exist on both sides of μ1 to unfold it);
  /// normal_form_note says why, and for a bifurcation curve's grazing end
  /// where to find it.
  std::optional<GrazingNormalForm> normal_form;
  std::string normal_form_note;
  /// One line: "fold_flip at omega = 1.61, r = 0.83 (residuals 1e-12, 3e-10)".
  std::string Describe(const std::string& name1, const std::string& name2) const;
};

struct Curve {
  SpecialPointType type = SpecialPointType::kFold;
  std::string parameter, parameter2;
  int p = 0, q = 0;
  /// In order along the curve: from the end reached with μ2 decreasing to
  /// the end reached with μ2 increasing. A closed curve is traced once,
  /// from its start round to the start again (its last point).
  std::vector<CurvePoint> points;
  std::vector<Codim2Point> codim2_points;  ///< in order along the curve
  Termination begin = Termination::kMaxPoints, end = Termination::kMaxPoints;
  std::string begin_message, end_message;
  double seconds = 0.0;
};

/// Where a curve starts: a fold, period doubling, Neimark–Sacker point or a
/// grazing, located on a branch in options.parameter of the system `system`
/// (whose options.parameter2 is the curve's start value of μ2). Its orbit's
/// p and q are the curve's. A grazing is a new contact (vanishing_impact <
/// 0), or P(1,q)'s impact vanishing: the curve is then where the
/// non-impacting response X cos(Ωt − φ), X = (K − Ω²M + iΩC)⁻¹ A, touches
/// the stop it comes closest to, |X_c(μ1, μ2)| = s xs (the curve's p is 0,
/// its points have no orbit). Any stop of the system: the orbit's η is at
/// its own section stop.
struct CurveStart {
  System system;
  SpecialPoint special;
};

/// Whether special points of this type lie on two-parameter curves that
/// ContinueCurve follows: fold, period doubling, Neimark–Sacker, grazing.
bool HasCurve(SpecialPointType type);

/// Follows the curve through `start` both ways. Throws InvalidInput for bad
/// options (the same parameter twice, n, bounds not holding the start), a
/// special point of another kind (branch points, sticking), a vanishing
/// impact of P(p, q) with p >= 2, or a start the corrector cannot put on
/// the curve. Such a vanishing impact is the grazing of P(p − 1, q) by a
/// new contact: pass that orbit's grazing point instead
/// (ReducedGrazingStart). Ends (Curve::begin and end) are
/// kParameterBound, kGrazing, kSticking, kMaxPoints, kCorrectorFailed,
/// kClosed, or kStopped (`control` cancelled). Progress: stage "curve",
/// points accepted.
Curve ContinueCurve(const CurveStart& start, const CurveOptions& options,
                    const RunControl& control = {});

/// The special point of `type` on the branch of `start.orbit` in
/// options.parameter nearest the start's value (the branch is followed both
/// ways within options' bounds); empty when the branch has none.
std::optional<SpecialPoint> LocateSpecialPoint(const BranchStart& start,
                                               const ContinuationOptions& options,
                                               SpecialPointType type);

/// At a vanishing impact `graze` of a P(p, q) branch (p >= 2), the grazing
/// of the reduced orbit P(p − 1, q) by a new contact, as a curve start;
/// empty when the reduced orbit is not found there.
std::optional<CurveStart> ReducedGrazingStart(const System& system, const Branch& branch,
                                              const SpecialPoint& graze,
                                              const ContinuationOptions& options);

/// The gradient of the defining rows used by the corrector (central
/// differences) beside a Richardson-extrapolated one from steps 100 and 50
/// times larger, at a point of a curve: the largest difference relative to
/// the gradient's largest entry.
double CompareCurveJacobian(const CurveStart& start, const CurveOptions& options,
                            const CurvePoint& point);

}  // namespace impactkit
