/// `impactkit continue`: pseudo-arclength continuation of a P(p, q) branch in
/// one parameter, its special points, and optionally the branches that
/// start at them (impactkit/continuation.hpp does the work).

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

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
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/continuation/diagram.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"

namespace impactkit::cli {
namespace {

struct ContinueRequest {
  SystemOptions system;
  OrbitSeedOptions seed;
  StickingSeedOptions sticking;
  std::string parameter = "omega";
  std::optional<double> from, to, start;
  double step = ContinuationOptions{}.initial_step, min_step = ContinuationOptions{}.min_step,
         max_step = ContinuationOptions{}.max_step;
  int max_points = ContinuationOptions{}.max_points;
  bool switch_period_doubling = false;
  bool follow_grazing = false;
  std::string out, json, plot;
};

ContinuationOptions MakeOptions(const ContinueRequest& request, const OrbitOptions& orbit) {
  RequireArclengthFlags(request.step, request.min_step, request.max_step, request.max_points);
  ContinuationOptions options;
  options.parameter = request.parameter;
  options.from = *request.from;
  options.to = *request.to;
  options.direction = request.start                 ? ContinuationDirection::kBoth
                      : *request.to > *request.from ? ContinuationDirection::kIncreasing
                                                    : ContinuationDirection::kDecreasing;
  options.initial_step = request.step;
  options.min_step = request.min_step;
  options.max_step = request.max_step;
  options.max_points = request.max_points;
  options.orbit = orbit;
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  return options;
}

std::string ContinueJson(const System& system, const std::vector<TracedBranch>& branches,
                         const Provenance& provenance) {
  nlohmann::json j = {{"provenance", provenance.Json()}};
  j.update(BranchJson(branches.front()));
  j["branches"] = nlohmann::json::array();
  for (const TracedBranch& b : branches) j["branches"].push_back(BranchJson(b));
  j["system"] = nlohmann::json::parse(SystemToJson(system));
  return j.dump(2) + "\n";
}

System StartSystem(const ContinueRequest& request) {
  if (*request.from == *request.to) {
    throw InvalidInput(fmt::format("--from and --to must differ (both {})", *request.from));
  }
  System system = ResolveSystem(request.system);
  GetParameter(system, request.parameter);  // an unknown name fails here, naming the choices
  RequireNotSet(request.system, request.parameter, "--param", "--from, --to and --start");
  MakeOptions(request, OrbitOptions{});  // and bad bounds or steps before any work
  const double lower = std::min(*request.from, *request.to);
  const double upper = std::max(*request.from, *request.to);
  if (request.start && !(*request.start >= lower && *request.start <= upper)) {
    throw InvalidInput(fmt::format("--start {} is not between --from and --to", *request.start));
  }
  for (double bound : {lower, upper}) {  // both ends valid before any work
    System at = system;
    SetParameter(at, request.parameter, bound);
    try {
      Validate(at);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("--{} {} = {} is not valid: {}",
                                     bound == *request.from ? "from" : "to", request.parameter,
                                     bound, e.what()));
    }
  }
  SetParameter(system, request.parameter, request.start.value_or(*request.from));
  Validate(system);
  return system;
}

/// What produced the outputs: the system and every setting resolved.
Provenance ProvenanceOf(const ContinueRequest& request, const System& system) {
  return MakeProvenance(
      request.system, system,
      fmt::format("continue --param {} --from {} --to {}{} --step {} --min-step {} --max-step {} "
                  "--max-points {}{}{}",
                  request.parameter, *request.from, *request.to,
                  request.start ? fmt::format(" --start {}", *request.start) : "", request.step,
                  request.min_step, request.max_step, request.max_points,
                  request.switch_period_doubling ? " --switch-pd" : "",
                  request.follow_grazing ? " --follow-grazing" : ""));
}

/// Says what --follow-grazing did where it did nothing visible: no grazing
/// on the branch, or no orbit with one impact more or fewer beside one.
void ReportGrazingFollowed(const std::vector<TracedBranch>& branches) {
  const Branch& main = branches.front().branch;
  const auto grazings =
      std::count_if(main.special_points.begin(), main.special_points.end(), [](const auto& s) {
        return s.type == SpecialPointType::kGrazing || s.type == SpecialPointType::kSticking;
      });
  const auto followed = std::count_if(branches.begin(), branches.end(),
                                      [](const auto& b) { return b.label.starts_with("graze"); });
  if (grazings == 0) {
    fmt::print(
        "note:       --follow-grazing: the branch meets no grazing in this range, so there is "
        "nothing to follow; widen --from/--to, or see where impacts appear with `impactkit "
        "sweep`\n");
  } else if (followed == 0) {
    fmt::print(
        "note:       --follow-grazing: no branch with one impact more or fewer starts at the "
        "branch's {} grazing{} (no orbit found beside it, or it lies outside --from/--to); the "
        "motion past it may be non-periodic (see it with `impactkit sweep`)\n",
        grazings, grazings == 1 ? "" : "s");
  }
}

void RunContinue(const ContinueRequest& request) {
  const System system = StartSystem(request);
  if (!request.plot.empty()) RequireGnuplot();
  // Created first: a bad path fails before the work. The other branches'
  // files go beside --out, whose directory this checks.
  OutputSet outputs;
  AtomicOutputFile* out = AddIfAsked(outputs, request.out);
  AtomicOutputFile* json = AddIfAsked(outputs, request.json);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);
  // A motion that sticks starts its sticking family; any other, the
  // impact map's.
  const StartOrbit found = SolveStartOrbit(
      system, StartRequest(system, request.seed, request.sticking, StartOrbitKind::kAny));
  const PeriodicOrbit& start = found.orbit;
  const ContinuationOptions options = MakeOptions(request, found.options);
  fmt::print("system:     {}\n", DescribeSystem(system));
  fmt::print("start:      {}{} at {} = {}, {}\n", start.Sticks() ? "sticking " : "",
             OrbitName(start), request.parameter, GetParameter(system, request.parameter),
             start.stable ? "stable" : "unstable");
  // The library's network, one switch deep: the branch through the start
  // and those born at its special points as the flags ask.
  DiagramOptions network;
  network.continuation = options;
  network.switch_period_doubling = request.switch_period_doubling;
  network.switch_grazing = request.follow_grazing;
  network.switch_branch_points = false;
  network.max_depth = request.switch_period_doubling || request.follow_grazing ? 1 : 0;
  std::vector<TracedBranch> branches;
  {
    const RunProgress progress(request.parameter);
    Diagram traced = TraceDiagram({{system, start, "from the start", options.direction}}, network,
                                  progress.Control());
    PredictGrazings(system, &traced);
    branches = LabelBranches(traced);
  }
  for (const TracedBranch& b : branches) PrintBranch(b);
  if (request.follow_grazing) ReportGrazingFollowed(branches);
  // A branch of one point is no branch: exit status 1 before any output.
  const Branch& traced = branches.front().branch;
  if (traced.points.size() < 2) {
    throw std::runtime_error(
        fmt::format("the {} branch could not be continued beyond its start: {} ({})",
                    FamilyName(traced), ToString(traced.end), traced.end_message));
  }
  const std::string provenance = ProvenanceOf(request, system).Text();
  std::vector<std::string> written;
  if (out) {
    for (const TracedBranch& b : branches) {
      const std::string path = BranchPath(request.out, b.label);
      CsvWriter& csv = b.label == "main"
                           ? outputs.AddCsv(*out, provenance, BranchColumns(b.branch))
                           : outputs.AddCsv(path, provenance, BranchColumns(b.branch));
      WriteBranchRows(csv, b.branch);
      written.push_back(path);
    }
  }
  if (json) {
    json->Write(ContinueJson(system, branches, ProvenanceOf(request, system)));
    written.push_back(request.json);
  }
  if (plot) {
    WriteChart(*plot, BranchChart(branches));
    written.push_back(request.plot);
  }
  // All together, last: a failure above (a branch file that cannot be
  // created, gnuplot) leaves every file as it was.
  outputs.Commit();
  for (const std::string& path : written) fmt::print("wrote:      {}\n", path);
}

}  // namespace

void AddContinueCommand(CLI::App& app) {
  auto request = std::make_shared<ContinueRequest>();
  CLI::App* command = app.add_subcommand(
      "continue",
      "Follow a periodic orbit P(p,q) as a parameter moves (pseudo-arclength continuation, "
      "through folds), locating folds, period doublings, Neimark-Sacker points, and the "
      "grazing or sticking point where the branch ends. The start orbit is found at --from "
      "(or --start, then followed both ways) as `impactkit orbit` finds it.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Continuation";
  command
      ->add_option("--param", request->parameter, "Parameter to vary: omega, xs, r, A1.., m, k, c")
      ->capture_default_str()
      ->group(group);
  command->add_option("--from", request->from, "Start value (and one bound) of the parameter")
      ->required()
      ->group(group);
  command->add_option("--to", request->to, "The other bound: the branch first heads there")
      ->required()
      ->group(group);
  command
      ->add_option("--start", request->start,
                   "Start value between --from and --to; the branch is then followed both ways "
                   "(default: start at --from and head for --to)")
      ->group(group);
  command->add_option("--step", request->step, "Initial arclength step in (eta, parameter)")
      ->capture_default_str()
      ->group(group);
  command->add_option("--min-step", request->min_step, "Smallest step before giving up")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-step", request->max_step, "Largest step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-points", request->max_points, "Points per direction at most")
      ->check(AtMost(kMaxBranchPoints, "points"))
      ->capture_default_str()
      ->group(group);
  command
      ->add_flag("--switch-pd", request->switch_period_doubling,
                 "At each period doubling, also follow the period-doubled branch P(2p,2q)")
      ->group(group);
  command
      ->add_flag("--follow-grazing", request->follow_grazing,
                 "At a grazing end, also follow the orbit with one impact more or fewer, "
                 "where one is found")
      ->group(group);
  AddOrbitSeedOptions(*command, request->seed, "Start orbit");
  AddStickingSeedOptions(*command, request->sticking, "Start orbit");
  command
      ->add_option("--out", request->out,
                   "CSV, one row per point: parameter, arclength, phase1.., v1.., range_xN, "
                   "mod1.. (multiplier moduli), stable, clearance, depth, special (the "
                   "special point's type by name, empty elsewhere); other branches go to "
                   "FILE.<label>.csv")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_option("--json", request->json,
                   "JSON: special_points [{type, param, ...}], end_reason, and every branch")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_option("--plot", request->plot,
                   "Figure: impact velocities against the parameter, stable solid, unstable "
                   "dashed, special points marked (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command->callback([request] { RunContinue(*request); });
}

}  // namespace impactkit::cli
