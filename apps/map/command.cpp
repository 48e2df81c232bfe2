/// `impactkit map`: a two-parameter brute-force map (impactkit/analysis/
/// parameter_map.hpp does the work): every cell's motion classified, written
/// as CSV, a JSON summary and a colour map, on all cores and under mpirun on
/// many machines, resumable from a checkpoint.

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "commands.hpp"
#include "common/curves.hpp"
#include "common/grid_driver.hpp"
#include "common/grid_flags.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/provenance.hpp"
#include "common/sweep_flags.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/parameter_map.hpp"
#include "impactkit/io/class_colors.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/io/grid_output.hpp"

namespace impactkit::cli {
namespace {

struct MapRequest {
  SystemOptions system;
  RangeFlags range;
  RangeFlags range2{"r"};
  RunFlags run;
  std::optional<int> threads;
  std::string checkpoint, out, json, plot;
  std::vector<std::string> curves;
};

ParameterMapOptions OptionsOf(const MapRequest& request, const System& system) {
  ParameterMapOptions options;
  ApplyRangeFlags(request.range, request.system, system, "", options.row);
  ApplyRunFlags(request.run, system, options.row);
  SweepOptions column;
  ApplyRangeFlags(request.range2, request.system, system, "2", column);
  Require(column.parameter != options.row.parameter,
          fmt::format("--param and --param2 are both '{}': a map needs two parameters",
                      column.parameter));
  options.parameter2 = column.parameter;
  options.from2 = column.from;
  options.to2 = column.to;
  options.steps2 = column.steps;
  std::string error;
  Require(options.IsValid(&error), error);
  return options;
}

/// The head of every output: all that decides the result.
Provenance ProvenanceOf(const MapRequest& request, const System& system,
                        const ParameterMapOptions& options) {
  const SweepOptions& row = options.row;
  std::string text = fmt::format(
      "map param={} from={} to={} steps={} param2={} from2={} to2={} steps2={} transient={} "
      "record={} start={} direction={} max_q={}{}",
      row.parameter, row.from, row.to, row.steps, options.parameter2, options.from2, options.to2,
      options.steps2, row.transient_periods, row.recorded_periods, ToString(row.start),
      ToString(row.direction), row.classify.period.max_q, RunFlagsProvenance(request.run));
  if (row.start == SweepStart::kPrevious) {
    text += fmt::format(
        " chunk={} warmup={} (along each row, each value from the previous one's final state; "
        "every chunk of {} values from the fixed state through the transients of the {} values "
        "before it)",
        row.chunk_values, row.warmup_values, row.chunk_values, row.warmup_values);
  } else {
    text += " (each cell from the fixed state)";
  }
  return MakeProvenance(request.system, system, std::move(text));
}

/// Counts per motion label, the JSON summary's heart.
std::map<std::string, std::int64_t> LabelCounts(const std::vector<GridCell>& cells) {
  std::map<std::string, std::int64_t> counts;
  for (const GridCell& cell : cells) ++counts[MotionLabel(cell)];
  return counts;
}

std::string SummaryJson(const Provenance& provenance, const ParameterMapTask& task,
                        const std::vector<GridCell>& cells) {
  const ParameterMapOptions& o = task.Options();
  nlohmann::ordered_json json;
  json["provenance"] = provenance.Json();
  json["param"] = {
      {"name", o.row.parameter}, {"from", o.row.from}, {"to", o.row.to}, {"steps", o.row.steps}};
  json["param2"] = {{"name", o.parameter2}, {"from", o.from2}, {"to", o.to2}, {"steps", o.steps2}};
  json["start"] = ToString(o.row.start);
  json["cells"] = cells.size();
  std::map<std::string, std::int64_t> kinds;
  for (const GridCell& cell : cells) ++kinds[ToString(cell.kind)];
  json["kinds"] = kinds;
  json["classes"] = LabelCounts(cells);
  return json.dump(2) + "\n";
}

using ClassKey = std::tuple<MotionKind, int, int>;

/// Periods drawn in their own colour; the rarer ones share one entry, so
/// that the legend stays one narrow column beside a figure panel however
/// many periods a map holds (the CSV and JSON keep every class).
constexpr std::size_t kLegendPeriods = 20;

/// A motion as the colour map tells it apart: impacting motions by period,
/// the others by kind alone.
ClassKey ClassOf(const GridCell& cell) {
  const bool by_period = cell.kind == MotionKind::kPeriodic || cell.kind == MotionKind::kSticking;
  return by_period ? ClassKey{cell.kind, cell.q, cell.p} : ClassKey{cell.kind, 0, 0};
}

/// The classes with a legend entry of their own: the kLegendPeriods most
/// frequent periods, then the kinds without a period, sorted by kind, q, p.
std::vector<ClassKey> LegendClasses(const std::map<ClassKey, std::int64_t>& counts) {
  std::vector<std::pair<std::int64_t, ClassKey>> periods;
  std::vector<ClassKey> legend;
  for (const auto& [key, count] : counts) {
    const MotionKind kind = std::get<0>(key);
    if (kind == MotionKind::kPeriodic || kind == MotionKind::kSticking) {
      periods.emplace_back(-count, key);  // most frequent first, then by key
    } else {
      legend.push_back(key);
    }
  }
  std::sort(periods.begin(), periods.end());
  for (std::size_t i = 0; i < std::min(periods.size(), kLegendPeriods); ++i) {
    legend.push_back(periods[i].second);
  }
  std::sort(legend.begin(), legend.end());
  return legend;
}

/// The legend's classes in their colours (ClassColor: the same class has
/// the same colour in every map), then one grey entry for the periods left
/// out.
ClassMap ChartOf(const ParameterMapTask& task, const std::vector<GridCell>& cells) {
  const ParameterMapOptions& o = task.Options();
  std::map<ClassKey, std::int64_t> counts;
  for (const GridCell& cell : cells) ++counts[ClassOf(cell)];
  ClassMap chart;
  std::map<ClassKey, int> class_of;
  for (const ClassKey& key : LegendClasses(counts)) {
    class_of[key] = static_cast<int>(chart.names.size());
    GridCell example;
    std::tie(example.kind, example.q, example.p) = key;
    chart.names.push_back(MotionLabel(example));
    chart.colors.push_back(ClassColor(example.kind, example.p, example.q));
  }
  const int other = static_cast<int>(chart.names.size());
  if (counts.size() > class_of.size()) {
    chart.names.push_back(fmt::format("{} other periods", counts.size() - class_of.size()));
    chart.colors.emplace_back(kOtherClassesColor);
  }
  const std::size_t k = task.Values1().size();
  for (const GridCell& cell : cells) {
    chart.x.push_back(task.Values1()[cell.index % k]);
    chart.y.push_back(task.Values2()[cell.index / k]);
    const auto found = class_of.find(ClassOf(cell));
    chart.cell_class.push_back(found == class_of.end() ? other : found->second);
  }
  chart.title = fmt::format("Motion over ({}, {})", ParameterLabel(o.row.parameter),
                            ParameterLabel(o.parameter2));
  chart.x_label = ParameterLabel(o.row.parameter);
  chart.y_label = ParameterLabel(o.parameter2);
  return chart;
}

void RunMapCommand(const MapRequest& request) {
  GridProcesses processes;
  const System system = ResolveSystem(request.system);
  const ParameterMapTask task(system, OptionsOf(request, system));
  const Provenance provenance = ProvenanceOf(request, system, task.Options());
  const GridDriveOptions drive =
      DriveOptionsOf("map", request.threads, request.checkpoint, processes);
  std::vector<Curve> overlays;
  if (!request.curves.empty()) {
    overlays = ReadCurves(request.curves, task.Options().row.parameter, task.Options().parameter2);
  }
  // Only the writer opens outputs, before the work: a bad path or a missing
  // gnuplot fails at once, not after hours.
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
  const ParameterMapOptions& o = task.Options();
  fmt::print("system:  {}\n", DescribeSystem(system));
  fmt::print("map:     {} {} values from {} to {} x {} {} values from {} to {}, start {}\n",
             o.row.parameter, o.row.steps, o.row.from, o.row.to, o.parameter2, o.steps2, o.from2,
             o.to2, ToString(o.row.start));
  fmt::print("run:     {}\n", RunReport(*outcome, drive, processes));
  std::string classes;
  for (const auto& [label, count] : LabelCounts(outcome->cells)) {
    classes += fmt::format("{}{} {}", classes.empty() ? "" : ", ", count, label);
  }
  fmt::print("result:  {}\n", classes);
  if (out) {
    out->Write(CsvHead({o.row.parameter, o.parameter2, kCellColumns}, provenance.Text()));
    const std::size_t k = task.Values1().size();
    for (const GridCell& cell : outcome->cells) {
      out->Write(fmt::format("{},{},{}\n", task.Values1()[cell.index % k],
                             task.Values2()[cell.index / k], CellFields(cell)));
    }
  }
  if (json) json->Write(SummaryJson(provenance, task, outcome->cells));
  if (plot) {
    ClassMap chart = ChartOf(task, outcome->cells);
    chart.overlays = overlays;
    plot->Write(RenderClassMap(chart, ImageFormatOf(plot->Path())));
  }
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.json, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:   {}\n", *path);
  }
}

}  // namespace

void AddMapCommand(CLI::App& app) {
  auto request = std::make_shared<MapRequest>();
  CLI::App* command = app.add_subcommand(
      "map",
      "Two-parameter brute-force map: a grid of --param by --param2 values, each row the sweep "
      "of --param at one --param2 value (as 'impactkit sweep'), every cell's motion classified "
      "(periodic P(p,q), sticking P(inf,q), chaotic, non_impacting, unresolved). Uses all cores; "
      "under 'mpirun -np K impactkit map ...' spreads chunks of rows over the ranks. Results are "
      "identical "
      "for any --threads and any number of ranks.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Map";
  AddRangeFlags(*command, request->range, group);
  AddRangeFlags(*command, request->range2, group, "2");
  AddRunFlags(*command, request->run, group);
  AddGridRunOptions(*command, request->threads, request->checkpoint);
  const std::string output = "Output (each written only if asked for, and only whole)";
  command
      ->add_option("--out", request->out,
                   "One row per cell: PARAM,PARAM2,kind,p,q,max_velocity,range_xN,lyapunov (p "
                   "= 0 when sticking; max_velocity the largest impact speed, range_xN the largest "
                   "per-period max - min of the contact mass; empty where undefined)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--json", request->json,
                   "Summary: the grid, and the cells of each kind and class")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--plot", request->plot,
                   "Colour map of the motion with a legend (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group(output);
  command
      ->add_option(
          "--curves", request->curves,
          "Curves to draw over --plot, as 'impactkit curve --json' writes them (one or more "
          "files; docs/curves-json.md)")
      ->type_name("FILE.json")
      ->check(CLI::ExistingFile)
      ->group(output);
  command->callback([request] { RunMapCommand(*request); });
}

}  // namespace impactkit::cli
