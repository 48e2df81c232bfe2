/// `impactkit diagram`: the connected bifurcation diagram over a parameter
/// range — a brute-force sweep, refined where the motion changes, whose
/// periodic and sticking windows seed branches, and
/// the network of branches traced from them through their period
/// doublings, grazings and branch points (impactkit/analysis/
/// swept_diagram.hpp does the work).

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "common/arclength_flags.hpp"
#include "common/branches.hpp"
#include "common/limits.hpp"
#include "common/orbit_seed.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "diagram/output.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/grazing_output.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"

namespace impactkit::cli {
namespace {

/// The library's recipe: its sweep and refinement are the defaults here.
const SweptDiagramOptions kRecipe;

struct DiagramRequest {
  SystemOptions system;
  OrbitSeedOptions seed;
  StickingSeedOptions sticking;
  std::string parameter = "omega";
  double from = 0.1, to = 2.5;
  std::optional<double> start;
  double step = ContinuationOptions{}.initial_step, max_step = ContinuationOptions{}.max_step;
  int max_points = ContinuationOptions{}.max_points;
  int max_depth = DiagramOptions{}.max_depth, max_branches = DiagramOptions{}.max_branches;
  int sweep_values = kRecipe.sweep.steps, sweep_transient = kRecipe.sweep.transient_periods,
      sweep_record = kRecipe.sweep.recorded_periods, max_q = kRecipe.sweep.classify.period.max_q;
  int refine = kRecipe.refine.factor;
  int threads = 0;  ///< 0: all cores
  std::string json, plot, grazings, axis = "velocity";
};

/// The system at --from (or --start), after the checks that need no work.
System DiagramSystem(const DiagramRequest& request) {
  Require(request.from != request.to,
          fmt::format("--from and --to must differ (both {})", request.from));
  System system = ResolveSystem(request.system);
  GetParameter(system, request.parameter);  // an unknown name fails here, naming the choices
  RequireNotSet(request.system, request.parameter, "--param", "--from, --to and --start");
  const double lower = std::min(request.from, request.to);
  const double upper = std::max(request.from, request.to);
  Require(!request.start || (*request.start >= lower && *request.start <= upper),
          fmt::format("--start {} is not between --from and --to", request.start.value_or(0)));
  for (double bound : {lower, upper}) {
    System at = system;
    SetParameter(at, request.parameter, bound);
    try {
      Validate(at);
    } catch (const InvalidInput& e) {
      throw InvalidInput(
          fmt::format("{} = {} is not valid: {}", request.parameter, bound, e.what()));
    }
  }
  SetParameter(system, request.parameter, request.start.value_or(lower));
  return system;
}

SweptDiagramOptions MakeOptions(const DiagramRequest& request) {
  Require(request.sweep_values >= 0, "--sweep-values must be >= 0 (0: no sweep seeds)");
  Require(request.sweep_values > 0 || request.start.has_value(),
          "--sweep-values 0 leaves no seed: give --start");
  Require(request.threads >= 0, "--threads must be >= 0 (0: all cores)");
  Require(request.max_depth >= 0,
          fmt::format("--max-depth must be >= 0, got {}", request.max_depth));
  Require(request.max_branches >= 1,
          fmt::format("--max-branches must be >= 1, got {}", request.max_branches));
  const int threads = request.threads > 0
                          ? request.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  SweptDiagramOptions options;
  ContinuationOptions& c = options.diagram.continuation;
  c.parameter = request.parameter;
  c.from = std::min(request.from, request.to);
  c.to = std::max(request.from, request.to);
  RequireArclengthFlags(std::min(request.step, request.max_step), c.min_step, request.max_step,
                        request.max_points, "the smallest step");
  c.initial_step = std::min(request.step, request.max_step);
  c.max_step = request.max_step;
  c.max_points = request.max_points;
  options.diagram.max_depth = request.max_depth;
  options.diagram.max_branches = request.max_branches;
  options.diagram.threads = threads;
  options.sweep.steps = std::max(1, request.sweep_values);
  options.sweep.transient_periods = request.sweep_transient;
  options.sweep.recorded_periods = request.sweep_record;
  options.sweep.classify.period.max_q = request.max_q;
  options.sweep.threads = threads;
  options.refine.factor = request.refine;
  // One flag bounds the windows seeded: no longer period than the sweep
  // looks for, and no more impacts per orbit than that.
  options.seeds.max_p = request.max_q;
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  return options;
}

/// The command that made a diagram's files.
Provenance DiagramProvenance(const DiagramRequest& request, const System& system) {
  return MakeProvenance(request.system, system,
                        fmt::format("diagram --param {} --from {} --to {} --max-depth {} "
                                    "--sweep-values {} --refine {} --max-q {}",
                                    request.parameter, request.from, request.to, request.max_depth,
                                    request.sweep_values, request.refine, request.max_q));
}

void RunDiagram(const DiagramRequest& request) {
  const System system = DiagramSystem(request);
  SweptDiagramOptions options = MakeOptions(request);
  Require(request.axis == "velocity" || request.axis == "range",
          fmt::format("--axis must be velocity or range, got '{}'", request.axis));
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;
  AtomicOutputFile* json = AddIfAsked(outputs, request.json);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);
  AtomicOutputFile* grazings = AddIfAsked(outputs, request.grazings);
  std::vector<DiagramSeed> seeds;
  if (request.start) {
    const StartOrbit found = SolveStartOrbit(
        system, StartRequest(system, request.seed, request.sticking, StartOrbitKind::kAny));
    options.seeds.orbit = found.options;
    seeds.push_back(
        {system, found.orbit, fmt::format("start at {} = {}", request.parameter, *request.start)});
  }
  fmt::print("system:     {}\n", DescribeSystem(system));
  SweptDiagram swept;
  if (request.sweep_values == 0) {
    const RunProgress progress(request.parameter);
    swept.seeds = seeds;
    swept.diagram = TraceDiagram(seeds, options.diagram, progress.Control());
  } else {
    {
      const RunProgress progress(request.parameter);
      swept = TraceSweptDiagram(system, seeds, options, progress.Control());
    }
    fmt::print("sweep:      {}\n", swept.sweep.BriefReport());
    if (swept.refined_values > 0) {
      fmt::print("refined:    {} values where the motion changes or has no period\n",
                 swept.refined_values);
    }
  }
  PredictGrazings(system, &swept.diagram);
  fmt::print("seeds:      {}\n", swept.seeds.size());
  PrintDiagram(swept.diagram);
  std::vector<std::string> written;
  if (grazings) {
    const std::vector<GrazingCheck> checks = CheckGrazings(system, swept.diagram);
    fmt::print("grazings checked by sweeps both ways ({}):\n", checks.size());
    for (const GrazingCheck& check : checks) {
      fmt::print("  {}\n", DescribeGrazingCheck(check, request.parameter));
    }
    nlohmann::json j = nlohmann::json::parse(GrazingChecksJson(checks, request.parameter));
    j["provenance"] = DiagramProvenance(request, system).Json();
    grazings->Write(j.dump(2) + "\n");
    written.push_back(request.grazings);
  }
  if (json) {
    nlohmann::json j = nlohmann::json::parse(DiagramJson(swept.diagram));
    j["provenance"] = DiagramProvenance(request, system).Json();
    j["system"] = nlohmann::json::parse(SystemToJson(system));
    json->Write(j.dump(2) + "\n");
    written.push_back(request.json);
  }
  if (plot) {
    const DiagramAxis axis =
        request.axis == "range" ? DiagramAxis::kRange : DiagramAxis::kImpactVelocity;
    plot->Write(RenderDiagram(DiagramFigure(swept, axis), ImageFormatOf(plot->Path())));
    written.push_back(request.plot);
  }
  outputs.Commit();
  for (const std::string& path : written) fmt::print("wrote:      {}\n", path);
}

}  // namespace

void AddDiagramCommand(CLI::App& app) {
  auto request = std::make_shared<DiagramRequest>();
  CLI::App* command = app.add_subcommand(
      "diagram",
      "The connected bifurcation diagram over a parameter range: a brute-force sweep, swept "
      "again finer where the motion changes, whose periodic and sticking windows seed "
      "branches, each followed both ways, and at every "
      "period doubling, grazing and branch point the branch that starts there, each branch "
      "once. Prints every branch and special point in parameter order.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Diagram";
  command->add_option("--param", request->parameter, "Parameter: omega, xs, r, A1.., m, k, c")
      ->capture_default_str()
      ->group(group);
  command->add_option("--from", request->from, "One end of the range")
      ->capture_default_str()
      ->group(group);
  command->add_option("--to", request->to, "The other end")->capture_default_str()->group(group);
  command
      ->add_option("--start", request->start,
                   "Also seed the orbit found at this value (as `impactkit orbit` finds it)")
      ->group(group);
  command->add_option("--step", request->step, "Initial arclength step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-step", request->max_step, "Largest arclength step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-points", request->max_points, "Points per branch direction at most")
      ->check(AtMost(kMaxBranchPoints, "points"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-depth", request->max_depth, "Switches from a seed's branch at most")
      ->check(AtMost(kMaxOrbitPeriod, "switches"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-branches", request->max_branches, "Branches traced at most")
      ->check(AtMost(kMaxSteps, "branches"))
      ->capture_default_str()
      ->group(group);
  command
      ->add_option("--sweep-values", request->sweep_values,
                   "Values of the seeding sweep before --refine (0: no sweep; then --start seeds)")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--sweep-transient", request->sweep_transient, "Sweep transient periods")
      ->check(AtMost(kMaxPeriods, "periods"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--sweep-record", request->sweep_record, "Sweep recorded periods")
      ->check(AtMost(kMaxPeriods, "periods"))
      ->capture_default_str()
      ->group(group);
  command
      ->add_option("--refine", request->refine,
                   "Values per sweep interval after refining it where the neighbours' motions "
                   "differ or have no period (chaotic, unresolved), so that windows narrower "
                   "than the spacing seed branches (1: no refinement)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-q", request->max_q, "Longest period the sweep looks for")
      ->check(AtMost(kMaxOrbitPeriod, "periods"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--threads", request->threads, "Threads (0: all cores)")
      ->check(AtMost(kMaxThreads, "threads"))
      ->capture_default_str()
      ->group(group);
  AddOrbitSeedOptions(*command, request->seed, "Start orbit (--start)");
  AddStickingSeedOptions(*command, request->sticking, "Start orbit (--start)");
  command
      ->add_option("--json", request->json,
                   "JSON: nodes [{type, param, multipliers, ...}], edges [{from, to, points}], "
                   "branches")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_option("--plot", request->plot,
                   "Figure: the branches (stable solid, unstable dashed), nodes marked by type, "
                   "over the sweep's points (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command
      ->add_option("--grazings", request->grazings,
                   "JSON: every grazing's prediction checked by sweeps both ways through it "
                   "(grazings [{param, grazing_orbit, contact, prediction, sweeps}]; "
                   "docs/continuation.md, 'What a grazing will do')")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command->add_option("--axis", request->axis, "What --plot shows: velocity or range (of x_N)")
      ->capture_default_str()
      ->group("Output");
  command->callback([request] { RunDiagram(*request); });
}

}  // namespace impactkit::cli
