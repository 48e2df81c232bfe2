/// `impactkit impactmap`, `impactkit returnmap` and `impactkit lyapunov`:
/// the impacts of a long run seen as a map (impact phase against impact
/// speed; successive slow impacts; exponents of the impact map). The
/// library does the work: simulate.hpp, map_fit.hpp, lyapunov.hpp.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/analysis/lyapunov.hpp"
#include "impactkit/analysis/map_fit.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/io/system_file.hpp"
#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/system_options.hpp"

namespace impactkit::cli {
namespace {

/// The run every map command starts with: from rest, `transient` forcing
/// periods discarded, then `periods` recorded.
struct RunOptions {
  int transient = 500;
  int periods = 5000;
};

void AddRunOptions(CLI::App& command, RunOptions& run, int default_periods) {
  run.periods = default_periods;
  command.add_option("--transient", run.transient, "Forcing periods run from rest and discarded")
      ->capture_default_str()
      ->group("Run");
  command.add_option("--periods", run.periods, "Forcing periods recorded after the transient")
      ->capture_default_str()
      ->group("Run");
}

void ValidateRun(const RunOptions& run) {
  if (run.transient < 0) {
    throw InvalidInput(fmt::format("--transient must be >= 0, got {}", run.transient));
  }
  if (run.periods < 1)
    throw InvalidInput(fmt::format("--periods must be >= 1, got {}", run.periods));
}

struct RecordedRun {
  std::vector<Impact> impacts;
  SimulationSummary summary;  ///< of the recorded window
  HybridState end;
};

RecordedRun RecordImpacts(const System& system, const RunOptions& run) {
  const Simulator simulator(system);
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  {
    ProgressLine progress("transient", 0.0, run.transient * period, period);
    simulator.Run(state, run.transient * period, progress);
  }
  ImpactRecorder recorder;
  ProgressLine progress("recording", state.t, state.t + run.periods * period, period);
  ObserverList observers;
  observers.Add(recorder);
  observers.Add(progress);
  RecordedRun result;
  result.summary = simulator.Run(state, state.t + run.periods * period, observers);
  if (result.summary.status != SimulationStatus::kReachedEnd) {
    throw std::runtime_error(
        fmt::format("the simulation stopped early: {}", result.summary.BriefReport()));
  }
  result.impacts = recorder.Impacts();
  result.end = state;
  return result;
}

std::string RunProvenance(const std::string& command, const RunOptions& run, const System& system) {
  return fmt::format("{} --transient {} --periods {} {}", command, run.transient, run.periods,
                     ParameterList(system));
}

void WritePng(const std::string& path, const LineChart& chart) {
  AtomicOutputFile png(path);
  png.Write(RenderPng(chart));
  png.Commit();
  fmt::print("wrote:       {}\n", path);
}

void PrintRun(const System& system, const RunOptions& run, const RecordedRun& recorded) {
  fmt::print("system:      {}\n", DescribeSystem(system));
  fmt::print("run:         from rest, {} periods discarded, {} recorded: {}\n", run.transient,
             run.periods, recorded.summary.BriefReport());
}

// ---- impactmap -------------------------------------------------------------

struct ImpactMapRequest {
  SystemOptions system;
  RunOptions run;
  std::string out;
  std::string plot;
};

void RunImpactMap(const ImpactMapRequest& request) {
  ValidateRun(request.run);
  const System system = ResolveSystem(request.system);
  std::optional<CsvWriter> csv;  // created first: a bad path fails before the work
  const std::string provenance = RunProvenance("impactmap", request.run, system);
  if (!request.out.empty())
    csv.emplace(request.out, provenance, std::vector<std::string>{"t", "phase", "v"});
  if (!request.plot.empty()) RequireGnuplot();
  const RecordedRun recorded = RecordImpacts(system, request.run);
  PrintRun(system, request.run, recorded);
  Curve points{"impacts", {}, {}, false, "#1f4e9a", true};
  double v_min = INFINITY, v_max = 0.0;
  for (const Impact& impact : recorded.impacts) {
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
  if (csv) {
    csv->Commit();
    fmt::print("wrote:       {}\n", request.out);
  }
  if (!request.plot.empty()) {
    LineChart chart;
    chart.title = fmt::format("impact map, omega = {}", system.omega);
    chart.x_label = fmt::format("phase at impact, t mod T (T = {:.6g})", system.ForcingPeriod());
    chart.y_label = fmt::format("impact velocity v{}(t-)", system.contact_dof + 1);
    chart.curves.push_back(points);
    WritePng(request.plot, chart);
  }
}

// ---- returnmap -------------------------------------------------------------

struct ReturnMapRequest {
  SystemOptions system;
  RunOptions run;
  double bound = 0.3;
  bool fit = false;
  std::optional<double> fit_from;
  std::optional<double> fit_to;
  std::string out;
  std::string plot;
  std::string json;
};

nlohmann::json FitJson(const MapFitSummary& fit) {
  const auto triple = [](const SqrtMapParameters& p) {
    return nlohmann::json{{"s", p.s}, {"d", p.d}, {"lambda", p.lambda}};
  };
  nlohmann::json covariance = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    covariance.push_back({fit.covariance(i, 0), fit.covariance(i, 1), fit.covariance(i, 2)});
  }
  return {{"termination", ToString(fit.termination)},
          {"message", fit.message},
          {"parameters", triple(fit.parameters)},
          {"standard_error", triple(fit.standard_error)},
          {"covariance", covariance},
          {"rms_residual", fit.rms_residual},
          {"sigma", fit.sigma},
          {"points", fit.points},
          {"points_on_root_branch", fit.points_on_root_branch}};
}

void RunReturnMap(const ReturnMapRequest& request) {
  ValidateRun(request.run);
  if (!(request.bound > 0.0)) {
    throw InvalidInput(fmt::format("--bound must be > 0, got {}", request.bound));
  }
  if (!request.fit && (request.fit_from || request.fit_to || !request.json.empty())) {
    throw InvalidInput("--fit-from, --fit-to and --json need --fit");
  }
  const System system = ResolveSystem(request.system);
  const std::string provenance = fmt::format("returnmap --bound {} {}", request.bound,
                                             RunProvenance("", request.run, system).substr(1));
  std::optional<CsvWriter> csv;  // created first: a bad path fails before the work
  if (!request.out.empty()) {
    csv.emplace(request.out, provenance, std::vector<std::string>{"v_j", "v_next"});
  }
  std::optional<AtomicOutputFile> json;
  if (!request.json.empty()) json.emplace(request.json);
  if (!request.plot.empty()) RequireGnuplot();

  const RecordedRun recorded = RecordImpacts(system, request.run);
  PrintRun(system, request.run, recorded);
  std::vector<double> speeds;
  for (const Impact& impact : recorded.impacts) speeds.push_back(impact.velocity);
  const ReturnMapPoints points = LowVelocityReturnMap(speeds, request.bound);
  fmt::print("return map:  {} pairs of successive impacts with speed < {} (of {} impacts)\n",
             points.from.size(), request.bound, speeds.size());
  for (std::size_t j = 0; j < points.from.size(); ++j) {
    if (csv) csv->WriteRow(std::vector<double>{points.from[j], points.to[j]});
  }
  if (csv) {
    csv->Commit();
    fmt::print("wrote:       {}\n", request.out);
  }

  std::optional<MapFitSummary> fit;
  if (request.fit) {
    const double from = request.fit_from.value_or(-INFINITY);
    const double to = request.fit_to.value_or(INFINITY);
    std::vector<double> x, y;
    for (std::size_t j = 0; j < points.from.size(); ++j) {
      if (points.from[j] >= from && points.from[j] <= to) {
        x.push_back(points.from[j]);
        y.push_back(points.to[j]);
      }
    }
    if (x.size() < 4) {
      throw std::runtime_error(fmt::format(
          "only {} return-map points to fit (need 4): widen --bound or the fit range", x.size()));
    }
    fit = FitSqrtMap(x, y);
    fmt::print(
        "fit Eq. 18:  v(j+1) = s sqrt(d - v(j)) + lambda v(j) for v(j) <= d, else lambda v(j)\n");
    fmt::print("             {}\n", fit->BriefReport());
    if (json) {
      nlohmann::json j = FitJson(*fit);
      j["command"] = "impactkit " + provenance;
      j["fit_range"] = {x.empty() ? 0.0 : *std::min_element(x.begin(), x.end()),
                        x.empty() ? 0.0 : *std::max_element(x.begin(), x.end())};
      j["system"] = nlohmann::json::parse(SystemToJson(system));
      json->Write(j.dump(2) + "\n");
      json->Commit();
      fmt::print("wrote:       {}\n", request.json);
    }
  }

  if (!request.plot.empty()) {
    LineChart chart;
    chart.title =
        fmt::format("return map of impacts with v < {}, omega = {}", request.bound, system.omega);
    chart.x_label = "v(j)";
    chart.y_label = "v(j+1)";
    chart.curves.push_back({"impacts", points.from, points.to, false, "#1f4e9a", true});
    if (fit && !points.from.empty()) {
      Curve curve{fmt::format("Eq. 18: s = {:.4g}, d = {:.4g}, lambda = {:.4g}", fit->parameters.s,
                              fit->parameters.d, fit->parameters.lambda),
                  {},
                  {},
                  true,
                  "#c0392b",
                  false};
      const auto [lo, hi] = std::minmax_element(points.from.begin(), points.from.end());
      for (int k = 0; k <= 800; ++k) {
        const double v = *lo + (*hi - *lo) * k / 800.0;
        curve.x.push_back(v);
        curve.y.push_back(SqrtMap(fit->parameters, v));
      }
      chart.curves.push_back(curve);
    }
    WritePng(request.plot, chart);
  }
}

// ---- lyapunov --------------------------------------------------------------

struct LyapunovRequest {
  SystemOptions system;
  int transient = 500;
  LyapunovOptions options;
  std::string json;
};

void RunLyapunov(const LyapunovRequest& request) {
  if (request.transient < 0) {
    throw InvalidInput(fmt::format("--transient must be >= 0, got {}", request.transient));
  }
  std::string error;
  if (!request.options.IsValid(&error)) throw InvalidInput(error);
  const System system = ResolveSystem(request.system);
  std::optional<AtomicOutputFile> json;  // created first: a bad path fails before the work
  if (!request.json.empty()) json.emplace(request.json);

  // The start: the last impact of a run from rest (the map needs an impact state).
  ImpactRecorder recorder;
  HybridState state = RestState(system);
  const SimulationSummary run =
      Simulate(system, {}, state, request.transient * system.ForcingPeriod(), recorder);
  fmt::print("system:      {}\n", DescribeSystem(system));
  fmt::print("start:       last impact after {} periods from rest ({})\n", request.transient,
             run.BriefReport());
  LyapunovResult result;
  if (recorder.Impacts().empty()) {
    result.message = "no impact in the transient run: the motion does not impact";
  } else {
    const Impact& last = recorder.Impacts().back();
    const Eigen::VectorXd eta =
        ImpactMap(system, request.options.map).ToEta(last.t, last.x, last.v);
    result = ImpactMapLyapunov(system, eta, request.options);
  }
  if (result.valid) {
    fmt::print("impacts:     {} counted after {} transient, over time {:.6g} ({:.6g} per impact)\n",
               result.impacts_used, request.options.transient_impacts, result.time_span,
               result.time_span / result.impacts_used);
    fmt::print("exponents:   per unit time        per impact\n");
    for (double e : result.exponents) {
      fmt::print("             {:<+20.10e} {:+.10e}\n", e,
                 e * result.time_span / result.impacts_used);
    }
    fmt::print("largest:     {:+.6e} per unit time ({})\n", result.largest,
               result.largest > 0 ? "positive: chaotic" : "negative: attracting");
  } else {
    fmt::print("exponents:   not computed: {}\n", result.message);
  }
  if (json) {
    nlohmann::json j;
    j["valid"] = result.valid;
    j["message"] = result.message;
    j["exponents"] = result.exponents;
    j["largest"] = result.largest;
    j["impacts_used"] = result.impacts_used;
    j["time_span"] = result.time_span;
    j["units"] = "per unit time";
    j["system"] = nlohmann::json::parse(SystemToJson(system));
    json->Write(j.dump(2) + "\n");
    json->Commit();
    fmt::print("wrote:       {}\n", request.json);
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
  command->add_option("--out", request->out, "Write the impacts as CSV: t,phase,v")
      ->type_name("FILE.csv")
      ->group("Output");
  command->add_option("--plot", request->plot, "Plot phase against impact speed (PNG, gnuplot)")
      ->type_name("FILE.png")
      ->group("Output");
  command->callback([request] { RunImpactMap(*request); });
}

void AddReturnMapCommand(CLI::App& app) {
  auto request = std::make_shared<ReturnMapRequest>();
  CLI::App* command = app.add_subcommand(
      "returnmap",
      "Return map v(j) -> v(j+1) of the low-velocity impacts of a long run (the paper's Fig. "
      "10): the impacts slower than --bound, in order, each paired with the next such impact. "
      "With --fit, least-squares fit of the square-root map (Eq. 18) through Ceres, with "
      "standard errors from the covariance.");
  AddSystemOptions(*command, request->system);
  AddRunOptions(*command, request->run, 5000);
  command->add_option("--bound", request->bound, "Impacts slower than this enter the map")
      ->capture_default_str()
      ->group("Map");
  command->add_flag("--fit", request->fit, "Fit Eq. 18 to the return map and report it")
      ->group("Fit");
  command
      ->add_option("--fit-from", request->fit_from,
                   "Fit only points with v(j) >= this (default: all)")
      ->group("Fit");
  command
      ->add_option("--fit-to", request->fit_to, "Fit only points with v(j) <= this (default: all)")
      ->group("Fit");
  command->add_option("--out", request->out, "Write the pairs as CSV: v_j,v_next")
      ->type_name("FILE.csv")
      ->group("Output");
  command->add_option("--plot", request->plot, "Plot the return map (and the fit) as PNG")
      ->type_name("FILE.png")
      ->group("Output");
  command
      ->add_option("--json", request->json,
                   "Write the fit as JSON: parameters, standard_error, covariance, "
                   "rms_residual, sigma, points")
      ->type_name("FILE.json")
      ->group("Output");
  command->callback([request] { RunReturnMap(*request); });
}

void AddLyapunovCommand(CLI::App& app) {
  auto request = std::make_shared<LyapunovRequest>();
  CLI::App* command = app.add_subcommand(
      "lyapunov",
      "Lyapunov exponents of the impact map (all 2N, per unit time) from QR-orthonormalised "
      "products of its analytic Jacobians, started at the last impact of a run from rest.");
  AddSystemOptions(*command, request->system);
  command
      ->add_option("--transient", request->transient,
                   "Forcing periods simulated from rest to reach the attractor")
      ->capture_default_str()
      ->group("Run");
  command
      ->add_option("--transient-impacts", request->options.transient_impacts,
                   "Map iterations that align the frame, not counted")
      ->capture_default_str()
      ->group("Run");
  command->add_option("--impacts", request->options.impacts, "Map iterations counted")
      ->capture_default_str()
      ->group("Run");
  command
      ->add_option("--json", request->json,
                   "Write the result as JSON: valid, message, exponents, largest, impacts_used, "
                   "time_span, system")
      ->type_name("FILE.json")
      ->group("Output");
  command->callback([request] { RunLyapunov(*request); });
}

}  // namespace impactkit::cli
