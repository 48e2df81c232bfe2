/// `impactkit simulate`: its flags, mapped onto a SimulateRequest
/// (simulate/run.hpp does the work).

#include <fmt/format.h>

#include <memory>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/system_options.hpp"
#include "simulate/run.hpp"

namespace impactkit::cli {
namespace {

void AddRunOptions(CLI::App& command, SimulateRequest& request) {
  const std::string group = "Run";
  command
      .add_option("--transient", request.transient,
                  "Forcing periods to run and discard before recording")
      ->type_name("N")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command.add_option("--periods", request.periods, "Forcing periods to record")
      ->type_name("N")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--samples-per-period", request.samples_per_period,
                  "Samples per forcing period in --series and --plot")
      ->type_name("K")
      ->check(AtMost(kMaxSamplesPerPeriod, "samples per period"))
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--x0", request.x0,
                  "Initial positions x1,...,xN at t = 0 (default: all 0); the contact mass "
                  "must start at or below xs")
      ->type_name("X1,...,XN")
      ->delimiter(',')
      ->group(group);
  command.add_option("--v0", request.v0, "Initial velocities v1,...,vN at t = 0 (default: all 0)")
      ->type_name("V1,...,VN")
      ->delimiter(',')
      ->group(group);
  command
      .add_option_function<std::string>(
          "--chatter",
          [&request](const std::string& method) {
            request.chatter =
                method == "threshold" ? ChatterMethod::kThreshold : ChatterMethod::kAccumulation;
          },
          "How an accumulating sequence of impacts ends: 'accumulation' jumps to its predicted "
          "accumulation point (Budd & Dux); 'threshold' sticks once two impacts come closer "
          "than --chatter-threshold (the paper's rule)")
      ->type_name("METHOD")
      ->check(CLI::IsMember({"accumulation", "threshold"}))
      ->default_str("accumulation")
      ->group(group);
  command
      .add_option("--chatter-threshold", request.chatter_threshold,
                  fmt::format("With --chatter threshold: the inter-impact time below which "
                              "the mass sticks (default {})",
                              SimulationOptions{}.chatter_threshold))
      ->type_name("DT")
      ->group(group);
}

void AddOutputOptions(CLI::App& command, SimulateRequest& request) {
  const std::string group = "Output (each written only if asked for, and only whole)";
  command
      .add_option("--series", request.series,
                  "Time series CSV of the window: columns t,x1..xN,v1..vN,stuck")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(group);
  command
      .add_option("--impacts", request.impacts,
                  "Impacts CSV of the window: columns t,phase,velocity,x1..xN,v1..vN; velocity is "
                  "the impact speed of the contact mass, x and v the state just before impact")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(group);
  command
      .add_option("--plot", request.plot,
                  "Figure of x1..xN against t over the window, stop marked (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group(group);
  command
      .add_option("--json", request.json,
                  "Summary as JSON: system, run, window, impacts, motion, final state")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group(group);
}

}  // namespace

void AddSimulateCommand(CLI::App& app) {
  // Owned by the callback, which CLI11 keeps alive as long as the app.
  auto request = std::make_shared<SimulateRequest>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate from an initial state: discard a transient of whole forcing periods, record a "
      "window, summarise it (impacts per period, sticking, chatter, the motion's period "
      "P(p,q)) and write it as CSV, PNG or JSON.");
  AddSystemOptions(*command, request->system);
  AddRunOptions(*command, *request);
  AddOutputOptions(*command, *request);
  command->callback([request] { RunSimulate(*request); });
}

}  // namespace impactkit::cli
