// impactkit.sweep, impactkit.lyapunov, impactkit.resonance:
// analysis/sweep.hpp, analysis/lyapunov.hpp, analysis/resonance.hpp.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "impactkit/analysis/grid_cell.hpp"
#include "impactkit/analysis/lyapunov.hpp"
#include "impactkit/analysis/resonance.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/io/sweep_output.hpp"
#include "option_sets.hpp"

namespace impactkit::python {
namespace {

/// The sweep's points as columns: one entry per value, and the impacts and
/// the per-period ranges of all values concatenated, `impact_offsets` and
/// `range_offsets` (K + 1 each) marking where each value's start (value k
/// owns entries offsets[k] .. offsets[k+1]); and the table `impactkit sweep
/// --summary` writes, as CSV text without provenance (the library's columns
/// and rows, io/sweep_output.hpp), which SweepResult.to_pandas reads.
py::dict SweepArrays(const SweepResult& result, const std::string& parameter) {
  std::vector<double> value, range_contact, range_first, impact_t, impact_phase, impact_velocity;
  std::vector<std::int64_t> offsets{0}, range_offsets{0}, p, q, impact_stop;
  std::string summary = CsvHead(SweepSummaryColumns(parameter), "");
  py::list kind, description;
  for (const SweepPoint& point : result.points) {
    value.push_back(point.value);
    range_contact.insert(range_contact.end(), point.range_contact.begin(),
                         point.range_contact.end());
    range_first.insert(range_first.end(), point.range_first.begin(), point.range_first.end());
    range_offsets.push_back(static_cast<std::int64_t>(range_contact.size()));
    for (const SweepImpact& impact : point.impacts) {
      impact_t.push_back(impact.t);
      impact_phase.push_back(impact.phase);
      impact_velocity.push_back(impact.velocity);
      impact_stop.push_back(impact.stop);
    }
    summary += SweepSummaryRow(point);
    offsets.push_back(static_cast<std::int64_t>(impact_t.size()));
    kind.append(ToString(point.classification.kind));
    description.append(point.classification.ToString());
    // The schema of every output (docs/cli.md, "Motion kinds"); in an
    // integer array p = 0 where it is inf (sticking) or undefined: kind says which.
    const GridCell cell = CellOf(0, point);
    p.push_back(cell.p);
    q.push_back(cell.q);
  }
  py::dict out;
  out["values"] = MoveToArray(std::move(value));
  out["kind"] = kind;
  out["description"] = description;
  out["p"] = MoveToArray(std::move(p));
  out["q"] = MoveToArray(std::move(q));
  out["range_contact"] = MoveToArray(std::move(range_contact));
  out["range_first"] = MoveToArray(std::move(range_first));
  out["range_offsets"] = MoveToArray(std::move(range_offsets));
  out["impact_offsets"] = MoveToArray(std::move(offsets));
  out["impact_t"] = MoveToArray(std::move(impact_t));
  out["impact_phase"] = MoveToArray(std::move(impact_phase));
  out["impact_velocity"] = MoveToArray(std::move(impact_velocity));
  out["impact_stop"] = MoveToArray(std::move(impact_stop));
  out["summary_csv"] = summary;
  out["termination"] = ToString(result.termination);
  out["report"] = result.BriefReport();
  return out;
}

py::dict SweepPy(const System& system, const std::string& parameter, double from, double to,
                 int steps, int transient_periods, int recorded_periods, int threads,
                 const std::string& each_from, int chunk_values, bool full_transient,
                 const py::object& progress) {
  SweepOptions options;
  options.parameter = parameter;
  options.from = from;
  options.to = to;
  options.steps = steps;
  options.transient_periods = transient_periods;
  options.recorded_periods = recorded_periods;
  options.threads = threads;
  options.chunk_values = chunk_values;
  options.full_transient = full_transient;
  options.start = StartFromName(each_from);
  const InterruptibleRun run(progress);
  const SweepResult result = WithoutGil([&] { return RunSweep(system, options, run); });
  return SweepArrays(result, parameter);
}

py::dict LyapunovPy(const System& system, const Eigen::VectorXd& eta, int impacts,
                    int transient_impacts) {
  LyapunovOptions options;
  options.impacts = impacts;
  options.transient_impacts = transient_impacts;
  const LyapunovResult result = WithoutGil([&] { return ImpactMapLyapunov(system, eta, options); });
  if (!result.valid) ThrowNumericalError(result.message);
  std::vector<double> exponents = result.exponents;
  py::dict out;
  out["exponents"] = MoveToArray(std::move(exponents));
  out["largest"] = result.largest;
  out["impacts_used"] = result.impacts_used;
  out["time_span"] = result.time_span;
  return out;
}

py::dict ResonancePy(const System& system, double from, double to, int steps) {
  const std::vector<ResonancePoint> curve = ResonanceCurve(system, from, to, steps);
  const auto n = static_cast<py::ssize_t>(curve.size());
  const py::ssize_t dof = system.Dof();
  std::vector<double> omega, range, phase;
  for (const ResonancePoint& point : curve) {
    omega.push_back(point.omega);
    range.insert(range.end(), point.range.begin(), point.range.end());
    phase.insert(phase.end(), point.phase.begin(), point.phase.end());
  }
  py::list peaks;
  for (const ResonancePeak& peak : ResonancePeaks(system, curve)) {
    peaks.append(py::dict(py::arg("dof") = peak.dof, py::arg("omega") = peak.omega,
                          py::arg("range") = peak.range));
  }
  py::dict out;
  out["omega"] = MoveToArray(std::move(omega));
  out["range"] = MoveToArray<double, 2>(std::move(range), {n, dof});
  out["phase"] = MoveToArray<double, 2>(std::move(phase), {n, dof});
  out["peaks"] = peaks;
  return out;
}

/// impactkit.SweepOptions: the keywords of sweep, over SweepOptions.
void BindSweepOptions(py::module_& module, const SweepOptions& defaults) {
  OptionSetBinding<SweepOptions>(defaults)
      .Field("parameter", &SweepOptions::parameter,
             "The swept parameter: a name of System.parameter_names().")
      .Field("from_", &SweepOptions::from, "One end of the range.")
      .Field("to", &SweepOptions::to, "The other end (either order).")
      .Field("steps", &SweepOptions::steps, "K >= 1 values, both ends included (K = 1: from_).")
      .Field("transient_periods", &SweepOptions::transient_periods,
             "Forcing periods run and discarded at each value (>= 0).")
      .Field("recorded_periods", &SweepOptions::recorded_periods,
             "Forcing periods recorded at each value (>= 1).")
      .Field("threads", &SweepOptions::threads,
             "Worker threads (>= 1); results do not depend on it.")
      .Converted(
          "each_from", [](const SweepOptions& o) { return StartName(o.start); },
          [](SweepOptions& o, const std::string& name) { o.start = StartFromName(name); },
          "Where each value starts: 'previous' (the previous value's final state) or "
          "'rest'.")
      .Field("chunk_values", &SweepOptions::chunk_values,
             "Consecutive values per chunk (>= 0; 0: one chunk). Part of the result's "
             "definition: change it and the chunk boundaries move.")
      .Field("full_transient", &SweepOptions::full_transient,
             "Run every value's whole transient: no early end at an orbit confirmed by a Newton "
             "solve (the same class from the same start; docs/grids.md).")
      .Bind(module, "SweepOptions",
            "The keywords of impactkit.sweep (but system), with its defaults: the library's "
            "SweepOptions (analysis/sweep.hpp). impactkit.sweep(system, "
            "**impactkit.SweepOptions(steps=11)) passes a set.");
}

}  // namespace

SweepStart StartFromName(const std::string& each_from) {
  if (each_from == "previous") return SweepStart::kPrevious;
  if (each_from == "rest") return SweepStart::kFixed;
  throw InvalidInput("each_from must be 'previous' or 'rest', got '" + each_from + "'");
}

std::string StartName(SweepStart start) {
  return start == SweepStart::kPrevious ? "previous" : "rest";
}

void BindAnalysis(py::module_& module) {
  // The defaults are the library's, as the command line's are: those of the
  // function's keywords and of SweepOptions, from the same struct.
  const SweepOptions kSweep;
  BindSweepOptions(module, kSweep);
  module.def(
      "sweep", &SweepPy, py::arg("system"), py::kw_only(), py::arg("parameter") = kSweep.parameter,
      py::arg("from_") = kSweep.from, py::arg("to") = kSweep.to, py::arg("steps") = kSweep.steps,
      py::arg("transient_periods") = kSweep.transient_periods,
      py::arg("recorded_periods") = kSweep.recorded_periods, py::arg("threads") = kSweep.threads,
      py::arg("each_from") = StartName(kSweep.start), py::arg("chunk_values") = kSweep.chunk_values,
      py::arg("full_transient") = kSweep.full_transient, py::arg("progress") = false,
      R"(Brute-force bifurcation diagram: `steps` values of a named parameter from
from_ to to, each simulated to steady state and classified.
Results do not depend on `threads`. Returns a dict: values, kind, description,
p, q (0 where undefined; a sticking motion has its q and p = 0, its kind
says so); of all values concatenated, the max - min of x_c
and of x_1 in every recorded forcing period (range_contact, range_first,
delimited by range_offsets, K + 1) and every recorded impact (impact_t,
impact_phase, impact_velocity, impact_stop (0-based), delimited by
impact_offsets); summary_csv, the table `impactkit sweep --summary` writes
(CSV text, without its provenance); termination
('completed') and report. each_from: 'previous' (each value from the previous final
state) or 'rest'. Releases the GIL; Ctrl-C raises
KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.SweepOptions's: `sweep(system, **impactkit.SweepOptions(...))`
passes a set.)");
  module.def("lyapunov", &LyapunovPy, py::arg("system"), py::arg("eta"), py::kw_only(),
             py::arg("impacts") = 2000, py::arg("transient_impacts") = 200,
             R"(Lyapunov exponents of the impact map from the impact state eta, per unit
time, descending. Returns a dict: exponents (2N,), largest, impacts_used,
time_span. Raises NumericalError when the map fails (chatter, grazing, a lost
impact), with the library's message. Releases the GIL.)");
  module.def("resonance", &ResonancePy, py::arg("system"), py::kw_only(), py::arg("from_"),
             py::arg("to"), py::arg("steps"),
             R"(Closed-form resonance curves of the system without its stop: omega (n,),
range (n, N) = max - min of each x_i (2 |X_i|), phase (n, N), and peaks (a
list of {dof, omega, range}).)");
}

}  // namespace impactkit::python
