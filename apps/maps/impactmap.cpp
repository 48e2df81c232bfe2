/// `impactkit impactmap`: the impacts of a long run seen as a map, the phase
/// of each impact (t mod T) against its speed (the paper's Figs. 8-9).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/system_options.hpp"
#include "impactkit/io/output_set.hpp"
#include "maps/run.hpp"

namespace impactkit::cli {
namespace {

struct ImpactMapRequest {
  SystemOptions system;
  RunOptions run;
  std::string out;
  std::string plot;
};

void RunImpactMap(const ImpactMapRequest& request) {
  ValidateRun(request.run);
  const System system = ResolveSystem(request.system);
  const std::string provenance =
      RunProvenance("impactmap", request.run, request.system, system).Text();
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;  // created first: a bad path fails before the work
  CsvWriter* csv = nullptr;
  if (!request.out.empty()) {
    csv = &outputs.AddCsv(request.out, provenance,
                          std::vector<std::string>{"t", "phase", "velocity"});
  }
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);
  const RecordedRun recorded = RecordImpacts(system, request.run);
  PrintRun(system, request.run, recorded);
  Curve points{"impacts", {}, {}, false, "#1f4e9a", true};
  double v_min = INFINITY, v_max = 0.0;
  for (const ImpactView impact : recorded.impacts) {
    if (csv) csv->WriteRow(std::vector<double>{impact.t, impact.phase, impact.velocity});
    points.x.push_back(impact.phase);
    points.y.push_back(impact.velocity);
    v_min = std::min(v_min, impact.velocity);
    v_max = std::max(v_max, impact.velocity);
  }
  if (recorded.impacts.empty()) {
    fmt::print("impacts:     none in the recorded window\n");
  } else {
    fmt::print("impacts:     {} with speed in [{:.6g}, {:.6g}]\n", recorded.impacts.size(), v_min,
               v_max);
  }
  if (plot) {
    LineChart chart;
    chart.title = fmt::format("impact map, Ω = {}", system.omega);
    chart.x_label = fmt::format("phase at impact, t mod T (T = {:.6g})", system.ForcingPeriod());
    chart.y_label = ImpactSpeedLabel(system);
    chart.curves.push_back(points);
    WriteChart(*plot, chart);
  }
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:       {}\n", *path);
  }
}

}  // namespace

void AddImpactMapCommand(CLI::App& app) {
  auto request = std::make_shared<ImpactMapRequest>();
  CLI::App* command = app.add_subcommand(
      "impactmap",
      "Impact map of a long run (the paper's Figs. 8-9): the phase of each impact (t mod T) "
      "against its speed, from rest after a discarded transient.");
  AddSystemOptions(*command, request->system);
  AddRunOptions(*command, request->run, 5000);
  command->add_option("--out", request->out, "Write the impacts as CSV: t,phase,velocity")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group("Output");
  command->add_option("--plot", request->plot, "Plot phase against impact speed (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command->callback([request] { RunImpactMap(*request); });
}

}  // namespace impactkit::cli
