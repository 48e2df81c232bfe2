#include "impactkit/orbits/orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace impactkit {
namespace {

/// The same impact state with τ moved into [0, T): the map commutes with
/// shifts by T, and small times keep event times precise.
Eigen::VectorXd WithPhase(const ImpactMap& map, Eigen::VectorXd eta) {
  const int i = map.TimeIndex();
  eta(i) = map.GetSystem().Phase(eta(i));
  return eta;
}

/// U(η) = P_I^p(η) - η - q T e_τ and its Jacobian, as callbacks for the
/// nonlinear solvers; a failing map (or an η that is no impact state)
/// tells the solver to shorten its step.
class FixedPointProblem {
 public:
  FixedPointProblem(const ImpactMap& map, const OrbitOptions& options)
      : map_(map), options_(options) {}

  bool Residual(const Eigen::VectorXd& eta, Eigen::VectorXd* u) const {
    // Newton asks for the Jacobian where it has just asked for the residual:
    // the analytic one costs little beside the map, so compute both at once.
    const bool analytic = options_.jacobian == JacobianMethod::kAnalytic;
    const std::optional<MapResult> image = Map(eta, analytic);
    if (!image) return false;
    if (analytic) {
      cached_eta_ = eta;
      cached_jacobian_ = image->jacobian;
    }
    *u = image->eta - eta;
    (*u)(map_.TimeIndex()) -= options_.q * map_.GetSystem().ForcingPeriod();
    return u->allFinite();
  }

  bool Jacobian(const Eigen::VectorXd& eta, Eigen::MatrixXd* jacobian) const {
    if (options_.jacobian == JacobianMethod::kFiniteDifference) {
      *jacobian = map_.FiniteDifferenceJacobian(eta, options_.p);
      if (jacobian->size() == 0) return false;
    } else if (cached_eta_.size() == eta.size() && cached_eta_ == eta) {
      *jacobian = cached_jacobian_;
    } else {
      const std::optional<MapResult> image = Map(eta, true);
      if (!image) return false;
      *jacobian = image->jacobian;
    }
    jacobian->diagonal().array() -= 1.0;
    return jacobian->allFinite();
  }

 private:
  std::optional<MapResult> Map(const Eigen::VectorXd& eta, bool with_jacobian) const {
    if (!eta.allFinite() || !(map_.Speed(eta, map_.SectionStop()) > 0)) return std::nullopt;
    MapResult image = map_.Apply(eta, options_.p, with_jacobian);
    if (image.status != MapStatus::kOk) return std::nullopt;
    return image;
  }

  const ImpactMap& map_;
  const OrbitOptions& options_;
  mutable Eigen::VectorXd cached_eta_;  ///< where cached_jacobian_ was computed
  mutable Eigen::MatrixXd cached_jacobian_;
};

}  // namespace

OrbitPeriod PrimitivePeriod(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            double tolerance) {
  const MapResult image = map.Apply(eta, p, false);
  if (image.status != MapStatus::kOk) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, ToString(image.status)));
  }
  const double scale = 1.0 + eta.cwiseAbs().maxCoeff();
  const double period = map.GetSystem().ForcingPeriod();
  for (int part = 1; part < p; ++part) {  // the shortest repeating part first
    if (p % part != 0 || q % (p / part) != 0) continue;
    if (image.stops[part - 1] != map.SectionStop()) continue;
    Eigen::VectorXd gap = image.path[part - 1] - eta;
    gap(map.TimeIndex()) -= (q / (p / part)) * period;
    if (gap.cwiseAbs().maxCoeff() <= tolerance * scale) return {part, q / (p / part)};
  }
  return {p, q};
}

namespace {

/// D P_I^p at η by finite differences; throws where a perturbed map fails.
Eigen::MatrixXd FiniteDifferenceJacobianOrThrow(const ImpactMap& map, const Eigen::VectorXd& eta,
                                                int p) {
  Eigen::MatrixXd jacobian = map.FiniteDifferenceJacobian(eta, p);
  if (jacobian.size() == 0) {
    throw InvalidInput(
        "the finite-difference Jacobian cannot be formed here: a perturbed map loses or grazes an "
        "impact (use the analytic Jacobian)");
  }
  return jacobian;
}

MapResult ApplyOrThrow(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  MapResult image = map.Apply(eta, p, true);
  if (image.status != MapStatus::kOk) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, ToString(image.status)));
  }
  return image;
}

}  // namespace

JacobianComparison CompareJacobians(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  const Eigen::MatrixXd analytic = ApplyOrThrow(map, eta, p).jacobian;
  const Eigen::MatrixXd difference = analytic - FiniteDifferenceJacobianOrThrow(map, eta, p);
  JacobianComparison comparison;
  comparison.max_difference = difference.cwiseAbs().maxCoeff();
  comparison.max_relative_difference =
      comparison.max_difference / std::max(1.0, analytic.cwiseAbs().maxCoeff());
  return comparison;
}

PeriodicOrbit DescribeOrbit(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            JacobianMethod method) {
  const MapResult image = ApplyOrThrow(map, eta, p);
  const System& system = map.GetSystem();
  PeriodicOrbit orbit;
  orbit.p = p;
  orbit.q = q;
  orbit.omega = system.omega;
  orbit.eta = eta;
  orbit.stop = map.SectionStop();
  orbit.jacobian = method == JacobianMethod::kAnalytic
                       ? image.jacobian
                       : FiniteDifferenceJacobianOrThrow(map, eta, p);
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(eta.size());
  shift(map.TimeIndex()) = q * system.ForcingPeriod();
  orbit.residual = (image.eta - eta - shift).cwiseAbs().maxCoeff();
  for (int k = 0; k < p; ++k) {
    const Eigen::VectorXd& at = k == 0 ? eta : image.path[k - 1];
    const int stop = k == 0 ? map.SectionStop() : image.stops[k - 1];
    const double t = at(map.TimeIndex());
    orbit.impacts.push_back({t, system.Phase(t), map.Speed(at, stop), stop});
  }
  Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(orbit.jacobian).eigenvalues();
  std::sort(lambda.begin(), lambda.end(),
            [](const auto& a, const auto& b) { return std::abs(a) > std::abs(b); });
  orbit.multipliers = lambda;
  orbit.stable = lambda.size() == 0 || std::abs(lambda(0)) < 1.0;
  orbit.contacts = MeasureOrbitContacts(map, eta, p);
  return orbit;
}

std::string ToString(JacobianMethod method) {
  return method == JacobianMethod::kAnalytic ? "analytic" : "finite-difference";
}

bool OrbitOptions::IsValid(std::string* error) const {
  if (p < 1 || q < 1) {
    if (error) *error = fmt::format("p and q must be >= 1, got p = {}, q = {}", p, q);
    return false;
  }
  return newton.IsValid(error) && map.IsValid(error);
}

std::string OrbitSummary::BriefReport() const {
  return fmt::format("{}: residual {:.2e} after {} iterations{}, {:.3g} s{}", ToString(termination),
                     residual, iterations, used_fallback ? " (Levenberg-Marquardt fallback)" : "",
                     seconds, message.empty() ? "" : " (" + message + ")");
}

OrbitSummary FindOrbit(const System& system, const Eigen::VectorXd& guess,
                       const OrbitOptions& options, PeriodicOrbit* orbit) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const ImpactMap map(system, options.map);
  map.ValidateEta(guess);
  const FixedPointProblem problem(map, options);
  const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    return problem.Residual(x, f);
  };
  const Jacobian jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    return problem.Jacobian(x, j);
  };

  OrbitSummary summary;
  Eigen::VectorXd eta = WithPhase(map, guess);
  Eigen::VectorXd u;
  if (!problem.Residual(eta, &u)) {
    const MapResult image = map.Apply(eta, options.p, false);
    summary.termination = Termination::kFailure;
    summary.message = fmt::format("the map failed at the seed after {} of {} impacts: {}",
                                  image.impacts_done, options.p, ToString(image.status));
    return summary;
  }
  SolveSummary solve = SolveNewton(residual, jacobian, options.newton, &eta);
  summary.iterations = solve.iterations;
  if (solve.termination != Termination::kConverged && options.least_squares_fallback) {
    eta = WithPhase(map, guess);
    solve = SolveLeastSquares(residual, jacobian, options.newton, &eta);
    summary.iterations += solve.iterations;
    summary.used_fallback = true;
  }
  summary.termination = solve.termination;
  summary.message = solve.message;
  summary.residual = solve.residual_norm;
  eta = WithPhase(map, eta);
  if (summary.termination == Termination::kConverged) {
    try {
      *orbit = DescribeOrbit(map, eta, options.p, options.q, options.jacobian);
    } catch (const InvalidInput& e) {
      // U vanishes at a point whose map fails (an impact of speed ~0: the
      // solver met a grazing orbit); the guess was fine, the point is no
      // orbit.
      summary.termination = Termination::kFailure;
      summary.message = fmt::format("converged to a point that is no orbit: {}", e.what());
    }
  }
  if (summary.termination != Termination::kConverged) {
    orbit->eta = eta;
    orbit->stop = map.SectionStop();
  }
  orbit->residual = solve.residual_norm;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace impactkit
