#include "continuation/grazing_corner.hpp"

#include <cmath>

#include "continuation/curve_tests.hpp"
#include "continuation/defining_function.hpp"
#include "continuation/vanishing_impact.hpp"
#include "impactkit/orbits/grazing_limit.hpp"

namespace impactkit::detail {
namespace {

/// Both functions are closed-form (the response, its transition matrix):
/// rounding ~1e-15, so much less than the orbits' 1e-11 can be asked.
constexpr double kCornerTolerance = 1e-13;
constexpr int kCornerIterations = 30;

}  // namespace

std::optional<GrazingCorner> LocateGrazingCorner(const CurveProblem& problem, int q, double lambda,
                                                 double mu1, double mu2) {
  const Rows rows = [&](const Eigen::VectorXd& mu, Eigen::VectorXd* g) {
    if (!mu.allFinite()) return false;
    try {
      const System system = problem.SystemAt(mu(0), mu(1));
      g->resize(2);
      *g << NonImpactingClearance(system), ResponseTouchMonodromy(system, q).GrazingLimit(lambda);
    } catch (const InvalidInput&) {
      return false;  // outside a parameter's range
    }
    return g->allFinite();
  };
  NewtonOptions newton;
  newton.residual_tolerance = kCornerTolerance;
  newton.max_iterations = kCornerIterations;
  Eigen::VectorXd mu(2);
  mu << mu1, mu2;
  const SolveSummary summary =
      SolveNewton([&](const Eigen::VectorXd& x, Eigen::VectorXd* f) { return rows(x, f); },
                  [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
                    return CentralDifferenceGradient(rows, x, kDefiningStep, j);
                  },
                  newton, &mu);
  Eigen::VectorXd g;
  if (summary.termination != Termination::kConverged || !rows(mu, &g)) return std::nullopt;
  return GrazingCorner{mu(0), mu(1), g(0), g(1)};
}

std::optional<Codim2Point> GrazingCornerAhead(const CurveProblem& problem, SpecialPointType type,
                                              const CurvePoint& a, const CurvePoint& b) {
  if ((type != SpecialPointType::kFold && type != SpecialPointType::kPeriodDoubling) ||
      b.orbit.p != 1 || !(b.orbit.contacts.slowest_depth < kCornerDepth)) {
    return std::nullopt;
  }
  const std::optional<double> ma = LinearMonitor(a, Monitor::kDepth);
  const std::optional<double> mb = LinearMonitor(b, Monitor::kDepth);
  if (!ma || !mb || !(*mb < *ma)) return std::nullopt;
  // The monitor (∝ v) is linear in arclength: where it reaches zero.
  const double ahead = *mb / (*ma - *mb);
  const double guess1 = b.parameter + ahead * (b.parameter - a.parameter);
  const double guess2 = b.parameter2 + ahead * (b.parameter2 - a.parameter2);
  const double lambda = type == SpecialPointType::kFold ? 1.0 : -1.0;
  const std::optional<GrazingCorner> corner =
      LocateGrazingCorner(problem, b.orbit.q, lambda, guess1, guess2);
  const double reach = std::hypot(guess1 - b.parameter, guess2 - b.parameter2);
  if (!corner || std::hypot(corner->mu1 - b.parameter, corner->mu2 - b.parameter2) > 2.0 * reach) {
    return std::nullopt;
  }
  Codim2Point end;
  end.type = GrazingMeeting(type);
  end.point.parameter = corner->mu1;
  end.point.parameter2 = corner->mu2;
  end.point.arclength = b.arclength + ahead * (b.arclength - a.arclength);
  end.point.defining = Eigen::VectorXd::Constant(1, corner->limit);
  end.defining_residual = std::abs(corner->limit);
  end.second_residual = std::abs(corner->clearance);
  return end;
}

}  // namespace impactkit::detail
