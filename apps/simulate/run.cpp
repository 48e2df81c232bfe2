#include "simulate/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <utility>

#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/provenance.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/io/output_file.hpp"
#include "simulate/output.hpp"
#include "simulate/summary.hpp"

namespace impactkit::cli {
namespace {

/// A series is held in memory until written: beyond this many rows, ask
/// for fewer periods or samples rather than exhaust memory at the end.
constexpr double kMaxSeriesRows = 2e7;

/// Two outputs naming one file would silently keep only the last written.
void CheckDistinctOutputs(const SimulateRequest& request) {
  const std::pair<const char*, const std::filesystem::path*> outputs[] = {
      {"--series", &request.series},
      {"--impacts", &request.impacts},
      {"--plot", &request.plot},
      {"--json", &request.json}};
  for (std::size_t i = 0; i < std::size(outputs); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const auto& [flag, path] = outputs[i];
      const auto& [other_flag, other_path] = outputs[j];
      Require(path->empty() || path->lexically_normal() != other_path->lexically_normal(),
              fmt::format("{} and {} name the same file {}", other_flag, flag, path->string()));
    }
  }
}

void CheckRequest(const SimulateRequest& request) {
  Require(request.transient >= 0,
          fmt::format("--transient must be >= 0 forcing periods, got {}", request.transient));
  Require(request.periods >= 1,
          fmt::format("--periods must be >= 1 forcing period, got {}", request.periods));
  Require(request.samples_per_period >= 1,
          fmt::format("--samples-per-period must be >= 1, got {}", request.samples_per_period));
  Require(!request.chatter_threshold || request.chatter == ChatterMethod::kThreshold,
          "--chatter-threshold applies only with --chatter threshold");
  Require(!request.chatter_threshold ||
              (*request.chatter_threshold > 0 && std::isfinite(*request.chatter_threshold)),
          fmt::format("--chatter-threshold must be finite and > 0, got {}",
                      request.chatter_threshold.value_or(0.0)));
  const double rows = static_cast<double>(request.periods) * request.samples_per_period;
  Require((request.series.empty() && request.plot.empty()) || rows <= kMaxSeriesRows,
          fmt::format("the series would have {:.3g} rows (--periods x --samples-per-period); at "
                      "most {:.3g}",
                      rows, kMaxSeriesRows));
  CheckDistinctOutputs(request);
}

Eigen::VectorXd ToVector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

HybridState InitialState(const System& system, const SimulateRequest& request) {
  HybridState state = RestState(system);
  // Sizes are ValidateState's to check: it names N and what was given.
  if (!request.x0.empty()) state.x = ToVector(request.x0);
  if (!request.v0.empty()) state.v = ToVector(request.v0);
  ValidateState(system, state);
  return state;
}

Window WindowOf(const SimulateRequest& request, const System& system) {
  Window window;
  window.period = system.ForcingPeriod();
  window.first_period = request.transient;
  window.periods = request.periods;
  window.begin = static_cast<double>(request.transient) * window.period;
  window.end = static_cast<double>(request.transient + request.periods) * window.period;
  return window;
}

/// What produced the outputs, every value resolved: the header of each CSV
/// file and the "provenance" of the JSON summary.
Provenance ProvenanceOf(const SimulateRequest& request, const System& system) {
  std::string text = fmt::format(
      "simulate transient={} periods={} samples_per_period={} chatter={}", request.transient,
      request.periods, request.samples_per_period, ToString(request.chatter));
  if (request.chatter == ChatterMethod::kThreshold) {
    text += fmt::format(" chatter_threshold={}", SimulationOptionsOf(request).chatter_threshold);
  }
  if (!request.x0.empty()) text += fmt::format(" x0={}", fmt::join(request.x0, ","));
  if (!request.v0.empty()) text += fmt::format(" v0={}", fmt::join(request.v0, ","));
  return MakeProvenance(request.system, system, std::move(text));
}

/// Runs to t_end with a progress line; a run that cannot reach t_end is a
/// failure, since its window would be silently short.
SimulationSummary Advance(const Simulator& simulator, HybridState& state, double t_end,
                          const std::string& stage, Observer* recorders) {
  ProgressLine progress(stage, state.t, t_end, simulator.GetSystem().ForcingPeriod());
  ObserverList observers;
  observers.Add(progress);
  if (recorders != nullptr) observers.Add(*recorders);
  const SimulationSummary summary = simulator.Run(state, t_end, observers);
  if (summary.termination != Termination::kCompleted) {
    throw std::runtime_error(fmt::format("the {} stopped at t = {:.6g}, before t = {:.6g}: {}",
                                         stage, state.t, t_end, Describe(summary.termination)));
  }
  return summary;
}

WindowAnalysis Analyse(const WindowRecorders& recorders, const Window& window,
                       const SimulationSummary& recording) {
  WindowAnalysis analysis;
  analysis.chatter_cuts = recording.chatter_cuts;
  const ImpactLog& impacts = recorders.steady.Impacts();
  analysis.impacts_per_period = static_cast<double>(impacts.size()) / window.periods;
  analysis.sticking_fraction = recorders.sticking.TotalTime() / (window.end - window.begin);
  analysis.chatter_sequences = static_cast<long>(recorders.steady.ChatterEnds().size());
  analysis.motion = recorders.steady.Period();
  analysis.searched_q = analysis.motion.searched_q;
  return analysis;
}

}  // namespace

SimulationOptions SimulationOptionsOf(const SimulateRequest& request) {
  SimulationOptions options;
  options.chatter = request.chatter;
  if (request.chatter_threshold) options.chatter_threshold = *request.chatter_threshold;
  return options;
}

WindowRecorders::WindowRecorders(const Window& window, std::optional<double> sample_interval)
    : steady(window.period) {
  steady.Reserve(window.periods);
  all.Add(steady);
  all.Add(sticking);
  if (sample_interval) all.Add(series.emplace(window.begin, *sample_interval, /*events=*/true));
}

void RunSimulate(const SimulateRequest& request) {
  CheckRequest(request);
  const System system = ResolveSystem(request.system);
  const HybridState initial_state = InitialState(system, request);
  const Simulator simulator(system, SimulationOptionsOf(request));
  if (!request.plot.empty()) RequireGnuplot();
  SimulateOutputs outputs(request, system, ProvenanceOf(request, system));

  const Window window = WindowOf(request, system);
  HybridState state = initial_state;
  double elapsed = Advance(simulator, state, window.begin, "transient", nullptr).seconds;
  std::optional<double> sample_interval;
  if (outputs.NeedsSeries()) sample_interval = window.period / request.samples_per_period;
  WindowRecorders recorders(window, sample_interval);
  const SimulationSummary recording =
      Advance(simulator, state, window.end, "recording", &recorders.all);
  elapsed += recording.seconds;

  const WindowAnalysis analysis = Analyse(recorders, window, recording);
  const SimulateResult result{request,  system,        window, recorders,
                              analysis, initial_state, state,  elapsed};
  outputs.Write(result);
  fmt::print("{}", SummaryText(result));
}

}  // namespace impactkit::cli
