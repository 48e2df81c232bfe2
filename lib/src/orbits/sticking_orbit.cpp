#include "impactkit/orbits/sticking_orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace impactkit {
namespace {

/// The same section state with t moved into [0, T): the map commutes with
/// shifts by T, and small times keep event times precise.
Eigen::VectorXd WithPhase(const StickingMap& map, Eigen::VectorXd s) {
  s(map.TimeIndex()) = map.GetSystem().Phase(s(map.TimeIndex()));
  return s;
}

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
  return fmt::format("{}: residual {:.2e} after {} iterations, {:.3g} s{}", ToString(termination),
                     residual, iterations, seconds, message.empty() ? "" : " (" + message + ")");
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
  const double shift = options.q * system.ForcingPeriod();
  const int k = options.releases;
  Eigen::VectorXd s = WithPhase(map, guess);
  ApplyOrThrow(map, s, k);  // a guess that does not release or stick again is bad input

  // Newton asks for the Jacobian where it has just asked for the residual:
  // the analytic one costs little beside the map, so both come at once.
  Eigen::VectorXd cached_at;
  Eigen::MatrixXd cached_jacobian;
  const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* u) {
    const StickingMapResult image = map.Apply(x, k, true);
    if (image.status != StickingMapStatus::kOk) return false;
    cached_at = x;
    cached_jacobian = image.jacobian;
    *u = image.state - x;
    (*u)(map.TimeIndex()) -= shift;
    return u->allFinite();
  };
  const Jacobian jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    if (cached_at.size() == x.size() && cached_at == x) {
      *j = cached_jacobian;
    } else {
      const StickingMapResult image = map.Apply(x, k, true);
      if (image.status != StickingMapStatus::kOk) return false;
      *j = image.jacobian;
    }
    j->diagonal().array() -= 1.0;
    return j->allFinite();
  };
  const SolveSummary solve = SolveNewton(residual, jacobian, options.newton, &s);
  StickingOrbitSummary summary;
  summary.iterations = solve.iterations;
  summary.termination = solve.termination;
  summary.message = solve.message;
  summary.residual = solve.residual_norm;
  s = WithPhase(map, s);
  if (summary.termination == Termination::kConverged) {
    *orbit = DescribeStickingOrbit(map, s, k, options.q);
  } else {
    orbit->state = s;
  }
  orbit->residual = solve.residual_norm;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace impactkit
