#include "simulate/output.hpp"

#include <fmt/format.h>

#include <array>

#include "common/output.hpp"
#include "common/plot.hpp"
#include "simulate/summary.hpp"

namespace impactkit::cli {
namespace {

std::vector<std::string> Numbered(const std::string& prefix, int count) {
  std::vector<std::string> names;
  for (int i = 1; i <= count; ++i) names.push_back(prefix + std::to_string(i));
  return names;
}

/// `first`, then x1..xN and v1..vN, then `last`.
std::vector<std::string> StateColumns(std::vector<std::string> first, int dof,
                                      const std::vector<std::string>& last) {
  for (const auto& names : {Numbered("x", dof), Numbered("v", dof), last}) {
    first.insert(first.end(), names.begin(), names.end());
  }
  return first;
}

void AppendState(std::vector<double>& row, const Eigen::Ref<const Eigen::VectorXd>& x,
                 const Eigen::Ref<const Eigen::VectorXd>& v) {
  row.insert(row.end(), x.begin(), x.end());
  row.insert(row.end(), v.begin(), v.end());
}

bool HasStop(const System& system, int dof) {
  for (const StopParameters& stop : system.stops) {
    if (stop.dof == dof) return true;
  }
  return false;
}

/// The paper's Fig. 4 style: the masses at stops solid and dark, the others
/// dashed in distinct colours, each stop as a dotted line.
LineChart TimeSeriesChart(const SimulateResult& result) {
  static constexpr std::array<const char*, 6> kPalette = {"#1f77b4", "#d62728", "#2ca02c",
                                                          "#9467bd", "#ff7f0e", "#8c564b"};
  const System& system = result.system;
  LineChart chart;
  const StopParameters& first = system.stops[0];
  chart.title =
      system.StopCount() == 1
          ? fmt::format("impactkit simulate: Ω = {:.6g}, xs = {:.6g}, r = {:.6g}: {}", system.omega,
                        first.position, first.restitution, MotionLabel(result.analysis))
          : fmt::format("impactkit simulate: Ω = {:.6g}, {} stops: {}", system.omega,
                        system.StopCount(), MotionLabel(result.analysis));
  chart.x_label = "t";
  chart.y_label = "displacement";
  const SampleLog& samples = result.recorders.series->Samples();
  for (int i = 0, other = 0; i < system.Dof(); ++i) {
    Curve curve;
    curve.title = fmt::format("x{}", i + 1);
    curve.dashed = !HasStop(system, i);
    if (curve.dashed) curve.color = kPalette[other++ % kPalette.size()];
    for (const SampleView sample : samples) {
      curve.x.push_back(sample.t);
      curve.y.push_back(sample.x(i));
    }
    chart.curves.push_back(std::move(curve));
  }
  for (int k = 0; k < system.StopCount(); ++k) {
    const StopParameters& stop = system.stops[k];
    chart.lines.push_back(
        {stop.position,
         system.StopCount() == 1
             ? fmt::format("stop xs = {:.6g}", stop.position)
             : fmt::format("stop {}: x{} {} {:.6g}", k + 1, stop.dof + 1,
                           stop.side == StopSide::kUpper ? "<=" : ">=", stop.position)});
  }
  return chart;
}

}  // namespace

SimulateOutputs::SimulateOutputs(const SimulateRequest& request, const System& system,
                                 Provenance provenance)
    : provenance_(std::move(provenance)) {
  const int dof = system.Dof();
  if (!request.series.empty()) {
    series_ = &set_.AddCsv(request.series, provenance_.Text(),
                           StateColumns({"t"}, dof, {"stuck", "event"}));
  }
  if (!request.impacts.empty()) {
    impacts_ = &set_.AddCsv(request.impacts, provenance_.Text(),
                            StateColumns({"t", "phase", "velocity"}, dof, {"stop"}));
  }
  plot_ = AddIfAsked(set_, request.plot);
  json_ = AddIfAsked(set_, request.json);
}

void SimulateOutputs::Write(const SimulateResult& result) {
  // Everything is written to the temporaries first and committed last, so a
  // failure (gnuplot, a full disk) leaves no partial set of files either.
  if (series_) WriteSeries(result);
  if (impacts_) WriteImpacts(result);
  if (plot_) WriteChart(*plot_, TimeSeriesChart(result));
  if (json_) json_->Write(SummaryJson(result, provenance_) + "\n");
  set_.Commit();
}

void SimulateOutputs::WriteSeries(const SimulateResult& result) {
  std::vector<double> row;
  std::vector<std::string> event(1);
  for (const SampleView sample : result.recorders.series->Samples()) {
    row.assign({sample.t});
    AppendState(row, sample.x, sample.v);
    row.push_back(sample.stuck ? 1.0 : 0.0);
    // Grid rows leave the event empty: a reader filters on it.
    event[0] = sample.kind == SampleKind::kGrid ? "" : ToString(sample.kind);
    series_->WriteRow(row, event);
  }
}

void SimulateOutputs::WriteImpacts(const SimulateResult& result) {
  std::vector<double> row;
  for (const ImpactView impact : result.recorders.steady.Impacts()) {
    row.assign({impact.t, impact.phase, impact.velocity});
    AppendState(row, impact.x, impact.v);
    row.push_back(impact.stop + 1);  // stops count from 1 in files, as in the system file
    impacts_->WriteRow(row);
  }
}

}  // namespace impactkit::cli
