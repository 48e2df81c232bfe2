#include "continuation/grazing_corner.hpp"

#include <cmath>

#include "continuation/curve_tests.hpp"
#include "continuation/defining_function.hpp"
#include "continuation/vanishing_impact.hpp"
#include "impactkit/orbits/grazing_limit.hpp"

namespace impactkit::detail {
namespace {

/// The response's functions are closed-form (rounding ~1e-15), so much
/// less than the orbits' 1e-11 can be asked of them.
constexpr double kResponseTolerance = 1e-13;
constexpr int kCornerIterations = 30;
/// The weight of σ(K_λ)'s row beside an orbit's equations (tolerance
/// 1e-11): it carries the rounding of the orbit's monodromy, a few 1e-9
/// on P(2,1), so it is asked 1e-8 — the accuracy the corner is reported
/// to.
constexpr double kLimitRowWeight = 1e-3;

struct GrazingCorner {
  double mu1 = 0.0, mu2 = 0.0;
  double clearance = 0.0;  ///< |the grazing equation| there
  double limit = 0.0;      ///< σ(K_λ) there
};

/// Newton on `rows` (as many as unknowns) from x, its Jacobian the
/// analytic `leading` rows (if any) above the gradient of the rows
/// `differenced`, the rest, by central differences; the converged x.
std::optional<Eigen::VectorXd> SolveCorner(
    const Rows& rows, const Rows& differenced,
    const std::function<bool(const Eigen::VectorXd&, Eigen::MatrixXd*)>& leading, double tolerance,
    Eigen::VectorXd x) {
  NewtonOptions newton;
  newton.residual_tolerance = tolerance;
  newton.max_iterations = kCornerIterations;
  const SolveSummary summary = SolveNewton(
      rows,
      [&](const Eigen::VectorXd& at, Eigen::MatrixXd* j) {
        Eigen::MatrixXd top, bottom;
        if (leading && !leading(at, &top)) return false;
        if (!CentralDifferenceGradient(differenced, at, kDefiningStep, &bottom)) return false;
        if (leading) {
          *j << top, bottom;
        } else {
          *j = bottom;
        }
        return true;
      },
      newton, &x);
  if (summary.termination != Termination::kConverged) return std::nullopt;
  return x;
}

/// p = 1: on the response's grazing, X = (μ1, μ2).
std::optional<GrazingCorner> ResponseCorner(const CurveProblem& problem, double lambda,
                                            const Eigen::Vector2d& guess) {
  const int q = problem.Options().orbit.q;
  const int stop = problem.TouchedStop();
  const Rows rows = [&](const Eigen::VectorXd& mu, Eigen::VectorXd* g) {
    if (!mu.allFinite()) return false;
    try {
      const System system = problem.SystemAt(mu(0), mu(1));
      g->resize(2);
      *g << NonImpactingClearance(system, stop),
          SplitMonodromy(system, {ResponseTouch(system, stop)}, q).GrazingLimit(lambda);
    } catch (const InvalidInput&) {
      return false;  // outside a parameter's range
    }
    return g->allFinite();
  };
  const std::optional<Eigen::VectorXd> mu = SolveCorner(rows, rows, {}, kResponseTolerance, guess);
  Eigen::VectorXd g;
  if (!mu || !rows(*mu, &g)) return std::nullopt;
  return GrazingCorner{(*mu)(0), (*mu)(1), std::abs(g(0)), g(1)};
}

/// p >= 2: P(p − 1, q) where it exists beyond b (past the depth's zero,
/// where b's vanishing impact is gone), seeded from the impact after the
/// vanishing one; with its (μ1, μ2).
std::optional<std::pair<PeriodicOrbit, Eigen::Vector2d>> ReducedOrbitBeyond(
    const CurveProblem& problem, const CurvePoint& b, const Eigen::Vector2d& guess) {
  const OrbitOptions& options = problem.Options().orbit;
  const MapResult path = ImpactMap(problem.SystemAt(b.parameter, b.parameter2), options.map)
                             .Apply(b.orbit.eta, options.p, false);
  if (path.termination != Termination::kCompleted) return std::nullopt;
  OrbitOptions reduced = options;
  reduced.p = options.p - 1;
  // Its section is the stop of the impact after the vanishing one.
  const auto after = static_cast<std::size_t>(b.orbit.contacts.slowest_impact);
  reduced.map.stop = path.stops[after];
  const Eigen::VectorXd& seed = path.path[after];
  const Eigen::Vector2d from(b.parameter, b.parameter2);
  for (double beyond : {1.0, 1.5, 2.0, 3.0}) {
    const Eigen::Vector2d mu = from + beyond * (guess - from);
    PeriodicOrbit orbit;
    try {
      if (FindOrbit(problem.SystemAt(mu(0), mu(1)), seed, reduced, &orbit).termination ==
              Termination::kConverged &&
          orbit.contacts.clearance && *orbit.contacts.clearance > 0) {
        return std::pair{orbit, mu};
      }
    } catch (const InvalidInput&) {
      continue;  // outside a parameter's range
    }
  }
  return std::nullopt;
}

/// p >= 2: on P(p − 1, q)'s grazing curve, X = (η, t*, μ1, μ2).
std::optional<GrazingCorner> ReducedCorner(const CurveProblem& problem, double lambda,
                                           const CurvePoint& b, const Eigen::Vector2d& guess) {
  const auto beyond = ReducedOrbitBeyond(problem, b, guess);
  if (!beyond) return std::nullopt;
  const auto& [orbit, mu] = *beyond;
  CurveOptions options = problem.Options();
  options.orbit.p -= 1;
  options.orbit.map.stop = orbit.stop;
  const int flight = orbit.contacts.clearance_flight, touched = orbit.contacts.clearance_stop;
  const CurveProblem grazing(problem.Base(), options, SpecialPointType::kGrazing, flight, touched);
  const Rows limit = [&](const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    try {
      const ImpactMap map(grazing.SystemAt(CurveProblem::Mu1(x), CurveProblem::Mu2(x)),
                          options.orbit.map);
      const std::optional<std::vector<StopContact>> contacts =
          TouchContacts(map, grazing.Eta(x), options.orbit.p, options.orbit.q, flight,
                        grazing.ContactTime(x), touched);
      if (!contacts) return false;
      const SpeedSplitMonodromy m = SplitMonodromy(map.GetSystem(), *contacts, options.orbit.q);
      *g = Eigen::VectorXd::Constant(1, kLimitRowWeight * m.GrazingLimit(lambda));
    } catch (const InvalidInput&) {
      return false;  // outside a parameter's range, or no longer an impact state
    }
    return g->allFinite();
  };
  const Rows rows = [&](const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    Eigen::VectorXd f, l;
    if (!grazing.Residual(x, &f) || !limit(x, &l)) return false;
    g->resize(f.size() + 1);
    *g << f, l;
    return true;
  };
  const std::optional<Eigen::VectorXd> x = SolveCorner(
      rows, limit,
      [&](const Eigen::VectorXd& at, Eigen::MatrixXd* j) { return grazing.Jacobian(at, j); },
      options.orbit.newton.residual_tolerance,
      grazing.Join(orbit.eta, orbit.contacts.clearance_time, mu(0), mu(1)));
  Eigen::VectorXd g;
  if (!x || !rows(*x, &g)) return std::nullopt;
  // The grazing rows hold the touch kGrazingMargin inside the stop.
  const double clearance = std::abs(g(g.size() - 3) - kGrazingMargin);
  return GrazingCorner{CurveProblem::Mu1(*x), CurveProblem::Mu2(*x), clearance,
                       g(g.size() - 1) / kLimitRowWeight};
}

}  // namespace

std::optional<Codim2Point> GrazingCornerAhead(const CurveProblem& problem, SpecialPointType type,
                                              const CurvePoint& a, const CurvePoint& b) {
  // Only a crossing of a real multiplier has the closed-form corner below.
  const TestFunction* own = TestFunctionOf(type);
  if (!own || !own->critical_multiplier || !(b.orbit.contacts.slowest_depth < kCornerDepth)) {
    return std::nullopt;
  }
  const std::optional<double> ma = PointMonitor(a, Monitor::kDepth);
  const std::optional<double> mb = PointMonitor(b, Monitor::kDepth);
  if (!ma || !mb || !(*mb < *ma)) return std::nullopt;
  // The monitor (∝ v) is linear in arclength: where it reaches zero.
  const double ahead = *mb / (*ma - *mb);
  const Eigen::Vector2d from(b.parameter, b.parameter2);
  const Eigen::Vector2d guess = from + ahead * (from - Eigen::Vector2d(a.parameter, a.parameter2));
  const double lambda = *own->critical_multiplier;
  const std::optional<GrazingCorner> corner = b.orbit.p == 1
                                                  ? ResponseCorner(problem, lambda, guess)
                                                  : ReducedCorner(problem, lambda, b, guess);
  if (!corner ||
      (Eigen::Vector2d(corner->mu1, corner->mu2) - from).norm() > 2.0 * (guess - from).norm()) {
    return std::nullopt;
  }
  Codim2Point end;
  end.type = GrazingMeeting(type);
  end.point.parameter = corner->mu1;
  end.point.parameter2 = corner->mu2;
  end.point.arclength = b.arclength + ahead * (b.arclength - a.arclength);
  end.point.defining = Eigen::VectorXd::Constant(1, corner->limit);
  end.defining_residual = std::abs(corner->limit);
  end.second_residual = corner->clearance;
  return end;
}

}  // namespace impactkit::detail
