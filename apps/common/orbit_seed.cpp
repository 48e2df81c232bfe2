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

void AddStickingSeedOptions(CLI::App& command, StickingSeedOptions& options,
                            const std::string& group) {
  command
      .add_flag("--sticking", options.sticking,
                "Start from a sticking orbit P(inf,q): from the steady simulation, or from "
                "--guess (a release state: x and v of the other masses, then t) with --q")
      ->group(group);
  command
      .add_option("--releases", options.releases,
                  "With --sticking --guess: sticking phases per orbit")
      ->type_name("K")
      ->check(CLI::Range(1, static_cast<int>(kMaxOrbitPeriod)))
      ->capture_default_str()
      ->group(group);
}

namespace {

/// The 0-based stop of a --guess: --stop K, or the first.
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

/// What to try when no orbit converged from the seed: the solver's report
/// says only why it stopped, not what the user can change.
std::string OrbitSearchHint(const StartOrbitRequest& request) {
  const std::string elsewhere =
      "or find the orbit where it exists and follow it here with `impactkit continue`";
  if (request.guess) {
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

StartOrbitRequest StartRequest(const System& system, const OrbitSeedOptions& seed,
                               const StickingSeedOptions& sticking, StartOrbitKind kind) {
  StartOrbitRequest request;
  request.kind = sticking.sticking ? StartOrbitKind::kSticking : kind;
  request.p = seed.p;
  request.q = seed.q;
  request.stop = GuessStop(system, seed);
  if (!seed.guess.empty()) {
    request.guess = Eigen::Map<const Eigen::VectorXd>(seed.guess.data(),
                                                      static_cast<Eigen::Index>(seed.guess.size()));
    if (sticking.sticking) request.releases = sticking.releases;
  }
  request.transient = seed.transient;
  request.solver.jacobian =
      seed.jacobian == "fd" ? JacobianMethod::kFiniteDifference : JacobianMethod::kAnalytic;
  request.solver.least_squares_fallback = !seed.no_fallback;
  return request;
}

StartOrbit SolveStartOrbit(const System& system, const StartOrbitRequest& request) {
  StartOrbit start = FindStartOrbit(system, request);
  if (!start.seeded) throw std::runtime_error(start.summary.message);
  if (start.summary.termination != Termination::kConverged) {
    const OrbitOptions& o = start.options;
    throw std::runtime_error(fmt::format(
        "no {} orbit found ({}); {}",
        o.releases > 0 ? fmt::format("sticking P(inf,{})", o.q) : fmt::format("P({},{})", o.p, o.q),
        start.summary.BriefReport(), OrbitSearchHint(request)));
  }
  return start;
}

}  // namespace impactkit::cli
