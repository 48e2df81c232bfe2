/// `impactkit returnmap`: the return map v(j) -> v(j+1) of the slow impacts
/// of a long run (the paper's Fig. 10) and, with --fit, the square-root map
/// of Eq. 18 fitted to it (impactkit/analysis/map_fit.hpp does the work).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/map_fit.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"
#include "maps/run.hpp"

namespace impactkit::cli {
namespace {

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
  Require(request.bound > 0.0, fmt::format("--bound must be > 0, got {}", request.bound));
  Require(request.fit || !(request.fit_from || request.fit_to || !request.json.empty()),
          "--fit-from, --fit-to and --json need --fit");
  const System system = ResolveSystem(request.system);
  const Provenance provenance = RunProvenance(fmt::format("returnmap --bound {}", request.bound),
                                              request.run, request.system, system);
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;  // created first: a bad path fails before the work
  CsvWriter* csv = nullptr;
  if (!request.out.empty()) {
    csv =
        &outputs.AddCsv(request.out, provenance.Text(), std::vector<std::string>{"v_j", "v_next"});
  }
  AtomicOutputFile* json = AddIfAsked(outputs, request.json);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);

  const RecordedRun recorded = RecordImpacts(system, request.run);
  PrintRun(system, request.run, recorded);
  std::vector<double> speeds;
  for (const ImpactView impact : recorded.impacts) speeds.push_back(impact.velocity);
  const ReturnMapPoints points = LowVelocityReturnMap(speeds, request.bound);
  fmt::print("return map:  {} pairs of successive impacts with speed < {} (of {} impacts)\n",
             points.from.size(), request.bound, speeds.size());
  for (std::size_t j = 0; j < points.from.size(); ++j) {
    if (csv) csv->WriteRow(std::vector<double>{points.from[j], points.to[j]});
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
      j["provenance"] = provenance.Json();
      j["fit_range"] = {x.empty() ? 0.0 : *std::min_element(x.begin(), x.end()),
                        x.empty() ? 0.0 : *std::max_element(x.begin(), x.end())};
      j["system"] = nlohmann::json::parse(SystemToJson(system));
      json->Write(j.dump(2) + "\n");
    }
  }

  if (plot) {
    LineChart chart;
    chart.title =
        fmt::format("return map of impacts with v < {}, Ω = {}", request.bound, system.omega);
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
    WriteChart(*plot, chart);
  }
  // All files together, then the verdict: a fit that did not converge is
  // still written (its JSON records how it ended).
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.json, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:       {}\n", *path);
  }
  // A fit that did not converge is no fit: exit status 1, after the report
  // (and the JSON with its termination) that say how it ended.
  if (fit && fit->termination != Termination::kConverged) {
    throw std::runtime_error(fmt::format("the Eq. 18 fit did not converge ({}): {}",
                                         Describe(fit->termination), fit->message));
  }
}

}  // namespace

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
      ->check(OutputPath())
      ->group("Output");
  command->add_option("--plot", request->plot, "Plot the return map (and the fit) (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command
      ->add_option("--json", request->json,
                   "Write the fit as JSON: parameters, standard_error, covariance, "
                   "rms_residual, sigma, points")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command->callback([request] { RunReturnMap(*request); });
}

}  // namespace impactkit::cli
