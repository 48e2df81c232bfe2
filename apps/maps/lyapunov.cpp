/// `impactkit lyapunov`: the Lyapunov exponents of the impact map, started
/// at the last impact of a run from rest (impactkit/analysis/lyapunov.hpp
/// does the work).

#include "impactkit/analysis/lyapunov.hpp"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit::cli {
namespace {

struct LyapunovRequest {
  SystemOptions system;
  int transient = 500;
  LyapunovOptions options;
  std::string json;
};

void RunLyapunov(const LyapunovRequest& request) {
  Require(request.transient >= 0,
          fmt::format("--transient must be >= 0, got {}", request.transient));
  std::string error;
  Require(request.options.impacts >= 1,
          fmt::format("--impacts must be >= 1, got {}", request.options.impacts));
  Require(
      request.options.transient_impacts >= 0,
      fmt::format("--transient-impacts must be >= 0, got {}", request.options.transient_impacts));
  Require(request.options.IsValid(&error), error);
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
    const ImpactView last = recorder.Impacts().back();
    LyapunovOptions options = request.options;
    options.map.stop = last.stop;
    const Eigen::VectorXd eta = ImpactMap(system, options.map).ToEta(last.t, last.x, last.v);
    result = ImpactMapLyapunov(system, eta, options);
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
    j["provenance"] =
        MakeProvenance(request.system, system,
                       fmt::format("lyapunov --transient {} --impacts {} --transient-impacts {}",
                                   request.transient, request.options.impacts,
                                   request.options.transient_impacts))
            .Json();
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
  // No exponents is no result: exit status 1, after the stdout line and the
  // JSON (valid: false) that record why.
  if (!result.valid) {
    throw std::runtime_error(fmt::format("Lyapunov exponents not computed: {}", result.message));
  }
}

}  // namespace

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
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group("Run");
  command
      ->add_option("--transient-impacts", request->options.transient_impacts,
                   "Map iterations that align the frame, not counted")
      ->check(AtMost(kMaxImpacts, "impacts"))
      ->capture_default_str()
      ->group("Run");
  command->add_option("--impacts", request->options.impacts, "Map iterations counted")
      ->check(AtMost(kMaxImpacts, "impacts"))
      ->capture_default_str()
      ->group("Run");
  command
      ->add_option("--json", request->json,
                   "Write the result as JSON: valid, message, exponents, largest, impacts_used, "
                   "time_span, system")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command->callback([request] { RunLyapunov(*request); });
}

}  // namespace impactkit::cli
