#include "common/orbit_seed.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "common/limits.hpp"

namespace impactkit::cli {

void AddOrbitSeedOptions(CLI::App& command, OrbitSeedOptions& options, const std::string& group) {
  command
      .add_option(
          "--p", options.p,
          "Impacts per orbit (with --q); default: those of the motion a simulation settles on")
      ->type_name("P")
      ->check(AtMost(kMaxOrbitPeriod, "impacts"))
      ->group(group);
  command
      .add_option("--q", options.q,
                  "Forcing periods per orbit (with --p); default: from the simulation, as --p")
      ->type_name("Q")
      ->check(AtMost(kMaxOrbitPeriod, "forcing periods"))
      ->group(group);
  command
      .add_option("--guess", options.guess,
                  "Initial guess eta = x1..xN without the contact mass, t, v1..vN, just before "
                  "an impact (v of the contact mass > 0); default: from simulation")
      ->type_name("X,...,T,V,...")
      ->delimiter(',')
      ->group(group);
  command
      .add_option("--stop", options.stop,
                  "With --guess and several stops: the stop (1, 2, ... as in the system file) "
                  "the guess's impact (or, with --sticking, release) is at; its mass is the one "
                  "left out of the guess (default 1)")
      ->type_name("K")
      ->check(CLI::PositiveNumber)
      ->group(group);
  command
      .add_option("--transient", options.transient,
                  "Forcing periods simulated from rest before seeding from the motion")
      ->type_name("N")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--jacobian", options.jacobian,
                  "Jacobian of the map: 'analytic' (saltation matrices) or 'fd' (finite "
                  "differences, the paper's method)")
      ->check(CLI::IsMember({"analytic", "fd"}))
      ->capture_default_str()
      ->group(group);
  command
      .add_flag("--no-fallback", options.no_fallback,
                "Do not try Levenberg-Marquardt when Newton fails")
      ->group(group);
}

int GuessStop(const System& system, const OrbitSeedOptions& options) {
  if (options.stop && options.guess.empty()) {
    throw InvalidInput("--stop goes with --guess (a seed from simulation knows its stop)");
  }
  const int stop = options.stop.value_or(1);
  if (stop > system.StopCount()) {
    throw InvalidInput(fmt::format("--stop {}: the system has {} stop{}", stop, system.StopCount(),
                                   system.StopCount() == 1 ? "" : "s"));
  }
  return stop - 1;
}

OrbitOptions ChooseSeed(const System& system, const OrbitSeedOptions& request,
                        Eigen::VectorXd* eta) {
  if (request.transient < 0) throw InvalidInput("--transient must be >= 0");
  OrbitOptions options;
  if (request.p.has_value() != request.q.has_value()) {
    throw InvalidInput("--p and --q go together: give both, or neither to detect them");
  }
  const int stop = GuessStop(system, request);
  if (!request.guess.empty()) {
    if (!request.p) throw InvalidInput("--guess needs --p and --q");
    *eta = Eigen::Map<const Eigen::VectorXd>(request.guess.data(),
                                             static_cast<Eigen::Index>(request.guess.size()));
    options.map.stop = stop;
  } else {
    const std::optional<OrbitSeed> seed = SeedFromSimulation(system, request.transient);
    if (!seed) throw std::runtime_error("the simulated motion has no impacts: no orbit to refine");
    if (!request.p && (!seed->motion.periodic || seed->motion.sticking)) {
      throw std::runtime_error(fmt::format(
          "the simulated motion is {}; give --p and --q (and --guess) to look for an orbit",
          seed->motion.sticking ? "sticking (an impact map orbit cannot stick)"
                                : seed->motion.ToString()));
    }
    *eta = seed->eta;
    options.map.stop = seed->stop;
    options.p = static_cast<int>(seed->motion.p);
    options.q = seed->motion.q;
  }
  if (request.p) {
    options.p = *request.p;
    options.q = *request.q;
  }
  options.jacobian =
      request.jacobian == "fd" ? JacobianMethod::kFiniteDifference : JacobianMethod::kAnalytic;
  options.least_squares_fallback = !request.no_fallback;
  return options;
}

namespace {

/// What to try when no orbit converged from the seed: the solver's report
/// says only why it stopped, not what the user can change.
std::string OrbitSearchHint(const OrbitSeedOptions& request) {
  const std::string elsewhere =
      "or find the orbit where it exists and follow it here with `impactkit continue`";
  if (!request.guess.empty()) {
    return "the guess may be too far from an orbit: take one from an impact of `impactkit "
           "simulate` at this value, " +
           elsewhere;
  }
  if (request.p) {
    return "the motion simulated here may not be this period: see it with `impactkit "
           "simulate`, give a --guess, " +
           elsewhere;
  }
  return "the simulated motion may not have settled: try a longer --transient, " + elsewhere;
}

}  // namespace

PeriodicOrbit FindStartOrbit(const System& system, const OrbitSeedOptions& seed,
                             OrbitOptions* options, OrbitSummary* summary) {
  Eigen::VectorXd eta;
  *options = ChooseSeed(system, seed, &eta);
  PeriodicOrbit orbit;
  const OrbitSummary result = FindOrbit(system, eta, *options, &orbit);
  if (result.termination != Termination::kConverged) {
    throw std::runtime_error(fmt::format("no P({},{}) orbit found ({}); {}", options->p, options->q,
                                         result.BriefReport(), OrbitSearchHint(seed)));
  }
  if (summary) *summary = result;
  return orbit;
}

}  // namespace impactkit::cli
