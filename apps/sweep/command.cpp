/// `impactkit sweep`: a brute-force bifurcation diagram over any named
/// parameter (impactkit/sweep.hpp does the work), written as CSV and PNG.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/provenance.hpp"
#include "common/sweep_flags.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/sweep_output.hpp"
#include "sweep/chart.hpp"

namespace impactkit::cli {
namespace {

struct SweepRequest {
  SystemOptions system;
  RangeFlags range;
  RunFlags run;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::string out, summary, plot;
};

/// The flags as library options; flag names in the messages.
SweepOptions OptionsOf(const SweepRequest& request, const System& system) {
  SweepOptions options;
  ApplyRangeFlags(request.range, request.system, system, "", options);
  ApplyRunFlags(request.run, system, options);
  if (request.threads < 1) {
    throw InvalidInput(fmt::format("--threads must be >= 1, got {}", request.threads));
  }
  options.threads = request.threads;
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  return options;
}

/// The head of every output: all that decides the result (the thread
/// count does not).
std::string ProvenanceText(const SweepRequest& request, const System& system,
                           const SweepOptions& options) {
  std::string text = fmt::format(
      "sweep param={} from={} to={} steps={} transient={} record={} start={} direction={} "
      "max_q={}",
      options.parameter, options.from, options.to, options.steps, options.transient_periods,
      options.recorded_periods, ToString(options.start), ToString(options.direction),
      options.classify.period.max_q);
  text += RunFlagsProvenance(request.run);
  if (options.start == SweepStart::kPrevious) {
    text += fmt::format(
        " chunk={} warmup={} (each value from the previous one's final state; every chunk of "
        "{} values from the fixed state through the transients of the {} values before it)",
        options.chunk_values, options.warmup_values, options.chunk_values, options.warmup_values);
  } else {
    text += " (each value from the fixed state)";
  }
  return MakeProvenance(request.system, system, std::move(text)).Text();
}

void RunSweepCommand(const SweepRequest& request) {
  const System system = ResolveSystem(request.system);
  const SweepOptions options = OptionsOf(request, system);
  const std::string provenance = ProvenanceText(request, system, options);
  // Outputs are opened before the work, so that a bad path or a missing
  // gnuplot fails at once, not after a long sweep.
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;
  CsvWriter* out = nullptr;
  if (!request.out.empty()) {
    out = &outputs.AddCsv(request.out, provenance, SweepImpactColumns(options.parameter));
  }
  AtomicOutputFile* summary = AddIfAsked(outputs, request.summary);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);

  SweepResult result;
  {
    const RunProgress progress(options.parameter);
    result = RunSweep(system, options, progress.Control());
  }

  fmt::print("system:  {}\n", DescribeSystem(system));
  fmt::print(
      "sweep:   {} from {} to {} in {} values, {}, {} transient + {} recorded periods, "
      "start {}, {} threads\n",
      options.parameter, options.from, options.to, options.steps, ToString(options.direction),
      options.transient_periods, options.recorded_periods, ToString(options.start),
      options.threads);
  fmt::print("result:  {}\n", result.BriefReport());
  if (out) WriteSweepImpactRows(*out, result);
  if (summary) {
    summary->Write(CsvHead(SweepSummaryColumns(options.parameter), provenance));
    for (const SweepPoint& point : result.points) summary->Write(SweepSummaryRow(point));
  }
  if (plot)
    plot->Write(RenderStacked(SweepCharts(system, options, result), 1000, 900,
                              ImageFormatOf(plot->Path())));
  // Committed last: a failure above leaves no partial set of files.
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.summary, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:   {}\n", *path);
  }
}

}  // namespace

void AddSweepCommand(CLI::App& app) {
  auto request = std::make_shared<SweepRequest>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Brute-force bifurcation diagram: step one named parameter through evenly spaced values, "
      "simulate each to steady state (from the previous value's final state by default), record "
      "every impact and the per-period max - min of the contact mass and of x1, and classify the "
      "motion (periodic P(p,q), sticking P(inf,q), chaotic, non_impacting, or unresolved). "
      "Results are identical for any --threads.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Sweep";
  AddRangeFlags(*command, request->range, group);
  AddRunFlags(*command, request->run, group);
  command->add_option("--threads", request->threads, "Worker threads (default: all cores)")
      ->type_name("N")
      ->check(AtMost(kMaxThreads, "threads"))
      ->group(group);
  const std::string output = "Output (each written only if asked for, and only whole)";
  command
      ->add_option("--out", request->out,
                   "Every recorded impact: columns PARAM,t,phase,velocity,stop (PARAM the "
                   "parameter's name; t from the start of that value's run, phase = t mod T, "
                   "velocity the impact speed)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option(
          "--summary", request->summary,
          "One row per value: param,kind,p,q,range_xN,range_x1,range_xN_min,"
          "range_x1_min,impacts,velocity_min,velocity_max,lyapunov,restarted (range_*: largest and "
          "smallest per-period max - min; p = 0 when sticking; empty where undefined)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--plot", request->plot,
                   "Figure like the paper's Fig. 3: max - min of the contact mass per period, and "
                   "impact velocity, against the parameter (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group(output);
  command->callback([request] { RunSweepCommand(*request); });
}

}  // namespace impactkit::cli
