/// `impactkit orbit`: a periodic orbit P(p, q) as a fixed point of the impact
/// map, with its multipliers (impactkit/orbit.hpp does the work), or a
/// sticking orbit P(inf, q) of the release map (orbit/sticking.hpp).

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/orbit_seed.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "orbit/sticking.hpp"

namespace impactkit::cli {
namespace {

struct OrbitRequest {
  SystemOptions system;
  OrbitSeedOptions seed;
  StickingSeedOptions sticking;
  double min_speed = 1e-3;
  std::string json;
  bool check_jacobian = false;
};

void Print(const System& system, const PeriodicOrbit& orbit, const OrbitSummary& summary,
           JacobianMethod summary_jacobian) {
  fmt::print("system:      {}\n", DescribeSystem(system));
  fmt::print("orbit:       P({},{}) at omega = {}, {}\n", orbit.p, orbit.q, orbit.omega,
             orbit.stable ? "stable" : "unstable");
  if (system.StopCount() == 1) {
    fmt::print("impacts:     phase (t mod T, T = {:.6g})   velocity v{}(t-)\n",
               system.ForcingPeriod(), system.stops[0].dof + 1);
    for (const OrbitImpact& i : orbit.impacts) {
      fmt::print("             {:<28.12f} {:.12f}\n", i.phase, i.velocity);
    }
  } else {
    fmt::print("impacts:     phase (t mod T, T = {:.6g})   speed            stop\n",
               system.ForcingPeriod());
    for (const OrbitImpact& i : orbit.impacts) {
      const StopParameters& stop = system.stops[i.stop];
      fmt::print("             {:<28.12f} {:<16.12f} {} (x{} {} {:.6g})\n", i.phase, i.velocity,
                 i.stop + 1, stop.dof + 1,
                 stop.side == StopSide::kUpper ? "<=" : ">=", stop.position);
    }
  }
  fmt::print("multipliers: real                 imag                 modulus\n");
  for (const std::complex<double>& m : orbit.multipliers) {
    fmt::print("             {:<+20.12e} {:<+20.12e} {:.12f}\n", m.real(), m.imag(), std::abs(m));
  }
  fmt::print("jacobian:    {}\n", ToString(summary_jacobian));
  fmt::print("solve:       {}\n", summary.BriefReport());
}

nlohmann::json OrbitJson(const System& system, const PeriodicOrbit& orbit,
                         const OrbitSummary& summary) {
  nlohmann::json j;
  j["kind"] = "impact";
  j["p"] = orbit.p;
  j["q"] = orbit.q;
  j["omega"] = orbit.omega;
  j["stable"] = orbit.stable;
  j["residual"] = orbit.residual;
  j["iterations"] = summary.iterations;
  j["least_squares_fallback"] = summary.used_fallback;
  j["fixed_time_formulation"] = summary.used_shooting;
  j["unresolved_impacts"] = summary.unresolved_impacts;
  j["impacts"] = nlohmann::json::array();
  for (const OrbitImpact& i : orbit.impacts) {
    j["impacts"].push_back(
        {{"t", i.t}, {"phase", i.phase}, {"velocity", i.velocity}, {"stop", i.stop + 1}});
  }
  j["multipliers"] = nlohmann::json::array();
  for (const std::complex<double>& m : orbit.multipliers) {
    j["multipliers"].push_back({m.real(), m.imag()});
  }
  j["eta"] = std::vector<double>(orbit.eta.data(), orbit.eta.data() + orbit.eta.size());
  j["system"] = nlohmann::json::parse(SystemToJson(system));
  return j;
}

void RunOrbit(const OrbitRequest& request) {
  const System system = ResolveSystem(request.system);
  std::optional<AtomicOutputFile> json;  // created first: a bad path fails before the work
  if (!request.json.empty()) json.emplace(request.json);
  const StartOrbit start = SolveStartOrbit(
      system, StartRequest(system, request.seed, request.sticking, StartOrbitKind::kAny));
  const PeriodicOrbit& orbit = start.orbit;
  const OrbitSummary& summary = start.summary;
  const OrbitOptions& options = start.options;
  if (orbit.Sticks()) {
    ReportStickingOrbit(system, orbit, summary, request.min_speed, request.check_jacobian,
                        json ? &*json : nullptr, request.json, request.system);
    return;
  }
  Print(system, orbit, summary, options.jacobian);
  std::optional<JacobianComparison> check;
  if (request.check_jacobian) {
    check = CompareJacobians(ImpactMap(system, options.map), orbit.eta, orbit.p);
    fmt::print(
        "check:       analytic vs finite-difference Jacobian: largest difference {:.3e} "
        "({:.3e} relative to its largest entry)\n",
        check->max_difference, check->max_relative_difference);
  }
  if (json) {
    nlohmann::json j = OrbitJson(system, orbit, summary);
    j["provenance"] = MakeProvenance(request.system, system,
                                     fmt::format("orbit --p {} --q {} --jacobian {}", orbit.p,
                                                 orbit.q, ToString(options.jacobian)))
                          .Json();
    j["jacobian"] = ToString(options.jacobian);
    if (check) {
      j["jacobian_check"] = {{"max_difference", check->max_difference},
                             {"max_relative_difference", check->max_relative_difference}};
    }
    json->Write(j.dump(2) + "\n");
    json->Commit();
    fmt::print("wrote:       {}\n", request.json);
  }
}

}  // namespace

void AddOrbitCommand(CLI::App& app) {
  auto request = std::make_shared<OrbitRequest>();
  CLI::App* command = app.add_subcommand(
      "orbit",
      "Find a periodic orbit P(p,q) (p impacts in q forcing periods) as a fixed point of the "
      "impact map by Newton's method (KINSOL; Levenberg-Marquardt through Ceres as fallback), "
      "and its multipliers and stability. Without --p/--q the system is simulated to steady "
      "state and the motion found there is refined: a sticking motion into a sticking orbit "
      "P(inf,q), a fixed point of the map from one release of the contact mass to the next.");
  AddSystemOptions(*command, request->system);
  AddOrbitSeedOptions(*command, request->seed, "Orbit");
  AddStickingSeedOptions(*command, request->sticking, "Orbit");
  command
      ->add_option("--min-speed", request->min_speed,
                   "Sticking orbits: list the impacts before each accumulation faster than this")
      ->type_name("V")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->group("Output");
  command
      ->add_option("--json", request->json,
                   "Write the orbit as JSON: kind (impact), p, q, omega, impacts [{t, phase, v}], "
                   "multipliers [[re, im]], stable, residual, iterations, eta, system, jacobian "
                   "(the method), jacobian_check (with --check-jacobian); for a sticking orbit "
                   "kind (sticking), stop (1-based), q, releases, stick_phases, release_phases, "
                   "stuck_durations, chatter [{impacts, accumulation, contact_force, "
                   "fast_impacts [{t, phase, v, stop}]}], multipliers, stable, state")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_flag("--check-jacobian", request->check_jacobian,
                 "Also form the finite-difference Jacobian at the orbit and print its largest "
                 "difference from the analytic one")
      ->group("Output");
  command->callback([request] { RunOrbit(*request); });
}

}  // namespace impactkit::cli
