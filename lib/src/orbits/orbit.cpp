#include "impactkit/orbits/orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "impactkit/orbits/grazing_limit.hpp"
#include "orbits/fixed_point.hpp"
#include "orbits/orbit_shooting.hpp"

namespace impactkit {

OrbitPeriod PrimitivePeriod(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            double tolerance) {
  const MapResult image = map.Apply(eta, p, false);
  if (image.termination != Termination::kCompleted) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, Describe(image.termination)));
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
  Eigen::MatrixXd jacobian = FiniteDifferenceJacobian(map, eta, p);
  if (jacobian.size() == 0) {
    throw InvalidInput(
        "the finite-difference Jacobian cannot be formed here: a perturbed map loses or grazes an "
        "impact (use the analytic Jacobian)");
  }
  return jacobian;
}

MapResult ApplyOrThrow(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  MapResult image = map.Apply(eta, p, true);
  if (image.termination != Termination::kCompleted) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, Describe(image.termination)));
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

Eigen::VectorXcd SortedByModulus(Eigen::VectorXcd values) {
  std::sort(values.begin(), values.end(),
            [](const auto& a, const auto& b) { return std::abs(a) > std::abs(b); });
  return values;
}

namespace {

/// The finite eigenvalues of the pencil [A u; n −v] − λ diag(I, 0), largest
/// first: by the matrix determinant lemma those of M(v) = A + u n / v,
/// from O(1) entries however small v is.
Eigen::VectorXcd PencilMultipliers(const SpeedSplitMonodromy& split, double speed) {
  const Eigen::Index n = split.regular.rows();
  Eigen::MatrixXd a(n + 1, n + 1), b = Eigen::MatrixXd::Zero(n + 1, n + 1);
  a << split.regular, split.singular, split.normal, -speed;
  b.topLeftCorner(n, n).setIdentity();
  const Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> pencil(a, b, false);
  // The one infinite eigenvalue (β = 0 to rounding) is the smallest |β|/|α|.
  const Eigen::VectorXcd alphas = pencil.alphas();
  const Eigen::VectorXd betas = pencil.betas();
  Eigen::Index infinite = 0;
  (betas.array().abs() / alphas.array().abs()).minCoeff(&infinite);
  Eigen::VectorXcd lambda(n);
  for (Eigen::Index i = 0, k = 0; i <= n; ++i) {
    if (i != infinite) lambda(k++) = alphas(i) / betas(i);
  }
  return SortedByModulus(lambda);
}

/// The multipliers of D P_I^p = `jacobian`, largest first. Near grazing
/// (an impact's speed v → 0) D P_I^p ~ A + u n / v (grazing_limit.hpp) has
/// norm ~1/v, and an eigensolver on it places each multiplier only to
/// ~ε ‖D P_I^p‖ absolutely: the small ones are lost (λ2 ~ 4e-10 against
/// an error ~2e-7 at v = 7e-10). Where that error exceeds 1e-9 of the
/// smallest, all but the largest come from the split monodromy's pencil
/// at the slowest impact (at any stop; docs/theory.md §5b).
Eigen::VectorXcd Multipliers(const ImpactMap& map, const std::vector<Eigen::VectorXd>& etas,
                             const std::vector<int>& stops, int q,
                             const Eigen::MatrixXd& jacobian) {
  Eigen::VectorXcd lambda =
      SortedByModulus(Eigen::EigenSolver<Eigen::MatrixXd>(jacobian).eigenvalues());
  constexpr double kRelativeAccuracy = 1e-9;
  const double error = std::numeric_limits<double>::epsilon() * jacobian.norm();
  if (lambda.size() < 2 || !(error > kRelativeAccuracy * std::abs(lambda(lambda.size() - 1)))) {
    return lambda;
  }
  // The contacts from the slowest impact on, within q periods.
  const int p = static_cast<int>(etas.size());
  int slowest = 0;
  for (int k = 1; k < p; ++k) {
    if (map.Speed(etas[k], stops[k]) < map.Speed(etas[slowest], stops[slowest])) slowest = k;
  }
  std::vector<StopContact> contacts;
  for (int k = 0; k < p; ++k) {
    const int at = (slowest + k) % p;
    contacts.push_back({map.ToState(etas[at], stops[at]), stops[at]});
    if (at < slowest) contacts.back().state.t += q * map.GetSystem().ForcingPeriod();
  }
  const Eigen::VectorXcd pencil = PencilMultipliers(SplitMonodromy(map.GetSystem(), contacts, q),
                                                    map.Speed(etas[slowest], stops[slowest]));
  lambda.tail(lambda.size() - 1) = pencil.tail(pencil.size() - 1);
  return lambda;
}

/// The orbit through the impacts `etas` (η_0 … η_{p−1}, at `stops`) with
/// D P_I^p = `jacobian` and max |U| = `residual`.
PeriodicOrbit OrbitThrough(const ImpactMap& map, const std::vector<Eigen::VectorXd>& etas,
                           const std::vector<int>& stops, int q, Eigen::MatrixXd jacobian,
                           double residual) {
  const System& system = map.GetSystem();
  const int p = static_cast<int>(etas.size());
  PeriodicOrbit orbit;
  orbit.p = p;
  orbit.q = q;
  orbit.omega = system.omega;
  orbit.eta = etas.front();
  orbit.stop = map.SectionStop();
  orbit.jacobian = std::move(jacobian);
  orbit.residual = residual;
  for (int k = 0; k < p; ++k) {
    const double t = etas[k](map.TimeIndex());
    orbit.impacts.push_back({t, system.Phase(t), map.Speed(etas[k], stops[k]), stops[k]});
  }
  orbit.multipliers = Multipliers(map, etas, stops, q, orbit.jacobian);
  const Eigen::VectorXcd& lambda = orbit.multipliers;
  orbit.stable = lambda.size() == 0 || std::abs(lambda(0)) < 1.0;
  std::vector<Eigen::VectorXd> path = etas;
  path.push_back(etas.front());
  path.back()(map.TimeIndex()) += q * system.ForcingPeriod();
  std::vector<int> path_stops = stops;
  path_stops.push_back(stops.front());
  orbit.contacts = MeasureOrbitContacts(map, path, path_stops);
  return orbit;
}

/// max |U| at η from the map's image of it.
double FixedPointResidual(const ImpactMap& map, const Eigen::VectorXd& eta, int q,
                          const MapResult& image) {
  Eigen::VectorXd u = image.eta - eta;
  u(map.TimeIndex()) -= q * map.GetSystem().ForcingPeriod();
  return u.cwiseAbs().maxCoeff();
}

}  // namespace

PeriodicOrbit DescribeOrbit(const ImpactMap& map, const Eigen::VectorXd& eta, int p, int q,
                            JacobianMethod method) {
  const MapResult image = ApplyOrThrow(map, eta, p);
  std::vector<Eigen::VectorXd> etas{eta};
  std::vector<int> stops{map.SectionStop()};
  for (int k = 0; k + 1 < p; ++k) {
    etas.push_back(image.path[k]);
    stops.push_back(image.stops[k]);
  }
  Eigen::MatrixXd jacobian = method == JacobianMethod::kAnalytic
                                 ? image.jacobian
                                 : FiniteDifferenceJacobianOrThrow(map, eta, p);
  return OrbitThrough(map, etas, stops, q, std::move(jacobian),
                      FixedPointResidual(map, eta, q, image));
}

double ResidualFloor(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& eta) {
  // Measured: max |U| at the orbits found 0.04 to 0.35 of one unit for v
  // from 7e-5 down to 7e-9 (tests/test_orbit_grazing.cpp).
  constexpr double kRoundings = 8.0;
  return kRoundings * std::numeric_limits<double>::epsilon() *
         jacobian.cwiseAbs().rowwise().sum().maxCoeff() * std::max(1.0, eta.cwiseAbs().maxCoeff());
}

std::string ToString(OrbitSection section) {
  return section == OrbitSection::kImpact ? "impact" : "release";
}

std::string OrbitName(const PeriodicOrbit& orbit) {
  return orbit.Sticks() ? fmt::format("P(inf,{})", orbit.q)
                        : fmt::format("P({},{})", orbit.p, orbit.q);
}

std::span<const OrbitImpact> CycleImpacts(const PeriodicOrbit& orbit, std::size_t k) {
  std::size_t first = 0;
  for (std::size_t i = 0; i < k; ++i) first += orbit.stuck[i].impacts;
  return std::span<const OrbitImpact>(orbit.impacts).subspan(first, orbit.stuck[k].impacts);
}

std::vector<OrbitImpact> LeadingImpacts(const PeriodicOrbit& orbit) {
  if (!orbit.Sticks()) return orbit.impacts;
  std::vector<OrbitImpact> leading;
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    const std::span<const OrbitImpact> cycle = CycleImpacts(orbit, k);
    if (!cycle.empty()) leading.push_back(cycle.front());
  }
  return leading;
}

std::string ToString(JacobianMethod method) {
  return method == JacobianMethod::kAnalytic ? "analytic" : "finite-difference";
}

bool OrbitOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (releases < 0) {
    return fail(fmt::format("releases must be >= 0 (0: an impacting orbit), got {}", releases));
  }
  if (Section() == OrbitSection::kRelease) {
    if (q < 1) {
      return fail(
          fmt::format("releases and q must be >= 1, got releases = {}, q = {}", releases, q));
    }
    return newton.IsValid(error) && release_map.IsValid(error);
  }
  if (p < 1 || q < 1) return fail(fmt::format("p and q must be >= 1, got p = {}, q = {}", p, q));
  return newton.IsValid(error) && map.IsValid(error);
}

std::string OrbitSummary::BriefReport() const {
  std::string shooting;
  if (unresolved_impacts > 0) {
    shooting = fmt::format(
        " (fixed-time formulation, residual max|W|; {} impact(s) below the arrival resolution: "
        "a simulation sees a grazing touch there)",
        unresolved_impacts);
  } else if (used_shooting) {
    shooting = fmt::format(
        " (fixed-time formulation, max|W| {:.2e}; residual accepted below the map's rounding "
        "floor {:.2e})",
        shooting_residual, residual_floor);
  }
  return fmt::format("{}{}{}, {:.3g} s{}", SolveReport(termination, residual, iterations),
                     used_fallback ? " (Levenberg-Marquardt fallback)" : "", shooting, seconds,
                     message.empty() ? "" : " (" + message + ")");
}

namespace {

/// The orbit through a fixed point η of the map. The analytic D P_I^p is
/// taken along its impacts at the times the fixed point gives them (the
/// last at τ + qT), not at the event search's own arrival, whose speed
/// carries U's rounding: near grazing, 1/v magnifies that (3.6e-6 relative
/// in the leading multiplier at v = 7e-7, tests/test_orbit_grazing.cpp).
/// Throws InvalidInput if the map fails from η.
PeriodicOrbit DescribeFixedPoint(const HybridSystem& hybrid, const ImpactMap& map,
                                 const OrbitOptions& options, const Eigen::VectorXd& eta) {
  if (options.jacobian == JacobianMethod::kFiniteDifference) {
    return DescribeOrbit(map, eta, options.p, options.q, options.jacobian);
  }
  const MapResult image = ApplyOrThrow(map, eta, options.p);
  std::vector<Eigen::VectorXd> etas{eta};
  std::vector<int> stops{map.SectionStop()};
  for (int k = 0; k + 1 < options.p; ++k) {
    etas.push_back(image.path[k]);
    stops.push_back(image.stops[k]);
  }
  const ShootingProblem path(hybrid, map, stops, options.q);
  return OrbitThrough(map, etas, stops, options.q, path.MapJacobian(path.Pack(etas)),
                      FixedPointResidual(map, eta, options.q, image));
}

/// Newton on U, then Levenberg–Marquardt from the guess (SolveFixedPoint):
/// kConverged with *orbit described, or why not, with *eta the best point.
OrbitSummary SolveOnMap(const HybridSystem& hybrid, const ImpactMap& map,
                        const OrbitOptions& options, const Eigen::VectorXd& guess,
                        Eigen::VectorXd* eta, PeriodicOrbit* orbit) {
  const FixedPointProblem problem(map, options.p, options.q,
                                  options.jacobian == JacobianMethod::kAnalytic);
  const FixedPointSolve solved =
      SolveFixedPoint(problem, guess, options.newton, options.least_squares_fallback);
  OrbitSummary summary;
  summary.iterations = solved.iterations;
  summary.used_fallback = solved.used_fallback;
  summary.termination = solved.solve.termination;
  summary.message = solved.solve.message;
  summary.residual = solved.solve.residual_norm;
  *eta = solved.x;
  if (summary.termination != Termination::kConverged) return summary;
  try {
    *orbit = DescribeFixedPoint(hybrid, map, options, *eta);
    orbit->residual = summary.residual;
  } catch (const InvalidInput& e) {
    // U vanishes at a point whose map fails (an impact of speed ~0: the
    // solver met a grazing orbit); the guess was fine, the point is no
    // orbit.
    summary.termination = Termination::kFailure;
    summary.message = fmt::format("converged to a point that is no orbit: {}", e.what());
  }
  return summary;
}

/// The impacts of the guess and their stops: the guess alone for p = 1,
/// else with its first p − 1 images (none if the map fails there).
std::optional<std::vector<Eigen::VectorXd>> ImpactsFrom(const ImpactMap& map,
                                                        const Eigen::VectorXd& guess, int p,
                                                        std::vector<int>* stops) {
  std::vector<Eigen::VectorXd> etas{guess};
  *stops = {map.SectionStop()};
  if (p == 1) return etas;
  const MapResult image = map.Apply(guess, p, false);
  if (image.termination != Termination::kCompleted) return std::nullopt;
  for (int k = 0; k + 1 < p; ++k) {
    etas.push_back(image.path[k]);
    stops->push_back(image.stops[k]);
  }
  return etas;
}

/// How many impacts of the fixed-time solution the map cannot follow
/// (below the arrival rule's resolution), each flight searched on its own
/// up to its impact; a reason to reject it if a flight meets a stop before
/// its impact.
int UnresolvedImpacts(const ImpactMap& map, const std::vector<Eigen::VectorXd>& etas,
                      const std::vector<int>& stops, int q, std::string* contact) {
  // An arrival within this fraction of a period of the impact is the
  // impact itself (the search places a crossing at speed u to ~ε L/u).
  constexpr double kSameImpact = 1e-6;
  const int p = static_cast<int>(etas.size());
  const double period = map.GetSystem().ForcingPeriod(), margin = kSameImpact * period;
  int unresolved = 0;
  for (int k = 0; k < p; ++k) {
    const double t_impact =
        k + 1 < p ? etas[k + 1](map.TimeIndex()) : etas[0](map.TimeIndex()) + q * period;
    const std::optional<ImpactMap::FlightEnd> end =
        map.FirstArrival(etas[k], stops[k], t_impact + margin);
    if (end && end->state.t < t_impact - margin) {
      *contact = fmt::format("flight {} meets stop {} at t = {:.10g}, before its impact at {:.10g}",
                             k + 1, end->stop + 1, end->state.t, t_impact);
      return 0;
    }
    if (!end || !end->impact) ++unresolved;
  }
  return unresolved;
}

/// The fixed-time solution z is an orbit if every impact moves towards its
/// stop (W also has virtual solutions, v <= 0), no flight meets a stop
/// before its impact (W ignores contacts between impacts), and, when every
/// impact is resolved, the map returns from η_0 to within U's rounding
/// floor.
void AcceptShooting(const ShootingProblem& problem, const ImpactMap& map,
                    const OrbitOptions& options, const Eigen::VectorXd& z, OrbitSummary* summary,
                    PeriodicOrbit* orbit) {
  auto reject = [&](const std::string& why) {
    summary->termination = Termination::kFailure;
    summary->message = "fixed-time formulation: converged to a point that is no orbit: " + why;
  };
  std::vector<Eigen::VectorXd> etas;
  std::vector<int> stops;
  for (int k = 0; k < problem.Impacts(); ++k) {
    etas.push_back(problem.Eta(z, k));
    stops.push_back(problem.Stop(k));
    const double speed = map.Speed(etas[k], stops[k]);
    if (!(speed > 0)) return reject(fmt::format("impact {} has speed {:.3g} <= 0", k + 1, speed));
  }
  Eigen::MatrixXd jacobian = problem.MapJacobian(z);
  summary->residual_floor =
      std::max(options.newton.residual_tolerance, ResidualFloor(jacobian, etas[0]));
  std::string contact;
  summary->unresolved_impacts = UnresolvedImpacts(map, etas, stops, options.q, &contact);
  if (!contact.empty()) return reject(contact);
  if (summary->unresolved_impacts > 0) {
    summary->residual = summary->shooting_residual;
  } else {
    const MapResult image = map.Apply(etas[0], options.p, false);
    if (image.termination != Termination::kCompleted) {
      return reject(fmt::format("the map from it fails after {} of {} impacts: {}",
                                image.impacts_done, options.p, Describe(image.termination)));
    }
    summary->residual = FixedPointResidual(map, etas[0], options.q, image);
    if (summary->residual > summary->residual_floor) {
      return reject(fmt::format("the map does not return to it, max|U| = {:.3g} above {:.3g}",
                                summary->residual, summary->residual_floor));
    }
  }
  *orbit = OrbitThrough(map, etas, stops, options.q, std::move(jacobian), summary->residual);
}

/// Newton on W = 0 (orbit_shooting.hpp) from the guess's impacts.
OrbitSummary SolveByShooting(const HybridSystem& hybrid, const ImpactMap& map,
                             const OrbitOptions& options, const Eigen::VectorXd& guess,
                             PeriodicOrbit* orbit) {
  OrbitSummary summary;
  summary.termination = Termination::kFailure;
  std::vector<int> stops;
  const auto etas = ImpactsFrom(map, guess, options.p, &stops);
  if (!etas) {
    summary.message = "fixed-time formulation: the map cannot follow the seed's impacts";
    return summary;
  }
  const ShootingProblem problem(hybrid, map, stops, options.q);
  Eigen::VectorXd z = problem.Pack(*etas);
  const SolveSummary solve = problem.Solve(options.newton, &z);
  summary.iterations = solve.iterations;
  summary.termination = solve.termination;
  summary.message = "fixed-time formulation: " + solve.message;
  summary.shooting_residual = solve.residual_norm;
  if (summary.termination != Termination::kConverged) return summary;
  summary.used_shooting = true;
  AcceptShooting(problem, map, options, problem.WithPhase(z), &summary, orbit);
  return summary;
}

}  // namespace

OrbitSummary FindOrbit(const System& system, const Eigen::VectorXd& guess,
                       const OrbitOptions& options, PeriodicOrbit* orbit) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  if (options.Section() == OrbitSection::kRelease) {
    OrbitSummary summary = FindStickingOrbit(system, guess, options, orbit);
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
  }
  const auto hybrid = std::make_shared<const HybridSystem>(system);
  const ImpactMap map(hybrid, options.map);
  map.ValidateEta(guess);

  Eigen::VectorXd eta;
  OrbitSummary summary = SolveOnMap(*hybrid, map, options, map.WithPhase(guess), &eta, orbit);
  if (summary.termination != Termination::kConverged && options.shooting_fallback) {
    OrbitSummary shooting = SolveByShooting(*hybrid, map, options, map.WithPhase(guess), orbit);
    shooting.iterations += summary.iterations;
    shooting.used_fallback = summary.used_fallback;
    if (shooting.termination == Termination::kConverged) {
      summary = shooting;
    } else {
      summary.iterations = shooting.iterations;
      summary.message += "; " + shooting.message;
    }
  }
  if (summary.termination != Termination::kConverged) {
    orbit->eta = eta;
    orbit->stop = map.SectionStop();
    orbit->residual = summary.residual;
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace impactkit
