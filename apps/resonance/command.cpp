/// `impactkit resonance`: the resonance curves of the system without its stop
/// (the paper's Fig. 2), from the closed form of resonance.hpp.

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/resonance.hpp"
#include "impactkit/io/output_set.hpp"

namespace impactkit::cli {
namespace {

struct ResonanceRequest {
  SystemOptions system;
  double from = 0.1;
  double to = 2.5;
  int steps = 2401;
  std::string out;
  std::string plot;
};

void RunResonance(const ResonanceRequest& request) {
  const System system = ResolveSystem(request.system);
  const int n = system.Dof();
  std::vector<std::string> columns{"omega"};
  for (int i = 1; i <= n; ++i) columns.push_back(fmt::format("range_x{}", i));
  for (int i = 1; i <= n; ++i) columns.push_back(fmt::format("phase_x{}", i));
  Require(request.steps >= 1, fmt::format("--steps must be >= 1, got {}", request.steps));
  Require(request.from > 0 && request.from <= request.to && std::isfinite(request.to),
          fmt::format("--from and --to must satisfy 0 < --from <= --to (finite), got --from {}, "
                      "--to {}",
                      request.from, request.to));
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;  // created first: a bad path fails before the work
  CsvWriter* csv = nullptr;
  if (!request.out.empty()) {
    const Provenance provenance =
        MakeProvenance(request.system, system,
                       fmt::format("resonance --from {} --to {} --steps {}", request.from,
                                   request.to, request.steps));
    csv = &outputs.AddCsv(request.out, provenance.Text(), columns);
  }
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);
  const std::vector<ResonancePoint> curve =
      ResonanceCurve(system, request.from, request.to, request.steps);
  const std::vector<ResonancePeak> peaks = ResonancePeaks(system, curve);

  fmt::print("system:      {} (stop ignored: the linear chain)\n", DescribeSystem(system));
  fmt::print("curve:       max-min of x_i = 2|X_i(omega)|, {} values of omega in [{}, {}]\n",
             request.steps, request.from, request.to);
  fmt::print("peaks:       mass   omega            max-min\n");
  for (const ResonancePeak& peak : peaks) {
    fmt::print("             x{:<5} {:<16.10f} {:.10g}\n", peak.dof + 1, peak.omega, peak.range);
  }
  if (peaks.empty()) fmt::print("             none inside the range\n");
  if (csv) {
    std::vector<double> row(1 + 2 * n);
    for (const ResonancePoint& point : curve) {
      row[0] = point.omega;
      for (int i = 0; i < n; ++i) {
        row[1 + i] = point.range(i);
        row[1 + n + i] = point.phase(i);
      }
      csv->WriteRow(row);
    }
  }
  if (plot) {
    LineChart chart;
    chart.title = "resonance curves without the stop";
    chart.x_label = "forcing frequency Ω";
    chart.y_from_zero = true;
    chart.y_label = "max - min displacement";
    // The paper's Fig. 2: x_N solid, the other masses dashed.
    static const char* const kColors[] = {"#1f4e9a", "#c0392b", "#27ae60", "#8e44ad", "#d35400"};
    for (int i = n - 1; i >= 0; --i) {
      Curve c;
      c.title = fmt::format("x{}", i + 1);
      c.dashed = i != n - 1;
      c.color = kColors[i % 5];
      for (const ResonancePoint& point : curve) {
        c.x.push_back(point.omega);
        c.y.push_back(point.range(i));
      }
      chart.curves.push_back(c);
    }
    WriteChart(*plot, chart);
  }
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:       {}\n", *path);
  }
}

}  // namespace

void AddResonanceCommand(CLI::App& app) {
  auto request = std::make_shared<ResonanceRequest>();
  CLI::App* command = app.add_subcommand(
      "resonance",
      "Resonance curves of the system without its stop (the paper's Fig. 2): the max-min "
      "displacement 2|X_i| of each mass in the steady response, X = (K - omega^2 M + i omega "
      "C)^-1 A, over a range of omega, and the peaks.");
  AddSystemOptions(*command, request->system);
  command->add_option("--from", request->from, "First omega (> 0)")
      ->capture_default_str()
      ->group("Range");
  command->add_option("--to", request->to, "Last omega (>= --from)")
      ->capture_default_str()
      ->group("Range");
  command->add_option("--steps", request->steps, "Number of omega values, evenly spaced (>= 1)")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group("Range");
  command
      ->add_option("--out", request->out,
                   "Write the curve as CSV: omega,range_x1..range_xN,phase_x1..phase_xN")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group("Output");
  command->add_option("--plot", request->plot, "Plot the curves (needs gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command->callback([request] { RunResonance(*request); });
}

}  // namespace impactkit::cli
