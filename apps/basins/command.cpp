/// `impactkit basins`: basins of attraction over two state coordinates at
/// fixed parameters (impactkit/analysis/basins.hpp does the work), written as
/// CSV, a JSON list of the attractors with their orbits and basin shares, and
/// a colour map; run as `map` is (threads, mpirun, checkpoint).

#include <fmt/format.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "commands.hpp"
#include "common/grid_driver.hpp"
#include "common/grid_flags.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/provenance.hpp"
#include "common/sweep_flags.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/basins.hpp"
#include "impactkit/io/class_colors.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/io/grid_output.hpp"

namespace impactkit::cli {
namespace {

struct Axis {
  std::string coordinate;
  double from = 0.0;
  double to = 0.0;
  int steps = 0;
};

struct BasinsRequest {
  SystemOptions system;
  Axis axis{"x2"};
  Axis axis2{"v2"};
  RunFlags run;
  double tolerance = BasinsOptions{}.orbit_tolerance;
  std::optional<int> threads;
  std::string checkpoint, out, json, plot;
};

BasinsOptions OptionsOf(const BasinsRequest& request, const System& system) {
  BasinsOptions options;
  ApplyRunFlags(request.run, system, options.run);
  options.base = options.run.fixed_state;
  for (const auto& [axis, suffix] :
       {std::pair{&request.axis, ""}, std::pair{&request.axis2, "2"}}) {
    StateCoordinate(system, axis->coordinate);  // "unknown state coordinate ..."
    Require(axis->steps >= 1, fmt::format("--steps{} must be >= 1, got {}", suffix, axis->steps));
    Require(axis->steps == 1 || axis->from != axis->to,
            fmt::format("--from{0} and --to{0} are both {1}: {2} steps need a range (or "
                        "--steps{0} 1)",
                        suffix, axis->from, axis->steps));
  }
  Require(request.axis.coordinate != request.axis2.coordinate,
          fmt::format("--coord and --coord2 are both '{}': a basin picture needs two",
                      request.axis.coordinate));
  options.coordinate1 = request.axis.coordinate;
  options.from1 = request.axis.from;
  options.to1 = request.axis.to;
  options.steps1 = request.axis.steps;
  options.coordinate2 = request.axis2.coordinate;
  options.from2 = request.axis2.from;
  options.to2 = request.axis2.to;
  options.steps2 = request.axis2.steps;
  Require(request.tolerance > 0 && request.tolerance < 1,
          fmt::format("--tolerance must be in (0, 1), got {}", request.tolerance));
  options.orbit_tolerance = request.tolerance;
  std::string error;
  Require(options.IsValid(&error), error);
  return options;
}

/// The head of every output: all that decides the result.
Provenance ProvenanceOf(const BasinsRequest& request, const System& system,
                        const BasinsOptions& o) {
  return MakeProvenance(
      request.system, system,
      fmt::format("basins coord={} from={} to={} steps={} coord2={} from2={} to2={} steps2={} "
                  "transient={} record={} max_q={} tolerance={}{} (each cell from its own "
                  "start; the other coordinates from --x0/--v0, default rest)",
                  o.coordinate1, o.from1, o.to1, o.steps1, o.coordinate2, o.from2, o.to2, o.steps2,
                  o.run.transient_periods, o.run.recorded_periods, o.run.classify.period.max_q,
                  o.orbit_tolerance, RunFlagsProvenance(request.run)));
}

std::string AttractorLabel(const BasinsResult& result, int a) {
  const Attractor& attractor = result.attractors[a];
  GridCell cell;
  cell.kind = attractor.kind;
  cell.p = attractor.p;
  cell.q = attractor.q;
  return fmt::format("A{} {}", a + 1, MotionLabel(cell));
}

std::string SummaryJson(const Provenance& provenance, const BasinsTask& task,
                        const BasinsResult& result, std::int64_t cells) {
  const BasinsOptions& o = task.Options();
  const std::size_t k = task.Values1().size();
  nlohmann::ordered_json json;
  json["provenance"] = provenance.Json();
  json["coord"] = {{"name", o.coordinate1}, {"from", o.from1}, {"to", o.to1}, {"steps", o.steps1}};
  json["coord2"] = {{"name", o.coordinate2}, {"from", o.from2}, {"to", o.to2}, {"steps", o.steps2}};
  json["cells"] = cells;
  json["attractors"] = nlohmann::json::array();
  for (std::size_t a = 0; a < result.attractors.size(); ++a) {
    const Attractor& attractor = result.attractors[a];
    nlohmann::ordered_json entry;
    entry["id"] = a + 1;
    entry["label"] = AttractorLabel(result, static_cast<int>(a));
    entry["kind"] = ToString(attractor.kind);
    entry["p"] = attractor.p;
    entry["q"] = attractor.q;
    entry["cells"] = attractor.cells;
    entry["share"] = static_cast<double>(attractor.cells) / static_cast<double>(cells);
    entry["first_start"] = {{o.coordinate1, task.Values1()[attractor.first_cell % k]},
                            {o.coordinate2, task.Values2()[attractor.first_cell / k]}};
    entry["orbit"] = nlohmann::json::array();
    for (const AttractorImpact& i : attractor.orbit) {
      entry["orbit"].push_back({{"phase", i.phase}, {"velocity", i.velocity}});
    }
    json["attractors"].push_back(entry);
  }
  return json.dump(2) + "\n";
}

/// "x2 = 0, v2 = 0": the coordinates every start shares (--x0/--v0, rest
/// by default), all but the two that vary.
std::string FixedCoordinates(const System& system, const RunFlags& run, const BasinsOptions& o) {
  std::vector<std::string> fixed;
  for (const auto& [letter, values] : {std::pair{'x', &run.x0}, std::pair{'v', &run.v0}}) {
    for (int i = 0; i < system.Dof(); ++i) {
      const std::string name = fmt::format("{}{}", letter, i + 1);
      if (name == o.coordinate1 || name == o.coordinate2) continue;
      const double value = i < static_cast<int>(values->size()) ? (*values)[i] : 0.0;
      fixed.push_back(fmt::format("{} = {:.6g}", name, value));
    }
  }
  return fmt::format("{}", fmt::join(fixed, ", "));
}

/// Each attractor in the colour of its class (ClassColor), a further
/// attractor of a class already drawn in a shade of that colour.
ClassMap ChartOf(const System& system, const RunFlags& run, const BasinsTask& task,
                 const BasinsResult& result, const std::vector<GridCell>& cells) {
  ClassMap chart;
  std::map<std::tuple<MotionKind, int, int>, int> drawn;
  for (std::size_t a = 0; a < result.attractors.size(); ++a) {
    const Attractor& attractor = result.attractors[a];
    chart.names.push_back(AttractorLabel(result, static_cast<int>(a)));
    const int copy = drawn[{attractor.kind, attractor.p, attractor.q}]++;
    chart.colors.push_back(ClassColor(attractor.kind, attractor.p, attractor.q, copy));
  }
  const std::size_t k = task.Values1().size();
  for (const GridCell& cell : cells) {
    chart.x.push_back(task.Values1()[cell.index % k]);
    chart.y.push_back(task.Values2()[cell.index / k]);
    chart.cell_class.push_back(result.attractor[cell.index]);
  }
  const BasinsOptions& o = task.Options();
  const std::string fixed = FixedCoordinates(system, run, o);
  chart.title =
      fmt::format("Basins of attraction at {} = {:.6g} over ({}, {}){}{}", ParameterLabel("omega"),
                  system.omega, o.coordinate1, o.coordinate2, fixed.empty() ? "" : "; ", fixed);
  chart.x_label = o.coordinate1;
  chart.y_label = o.coordinate2;
  return chart;
}

void RunBasinsCommand(const BasinsRequest& request) {
  GridProcesses processes;
  const System system = ResolveSystem(request.system);
  const BasinsTask task(system, OptionsOf(request, system));
  const Provenance provenance = ProvenanceOf(request, system, task.Options());
  const GridDriveOptions drive =
      DriveOptionsOf("basins", request.threads, request.checkpoint, processes);
  OutputSet outputs;
  AtomicOutputFile *out = nullptr, *json = nullptr, *plot = nullptr;
  if (processes.Writer()) {
    if (!request.plot.empty()) RequireGnuplot();
    out = AddIfAsked(outputs, request.out);
    json = AddIfAsked(outputs, request.json);
    plot = AddIfAsked(outputs, request.plot);
  }
  const std::optional<GridOutcome> outcome = DriveGrid(task, drive, processes);
  if (!outcome) return;  // not the writer
  const BasinsResult result =
      IdentifyAttractors(outcome->cells, system.ForcingPeriod(), task.Options().orbit_tolerance);
  const BasinsOptions& o = task.Options();
  fmt::print("system:  {}\n", DescribeSystem(system));
  fmt::print("basins:  {} {} values from {} to {} x {} {} values from {} to {}\n", o.coordinate1,
             o.steps1, o.from1, o.to1, o.coordinate2, o.steps2, o.from2, o.to2);
  fmt::print("run:     {}\n", RunReport(*outcome, drive, processes));
  for (std::size_t a = 0; a < result.attractors.size(); ++a) {
    fmt::print("attractor {}: {} cells ({:.1f}%)\n", AttractorLabel(result, static_cast<int>(a)),
               result.attractors[a].cells,
               100.0 * static_cast<double>(result.attractors[a].cells) /
                   static_cast<double>(outcome->cells.size()));
  }
  if (out) {
    out->Write(
        CsvHead({o.coordinate1, o.coordinate2, "attractor", kCellColumns}, provenance.Text()));
    const std::size_t k = task.Values1().size();
    for (const GridCell& cell : outcome->cells) {
      out->Write(fmt::format("{},{},{},{}\n", task.Values1()[cell.index % k],
                             task.Values2()[cell.index / k], result.attractor[cell.index] + 1,
                             CellFields(cell)));
    }
  }
  if (json) {
    json->Write(
        SummaryJson(provenance, task, result, static_cast<std::int64_t>(outcome->cells.size())));
  }
  if (plot)
    plot->Write(RenderClassMap(ChartOf(system, request.run, task, result, outcome->cells),
                               ImageFormatOf(plot->Path())));
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.json, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:   {}\n", *path);
  }
}

void AddAxis(CLI::App& command, Axis& axis, const std::string& suffix, const std::string& group) {
  const std::string which = suffix.empty() ? "along each row" : "from row to row";
  command
      .add_option("--coord" + suffix, axis.coordinate,
                  "State coordinate varied " + which + ": x1..xN or v1..vN")
      ->type_name("NAME")
      ->capture_default_str()
      ->group(group);
  command.add_option("--from" + suffix, axis.from, "One end of its range")
      ->type_name("A")
      ->required()
      ->group(group);
  command.add_option("--to" + suffix, axis.to, "The other end")
      ->type_name("B")
      ->required()
      ->group(group);
  command.add_option("--steps" + suffix, axis.steps, "Number of values, both ends included")
      ->type_name("K")
      ->check(AtMost(kMaxSteps, "values"))
      ->required()
      ->group(group);
}

}  // namespace

void AddBasinsCommand(CLI::App& app) {
  auto request = std::make_shared<BasinsRequest>();
  CLI::App* command = app.add_subcommand(
      "basins",
      "Basins of attraction at fixed parameters: a grid of starts over two state coordinates "
      "(--coord, --coord2; the others from --x0/--v0, default rest), each run to its attractor "
      "and classified as 'impactkit sweep' does; attractors told apart by their orbit (two "
      "different P(1,1) orbits are two attractors). Runs as 'map' does: all cores, mpirun, "
      "--checkpoint.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Basins";
  AddAxis(*command, request->axis, "", group);
  AddAxis(*command, request->axis2, "2", group);
  AddRunFlags(*command, request->run, group);
  command
      ->add_option("--tolerance", request->tolerance,
                   "Two orbits are one attractor when each impact's phase is within this "
                   "fraction of the period, and its speed within it relatively, of one of the "
                   "other's")
      ->type_name("TOL")
      ->capture_default_str()
      ->group(group);
  AddGridRunOptions(*command, request->threads, request->checkpoint);
  const std::string output = "Output (each written only if asked for, and only whole)";
  command
      ->add_option(
          "--out", request->out,
          "One row per start: COORD,COORD2,attractor,kind,p,q,max_velocity,range_xN,lyapunov "
          "(attractor numbered from 1 as in --json)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--json", request->json,
                   "The attractors: kind, period, orbit (phase and speed of each impact of its "
                   "last q periods), basin size and share, a start in the basin")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group(output);
  command->add_option("--plot", request->plot, "Colour map of the basins (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group(output);
  command->callback([request] { RunBasinsCommand(*request); });
}

}  // namespace impactkit::cli
