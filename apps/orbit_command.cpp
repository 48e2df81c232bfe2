/// `impactkit orbit`: a periodic orbit P(p, q) as a fixed point of the impact
/// map, with its multipliers (impactkit/orbit.hpp does the work).

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "impactkit/orbit.hpp"
#include "impactkit/output_file.hpp"
#include "impactkit/system_file.hpp"
#include "system_options.hpp"

namespace impactkit::cli {
namespace {

struct OrbitRequest {
  SystemOptions system;
  std::optional<int> p, q;
  std::vector<double> guess;
  int transient = 500;
  std::string jacobian = "analytic";
  bool no_fallback = false;
  std::string json;
};

/// The seed: the user's guess, or the last impact of a steady simulation
/// (whose P(p, q) is used unless the user gave p and q).
OrbitOptions ChooseSeed(const System& system, const OrbitRequest& request, Eigen::VectorXd* eta) {
  OrbitOptions options;
  if (request.p.has_value() != request.q.has_value()) {
    throw InvalidInput("--p and --q go together: give both, or neither to detect them");
  }
  if (!request.guess.empty()) {
    if (!request.p) throw InvalidInput("--guess needs --p and --q");
    *eta = Eigen::Map<const Eigen::VectorXd>(request.guess.data(),
                                             static_cast<Eigen::Index>(request.guess.size()));
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
    options.p = static_cast<int>(seed->motion.p);
    options.q = seed->motion.q;
  }
  if (request.p) {
    options.p = *request.p;
    options.q = *request.q;
  }
  options.jacobian = request.jacobian == "fd" ? JacobianMethod::kFiniteDifference
                                              : JacobianMethod::kAnalytic;
  options.least_squares_fallback = !request.no_fallback;
  return options;
}

void Print(const System& system, const PeriodicOrbit& orbit, const OrbitSummary& summary) {
  fmt::print("system:      {}\n", DescribeSystem(system));
  fmt::print("orbit:       P({},{}) at omega = {}, {}\n", orbit.p, orbit.q, orbit.omega,
             orbit.stable ? "stable" : "unstable");
  fmt::print("impacts:     phase (t mod T, T = {:.6g})   velocity v{}(t-)\n",
             system.ForcingPeriod(), system.contact_dof + 1);
  for (const OrbitImpact& i : orbit.impacts) {
    fmt::print("             {:<28.12f} {:.12f}\n", i.phase, i.velocity);
  }
  fmt::print("multipliers: real                 imag                 modulus\n");
  for (const std::complex<double>& m : orbit.multipliers) {
    fmt::print("             {:<+20.12e} {:<+20.12e} {:.12f}\n", m.real(), m.imag(), std::abs(m));
  }
  fmt::print("solve:       {}\n", summary.BriefReport());
}

std::string OrbitJson(const System& system, const PeriodicOrbit& orbit,
                      const OrbitSummary& summary) {
  nlohmann::json j;
  j["p"] = orbit.p;
  j["q"] = orbit.q;
  j["omega"] = orbit.omega;
  j["stable"] = orbit.stable;
  j["residual"] = orbit.residual;
  j["iterations"] = summary.iterations;
  j["least_squares_fallback"] = summary.used_fallback;
  j["impacts"] = nlohmann::json::array();
  for (const OrbitImpact& i : orbit.impacts) {
    j["impacts"].push_back({{"t", i.t}, {"phase", i.phase}, {"v", i.velocity}});
  }
  j["multipliers"] = nlohmann::json::array();
  for (const std::complex<double>& m : orbit.multipliers) {
    j["multipliers"].push_back({m.real(), m.imag()});
  }
  j["eta"] = std::vector<double>(orbit.eta.data(), orbit.eta.data() + orbit.eta.size());
  j["system"] = nlohmann::json::parse(SystemToJson(system));
  return j.dump(2) + "\n";
}

void RunOrbit(const OrbitRequest& request) {
  const System system = ResolveSystem(request.system);
  if (request.transient < 0) throw InvalidInput("--transient must be >= 0");
  std::optional<AtomicOutputFile> json;  // created first: a bad path fails before the work
  if (!request.json.empty()) json.emplace(request.json);
  Eigen::VectorXd eta;
  const OrbitOptions options = ChooseSeed(system, request, &eta);
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(system, eta, options, &orbit);
  if (summary.termination != OrbitTermination::kConverged) {
    throw std::runtime_error(fmt::format("no P({},{}) orbit found: {}", options.p, options.q,
                                         summary.BriefReport()));
  }
  Print(system, orbit, summary);
  if (json) {
    json->Write(OrbitJson(system, orbit, summary));
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
      "state and the motion found there is refined.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Orbit";
  command->add_option("--p", request->p, "Impacts per orbit (with --q)")->type_name("P")->group(group);
  command->add_option("--q", request->q, "Forcing periods per orbit (with --p)")->type_name("Q")->group(group);
  command
      ->add_option("--guess", request->guess,
                   "Initial guess eta = x1..xN without the contact mass, t, v1..vN, just before "
                   "an impact (v of the contact mass > 0); default: from simulation")
      ->type_name("X,...,T,V,...")
      ->delimiter(',')
      ->group(group);
  command
      ->add_option("--transient", request->transient,
                   "Forcing periods simulated from rest before seeding from the motion")
      ->type_name("N")
      ->capture_default_str()
      ->group(group);
  command
      ->add_option("--jacobian", request->jacobian,
                   "Jacobian of the map: 'analytic' (saltation matrices) or 'fd' (finite "
                   "differences, the paper's method)")
      ->check(CLI::IsMember({"analytic", "fd"}))
      ->capture_default_str()
      ->group(group);
  command->add_flag("--no-fallback", request->no_fallback,
                    "Do not try Levenberg-Marquardt when Newton fails")
      ->group(group);
  command
      ->add_option("--json", request->json,
                   "Write the orbit as JSON: p, q, omega, impacts [{t, phase, v}], multipliers "
                   "[[re, im]], stable, residual, iterations, eta, system")
      ->type_name("FILE.json")
      ->group("Output");
  command->callback([request] { RunOrbit(*request); });
}

}  // namespace impactkit::cli
