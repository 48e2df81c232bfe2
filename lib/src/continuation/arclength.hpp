#pragma once
/// \file arclength.hpp
/// What every pseudo-arclength driver (branches, two-parameter curves)
/// shares: the checks of its step controls, so that their messages agree;
/// the bordered corrector, the predictor–corrector step and the step-size
/// rule; the tangent of the solution curve of an underdetermined system;
/// and the zero locator of a test function along it.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

/// What is wrong with the step controls, or nothing: 0 < min_step <=
/// initial_step <= max_step (finite), max_points >= 2, corrector_iterations
/// >= 1, max_correction in (0, 1].
std::optional<std::string> StepControlProblem(double min_step, double initial_step, double max_step,
                                              int max_points, int corrector_iterations,
                                              double max_correction);

/// The bordered corrector: solves F(x) = 0 (n equations, `residual`, with
/// its n x (n + 1) Jacobian `jacobian`) together with c · x = value (the
/// pseudo-arclength constraint, or a parameter held fixed) by Newton from
/// `guess`. Empty if Newton does not converge; *iterations gets its count.
std::optional<Eigen::VectorXd> CorrectBordered(const Residual& residual, const Jacobian& jacobian,
                                               const Eigen::VectorXd& guess,
                                               const Eigen::VectorXd& c, double value,
                                               const NewtonOptions& newton, int* iterations);

/// What is wrong with the user's test functions (continuation.hpp), or
/// nothing: each needs a name and a value function, and names are unique.
std::optional<std::string> UserTestProblem(const std::vector<UserTest>& tests);

/// The unit tangent of {x : F(x) = 0} at a point where F's Jacobian `j`
/// (n x (n + 1)) has full rank: with `previous` (a tangent, size n + 1) the
/// solution of the bordered system [J; previousᵀ] t = e_last, regular at
/// folds and continuing `previous` (previous · t = 1 > 0); without (size 0)
/// the null vector of J from its SVD, of either sign. Nothing where J is
/// singular or not finite.
std::optional<Eigen::VectorXd> ArclengthTangent(const Eigen::MatrixXd& j,
                                                const Eigen::VectorXd& previous);

/// Predicts from the point x0 along its unit tangent t by arclength s and
/// corrects on the hyperplane t · (X − x0) = s (`problem`.Correct, the
/// bordered corrector of a branch's or a curve's problem). Nothing where
/// the corrector fails or moves farther than max_correction |s| from the
/// prediction (a jump to another branch).
template <typename Problem>
std::optional<Eigen::VectorXd> PredictCorrect(const Problem& problem, const Eigen::VectorXd& x0,
                                              const Eigen::VectorXd& t, double s,
                                              const NewtonOptions& newton, double max_correction,
                                              int* iterations) {
  const Eigen::VectorXd guess = x0 + s * t;
  std::optional<Eigen::VectorXd> x = problem.Correct(guess, t, t.dot(x0) + s, newton, iterations);
  if (!x || (*x - guess).norm() > max_correction * std::abs(s)) return std::nullopt;
  return x;
}

/// The step after one whose corrector took `iterations`: 1.5 times longer
/// after an easy one (<= 2), 0.7 times after a hard one (>= 5), within
/// [min_step, max_step].
inline double NextStep(double step, int iterations, double min_step, double max_step) {
  if (iterations <= 2) return std::min(1.5 * step, max_step);
  if (iterations >= 5) return std::max(0.7 * step, min_step);
  return step;
}

/// Iterations of the locators (the Illinois method, secant approaches).
inline constexpr int kMaxLocateIterations = 80;

/// Halvings of a failed trial's distance from the bracket's nearer end
/// before the locator gives up on it.
inline constexpr int kTrialRetreats = 4;

/// A point near arclength *s from a, corrected from the nearer end of the
/// bracket (`lo` and `hi`, at lo_s and hi_s from a): at *s, else at half
/// the distance from that end, a quarter, ... up to kTrialRetreats times,
/// and *s moved to it. `full_step_failed`: the trial at *s itself was
/// just corrected from `lo` and failed, so the halving starts at once.
template <typename Point, typename Advance>
std::optional<Point> NearerEndTrial(const Point& lo, double lo_s, const Point& hi, double hi_s,
                                    double* s, bool full_step_failed, Advance advance) {
  const bool from_lo = std::abs(*s - lo_s) <= std::abs(hi_s - *s);
  const Point& from = from_lo ? lo : hi;
  const double from_s = from_lo ? lo_s : hi_s;
  double step = *s - from_s;
  for (int retreat = 0; retreat <= kTrialRetreats; ++retreat, step /= 2.0) {
    if (retreat == 0 && full_step_failed && from_lo) continue;
    if (std::optional<Point> trial = advance(from, step)) {
      *s = from_s + step;
      return trial;
    }
  }
  return std::nullopt;
}

/// The Illinois method on arclength for the zero of `value` between the
/// points a (s = 0) and b, where it changes sign. Each trial is corrected
/// onto the curve by `advance(from, s)` (nothing where the corrector fails)
/// from a, until the corrector fails there; from then on from the
/// bracket's nearer end (NearerEndTrial). The predictor is a tangent line:
/// where the curve bends sharply (a doubled branch next to its birth, whose
/// μ goes like the square of the distance from it and whose multiplier can
/// go from +1 to −1 within one step) a trial within a's step can be out of
/// the corrector's reach from a, while from a nearer point it is not. The
/// point with the least |value| found; where no trial converged (rare: the
/// corrector failing next to both ends) the nearer end stands in, its value
/// saying how near.
template <typename Point, typename Advance, typename Value>
Point IllinoisZero(const Point& a, const Point& b, Advance advance, Value value) {
  Point lo_point = a, hi_point = b;
  double lo = 0.0, hi = b.arclength - a.arclength;
  double f_lo = value(a), f_hi = value(b);
  std::optional<Point> best;
  int side = 0;
  bool from_a = true;
  for (int k = 0; k < kMaxLocateIterations && std::abs(hi - lo) > 1e-14 * std::abs(hi); ++k) {
    double s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    std::optional<Point> trial;
    if (from_a) trial = advance(a, s);
    if (!trial) {
      // lo is a itself until a trial replaces it.
      trial = NearerEndTrial(lo_point, lo, hi_point, hi, &s, from_a && lo == 0.0, advance);
      from_a = false;
    }
    if (!trial) break;
    const double f = value(*trial);
    if (!best || std::abs(f) < std::abs(value(*best))) best = trial;
    if (f == 0.0) break;
    if ((f > 0) == (f_lo > 0)) {
      lo = s;
      f_lo = f;
      lo_point = *std::move(trial);
      if (side == -1) f_hi /= 2.0;
      side = -1;
    } else {
      hi = s;
      f_hi = f;
      hi_point = *std::move(trial);
      if (side == +1) f_lo /= 2.0;
      side = +1;
    }
  }
  if (!best) best = std::abs(value(a)) < std::abs(value(b)) ? a : b;
  return *best;
}

}  // namespace impactkit
