#include "impactkit/orbits/sticking_orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "orbits/fixed_point.hpp"

namespace impactkit {
namespace {

StickingMapResult ApplyOrThrow(const StickingMap& map, const Eigen::VectorXd& s, int k,
                               bool with_contacts = false) {
  StickingMapResult image = map.Apply(s, k, true, with_contacts);
  if (image.termination != Termination::kCompleted) {
    throw InvalidInput(
        fmt::format("no sticking orbit through this release state: after {} of {} releases, {}",
                    image.cycles_done, k, Describe(image.termination)));
  }
  return image;
}

}  // namespace

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
  return SortedByModulus(lambda);
}

PeriodicOrbit DescribeStickingOrbit(const StickingMap& map, const Eigen::VectorXd& s, int releases,
                                    int q, JacobianMethod method) {
  const StickingMapResult image = ApplyOrThrow(map, s, releases, true);
  const System& system = map.GetSystem();
  PeriodicOrbit orbit;
  orbit.section = OrbitSection::kRelease;
  orbit.stop = map.SectionStop();
  orbit.releases = releases;
  orbit.q = q;
  orbit.omega = system.omega;
  orbit.eta = s;
  OrbitContacts& contacts = orbit.contacts;
  contacts.slowest_depth = std::numeric_limits<double>::infinity();
  contacts.contact_min = contacts.contact_max = system.stops[orbit.stop].position;
  double clearance = std::numeric_limits<double>::infinity();
  for (const StickingCycle& cycle : image.cycles) {
    for (const StickingImpact& impact : cycle.impacts) {
      orbit.impacts.push_back({impact.t, system.Phase(impact.t), impact.velocity, impact.stop});
    }
    orbit.stuck.push_back({cycle.stop, cycle.accumulation, system.Phase(cycle.accumulation),
                           cycle.next_release, system.Phase(cycle.next_release),
                           cycle.contact_force, cycle.hold_margin,
                           static_cast<int>(cycle.impacts.size())});
    contacts.contact_min = std::min(contacts.contact_min, cycle.contact_min);
    contacts.contact_max = std::max(contacts.contact_max, cycle.contact_max);
    contacts.contact_margin = std::min(contacts.contact_margin, cycle.contact_force);
    contacts.hold_margin = std::min(contacts.hold_margin, cycle.hold_margin);
    if (cycle.clearance < clearance) {
      clearance = cycle.clearance;
      contacts.clearance_time = cycle.clearance_time;
      contacts.clearance_stop = cycle.clearance_stop;
    }
    for (std::size_t i = 0; i < cycle.impacts.size(); ++i) {
      if (i == 0 || cycle.impacts[i].stop != cycle.stop) {
        contacts.approach_impact_speed =
            std::min(contacts.approach_impact_speed, cycle.impacts[i].velocity);
      }
    }
  }
  if (std::isfinite(clearance)) contacts.clearance = clearance;
  orbit.p = static_cast<int>(orbit.impacts.size());
  orbit.jacobian = method == JacobianMethod::kAnalytic ? image.jacobian
                                                       : FiniteDifferenceJacobian(map, s, releases);
  if (orbit.jacobian.size() == 0) {
    throw InvalidInput(
        "the finite-difference Jacobian cannot be formed here: a perturbed map does not stick");
  }
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(s.size());
  shift(map.TimeIndex()) = q * system.ForcingPeriod();
  orbit.residual = (image.state - s - shift).cwiseAbs().maxCoeff();
  orbit.multipliers = SectionMultipliers(map, s, orbit.jacobian);
  orbit.stable = orbit.multipliers.size() == 0 || std::abs(orbit.multipliers(0)) < 1.0;
  return orbit;
}

OrbitSummary FindStickingOrbit(const System& system, const Eigen::VectorXd& guess,
                               const OrbitOptions& options, PeriodicOrbit* orbit) {
  const StickingMap map(system, options.release_map);
  map.ValidateSection(guess);
  const Eigen::VectorXd seed = map.WithPhase(guess);
  // A state the stop still pushes on is no section state, as an impact
  // state moving away from its stop is none (ImpactMap::ValidateEta).
  const Termination first = map.Apply(seed, 1, false).termination;
  if (first == Termination::kNotReleased) {
    throw InvalidInput("the guess is " + Describe(first));
  }
  const FixedPointProblem problem(map, options.releases, options.q,
                                  options.jacobian == JacobianMethod::kAnalytic);
  const FixedPointSolve solved =
      SolveFixedPoint(problem, seed, options.newton, options.least_squares_fallback);
  OrbitSummary summary;
  summary.iterations = solved.iterations;
  summary.used_fallback = solved.used_fallback;
  summary.termination = solved.solve.termination;
  summary.message = solved.solve.message;
  summary.residual = solved.solve.residual_norm;
  if (summary.termination == Termination::kConverged) {
    try {
      *orbit = DescribeStickingOrbit(map, solved.x, options.releases, options.q, options.jacobian);
    } catch (const InvalidInput& e) {
      // The fixed point holds, but a perturbed map does not stick: no
      // finite-difference Jacobian there.
      summary.termination = Termination::kFailure;
      summary.message = e.what();
    }
  } else {
    orbit->eta = solved.x;
    orbit->section = OrbitSection::kRelease;
    orbit->stop = map.SectionStop();
  }
  orbit->residual = summary.residual;
  return summary;
}

}  // namespace impactkit
