#pragma once
/// \file test_functions.hpp
/// The kinds of special point met along a branch, and the bifurcation test
/// functions as data: each a named condition on the fixed point's Jacobian
/// D P and its multipliers λ, zero where the bifurcation happens.
///
///     fold              det(D P − I)            a multiplier through +1
///     period doubling   det(D P + I)            a multiplier through −1
///     Neimark–Sacker    Π_{i<j} (λ_i λ_j − 1)   a complex pair through |λ| = 1
///
/// Continuation watches each for a sign change between consecutive points
/// and locates its zero; the two-parameter code follows the same list.

#include <Eigen/Dense>
#include <array>
#include <complex>
#include <optional>
#include <string>
#include <string_view>

namespace impactkit {

enum class SpecialPointType {
  kFold,
  kPeriodDoubling,
  kNeimarkSacker,
  kGrazing,
  kSticking,
  /// The orbit becomes a shorter orbit traversed several times (a P(2,2)
  /// that is P(1,1) twice): the branch meets the branch of that shorter
  /// orbit at its period doubling.
  kBranchPoint,
  /// A multiplier +1 where the branch does not turn (μ keeps its
  /// direction): another branch of the same P(p, q) crosses it — in a
  /// system with a symmetry (a symmetric clearance), the pitchfork where
  /// the symmetric orbit gives birth to a pair of asymmetric ones.
  kPitchfork,
  /// On a family of sticking orbits: the chatter stops ending in sticking
  /// (the stop's force Fs(t*) at its accumulation point falls to 0).
  kNoSticking,
  /// On a family of sticking orbits: Fs touches 0 inside a stuck phase,
  /// beyond which the mass leaves the stop there (one more sticking phase).
  kEarlyRelease,
  /// A zero of a test function of the user's (ContinuationOptions::
  /// user_tests): a quantity of the orbit crossing a level.
  kUserTest,
};

/// "fold", "period_doubling", "neimark_sacker", "grazing", "sticking",
/// "branch_point", "pitchfork", "no_sticking", "early_release",
/// "user_test": the name that outputs (CSV, JSON) use for the type.
std::string ToString(SpecialPointType type);
/// The type of a name of ToString; empty for any other name.
std::optional<SpecialPointType> SpecialPointTypeFromName(std::string_view name);

struct TestFunction {
  SpecialPointType type;
  /// The test function's value at a fixed point with Jacobian `jacobian`
  /// and eigenvalues `multipliers`.
  double (*value)(const Eigen::MatrixXd& jacobian, const Eigen::VectorXcd& multipliers);
  /// How far a multiplier is from the critical one (+1, −1, the upper unit
  /// half-circle): the critical multiplier is the one nearest.
  double (*distance)(std::complex<double> multiplier);
  /// A located zero whose critical multiplier is farther than this is not
  /// this bifurcation (Π (λ_i λ_j − 1) also vanishes at a real pair with
  /// product 1, a neutral saddle; det(D P ∓ I) changes sign where a
  /// multiplier passes through infinity).
  double max_distance;
  /// The real multiplier λ it is the crossing of (+1, −1), if it is one:
  /// then its point is solved directly and its two-parameter curve defined
  /// by σ(D P − λ I) (critical_point.hpp, curve_problem.hpp); otherwise by
  /// the test function itself.
  std::optional<double> critical_multiplier;
  /// Its special point keeps the real eigenvector of the critical
  /// multiplier: the direction of the branch born there (a period
  /// doubling's doubled branch, branch switching).
  bool keeps_eigenvector = false;
};

inline constexpr std::size_t kBifurcationTestCount = 3;

/// Fold, period doubling and Neimark–Sacker, in that order.
const std::array<TestFunction, kBifurcationTestCount>& BifurcationTests();

/// The test function of `type`, and its index in BifurcationTests() (and
/// in a point's test values); null and -1 for a type no test function
/// locates (grazing, sticking, ...).
const TestFunction* TestFunctionOf(SpecialPointType type);
int TestIndex(SpecialPointType type);

/// Every test function's value at one fixed point, in BifurcationTests() order.
std::array<double, kBifurcationTestCount> EvaluateBifurcationTests(
    const Eigen::MatrixXd& jacobian, const Eigen::VectorXcd& multipliers);

}  // namespace impactkit
