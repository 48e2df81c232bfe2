#include "impactkit/orbits/sticking_orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "orbits/fixed_point.hpp"

namespace impactkit {
namespace {

StickingMapResult ApplyOrThrow(const StickingMap& map, const Eigen::VectorXd& s, int k,
                               bool with_contacts = false) {
  StickingMapResult image = map.Apply(s, k, true, with_contacts);
  if (image.status != StickingMapStatus::kOk) {
    throw InvalidInput(
        fmt::format("no sticking orbit through this release state: after {} of {} releases, {}",
                    image.cycles_done, k, ToString(image.status)));
  }
  return image;
}

}  // namespace

bool StickingOrbitOptions::IsValid(std::string* error) const {
  if (releases < 1 || q < 1) {
    if (error) {
      *error = fmt::format("releases and q must be >= 1, got releases = {}, q = {}", releases, q);
    }
    return false;
  }
  return newton.IsValid(error) && map.IsValid(error);
}

std::string StickingOrbitSummary::BriefReport() const {
  return fmt::format("{}, {:.3g} s{}", SolveReport(termination, residual, iterations), seconds,
                     message.empty() ? "" : " (" + message + ")");
}

Eigen::VectorXcd SectionMultipliers(const StickingMap& map, const Eigen::VectorXd& s,
                                    const Eigen::MatrixXd& jacobian) {
  // An orthonormal basis of the tangent space ker ∇Fs: the last m − 1
  // columns of the full QR of ∇Fsᵀ.
  const Eigen::VectorXd normal = map.ContactForceGradient(s).transpose();
  const Eigen::Index m = normal.size();
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(normal).householderQ();
  const Eigen::MatrixXd basis = q.rightCols(m - 1);
  Eigen::VectorXcd lambda(m - 1);
  if (m > 1) {
    const Eigen::MatrixXd restricted = basis.transpose() * jacobian * basis;
    lambda = Eigen::EigenSolver<Eigen::MatrixXd>(restricted).eigenvalues();
  }
  std::sort(lambda.begin(), lambda.end(),
            [](const auto& a, const auto& b) { return std::abs(a) > std::abs(b); });
  return lambda;
}

StickingOrbit DescribeStickingOrbit(const StickingMap& map, const Eigen::VectorXd& s, int releases,
                                    int q) {
  const StickingMapResult image = ApplyOrThrow(map, s, releases, true);
  const System& system = map.GetSystem();
  StickingOrbit orbit;
  orbit.stop = map.SectionStop();
  orbit.releases = releases;
  orbit.q = q;
  orbit.omega = system.omega;
  orbit.state = s;
  orbit.cycles = image.cycles;
  orbit.contact_margin = std::numeric_limits<double>::infinity();
  orbit.clearance = std::numeric_limits<double>::infinity();
  orbit.hold_margin = std::numeric_limits<double>::infinity();
  for (const StickingCycle& cycle : image.cycles) {
    orbit.contact_margin = std::min(orbit.contact_margin, cycle.contact_force);
    orbit.clearance = std::min(orbit.clearance, cycle.clearance);
    orbit.hold_margin = std::min(orbit.hold_margin, cycle.hold_margin);
    orbit.stick_phases.push_back(system.Phase(cycle.accumulation));
    orbit.release_phases.push_back(system.Phase(cycle.next_release));
    orbit.stuck_durations.push_back(cycle.next_release - cycle.accumulation);
  }
  orbit.jacobian = image.jacobian;
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(s.size());
  shift(map.TimeIndex()) = q * system.ForcingPeriod();
  orbit.residual = (image.state - s - shift).cwiseAbs().maxCoeff();
  orbit.multipliers = SectionMultipliers(map, s, orbit.jacobian);
  orbit.stable = orbit.multipliers.size() == 0 || std::abs(orbit.multipliers(0)) < 1.0;
  return orbit;
}

StickingOrbitSummary FindStickingOrbit(const System& system, const Eigen::VectorXd& guess,
                                       const StickingOrbitOptions& options, StickingOrbit* orbit) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const StickingMap map(system, options.map);
  map.ValidateSection(guess);
  const Eigen::VectorXd seed = map.WithPhase(guess);
  // A state the stop still pushes on is no section state, as an impact
  // state moving away from its stop is none (ImpactMap::ValidateEta).
  const StickingMapStatus first = map.Apply(seed, 1, false).status;
  if (first == StickingMapStatus::kNotReleased) {
    throw InvalidInput("the guess is " + ToString(first));
  }
  const FixedPointProblem problem(map, options.releases, options.q, true);
  const FixedPointSolve solved =
      SolveFixedPoint(problem, seed, options.newton, /*least_squares_fallback=*/false);
  StickingOrbitSummary summary;
  summary.iterations = solved.iterations;
  summary.termination = solved.solve.termination;
  summary.message = solved.solve.message;
  summary.residual = solved.solve.residual_norm;
  if (summary.termination == Termination::kConverged) {
    *orbit = DescribeStickingOrbit(map, solved.x, options.releases, options.q);
  } else {
    orbit->state = solved.x;
  }
  orbit->residual = summary.residual;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace impactkit
