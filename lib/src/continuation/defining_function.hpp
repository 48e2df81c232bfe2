#pragma once
/// \file defining_function.hpp (private)
/// What the defining systems of special points share — the two-parameter
/// curves (curve_problem.hpp) and the direct solve of one fold or period
/// doubling (critical_point.hpp): the minimally augmented function of a
/// matrix that must become singular, and the central-difference gradient of
/// the rows no analytic derivative is written for.

#include <Eigen/Dense>
#include <functional>

namespace impactkit::detail {

/// The borders of the minimally augmented system [A b; cᵀ 0] (Govaerts):
/// b and c the left and right singular vectors of A's least singular value
/// at a reference point, so that the bordered matrix is well conditioned
/// near it. Kept fixed while a solver runs: σ is then one smooth function.
struct SigmaBorders {
  Eigen::VectorXd b, c;
};

/// The borders for A = D P − λ I at the reference D P (λ = +1 for a fold,
/// −1 for a period doubling).
SigmaBorders MultiplierBorders(const Eigen::MatrixXd& dp, double lambda);

/// σ(D P − λ I) / (1 + ‖D P‖_F), where σ(A) is the last component of the
/// solution of [A b; cᵀ 0] (v, σ) = (0, 1): zero exactly where λ is a
/// multiplier, smooth in D P (unlike det, whose scale is the product of
/// every other multiplier's distance from λ). Divided by D P's size so that
/// one tolerance serves short orbits and long ones, whose D P has entries
/// of 1e4 and whose σ carries their rounding (~1e-10).
double MultiplierFunction(const Eigen::MatrixXd& dp, double lambda, const SigmaBorders& borders);

/// The weight of that function's row in a Newton system whose residual
/// tolerance is the orbit's (max |U| <= 1e-11): the D P of a long orbit is
/// known only to ~1e-9 (equivalent solves of one orbit move its multipliers
/// by that much), so σ cannot be asked for more. Weighting its row asks
/// 1e-9 of it and leaves Newton's steps as they are.
constexpr double kMultiplierRowWeight = 1e-2;

/// Relative step of the defining rows' central differences (below). Each map
/// carries event-time rounding of ~1e-12 (impact_map.hpp): this step leaves
/// ~1e-6 of it in the gradient, ample for Newton. A step near the cube root
/// of the rounding (1e-4 to 1e-5) would balance it against the truncation
/// error for a map of moderate curvature, but near a slow impact (speed v)
/// the map's curvature grows like 1/v³: on P(1,2)'s fold curve in (Ω, xs),
/// v ≈ 0.01, 1e-5 left a 1% error in the xs column, 1e-6 leaves 1e-4.
constexpr double kDefiningStep = 1e-6;

/// True when U's change between a difference's centre and one of its
/// points, `change`, is what U's analytic derivative predicts, `predicted`,
/// to within ten times it (plus U's rounding): the map there followed the same
/// impacts. Beside a grazing a step of 1e-6 can cross it, and the map then
/// takes the new contact: its U jumps by a flight and its D P is another
/// orbit's, so a row built on D P must not be differenced across it (the
/// N = 1 oscillator's P(1,1) fold curve in (Ω, xs) and the paper's P(3,1)
/// fold curve in (Ω, A1) failed so at clearance 7e-7: the gradient of σ
/// was wrong and Newton stalled). The allowance is wide because beside a
/// slow impact U is strongly curved: on P(1,2)'s period-doubling curve in
/// (Ω, r) near its vanishing impact a step of 1e-6 moved U 13–80 % off the
/// linear prediction, while the impact's disappearing moved it by 6.2 (a
/// whole flight), 10⁴ times the prediction.
bool SameImpacts(const Eigen::VectorXd& change, const Eigen::VectorXd& predicted);

/// `rows` at x (their number fixed by the first call); false where they have
/// no value.
using Rows = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* g)>;

/// The gradient of `rows` at x by central differences, step `relative_step`
/// · max(1, |x_i|) in each coordinate, one-sided where one side has no
/// value; false where neither side has one.
bool CentralDifferenceGradient(const Rows& rows, const Eigen::VectorXd& x, double relative_step,
                               Eigen::MatrixXd* gradient);

}  // namespace impactkit::detail
