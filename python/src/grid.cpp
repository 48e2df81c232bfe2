// impactkit.parameter_map and impactkit.basins: analysis/parameter_map.hpp,
// analysis/basins.hpp and the work units of analysis/grid_task.hpp.
#include <pybind11/stl.h>

#include <array>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "impactkit/analysis/basins.hpp"
#include "impactkit/analysis/parameter_map.hpp"
#include "option_sets.hpp"

namespace impactkit::python {
namespace {

/// The motion kinds by name, in the order of their codes (kind_code).
py::list MotionKindNames() {
  py::list kinds;
  for (const MotionKind k : {MotionKind::kPeriodic, MotionKind::kSticking, MotionKind::kChaotic,
                             MotionKind::kNonImpacting, MotionKind::kUnresolved}) {
    kinds.append(ToString(k));
  }
  return kinds;
}

/// Every unit of `task` on `threads` threads, the cells in index order.
/// Ctrl-C is checked and `progress` shown after each unit.
std::vector<GridCell> RunAll(const GridTask& task, int threads, const py::object& progress) {
  const InterruptibleRun run(progress);
  return WithoutGil([&] { return RunGrid(task, threads, run).cells; });
}

/// The cells as (rows, columns) arrays: the kind by name and by its index in
/// `kinds`, and p, q, max_velocity, range_xN, lyapunov (NaN where undefined).
py::dict CellArrays(const std::vector<GridCell>& cells, py::ssize_t rows, py::ssize_t columns) {
  const std::array<py::ssize_t, 2> shape{rows, columns};
  std::vector<std::int64_t> kind, p, q;
  std::vector<double> max_v, range, lyapunov;
  py::list names;
  for (const GridCell& cell : cells) {
    kind.push_back(static_cast<std::int64_t>(cell.kind));
    names.append(ToString(cell.kind));
    p.push_back(cell.p);
    q.push_back(cell.q);
    max_v.push_back(cell.max_v);
    range.push_back(cell.range_xN);
    lyapunov.push_back(cell.lyapunov);
  }
  py::dict out;
  out["kinds"] = MotionKindNames();
  out["kind_code"] = MoveToArray(std::move(kind), shape);
  out["kind"] = py::module_::import("numpy").attr("array")(names).attr("reshape")(rows, columns);
  out["p"] = MoveToArray(std::move(p), shape);
  out["q"] = MoveToArray(std::move(q), shape);
  out["max_velocity"] = MoveToArray(std::move(max_v), shape);
  out["range_xN"] = MoveToArray(std::move(range), shape);
  out["lyapunov"] = MoveToArray(std::move(lyapunov), shape);
  return out;
}

py::dict ParameterMapPy(const System& system, const std::string& parameter, double from, double to,
                        int steps, const std::string& parameter2, double from2, double to2,
                        int steps2, int transient_periods, int recorded_periods, int threads,
                        const std::string& each_from, int chunk_values, bool full_transient,
                        const py::object& progress) {
  ParameterMapOptions options;
  options.row.parameter = parameter;
  options.row.from = from;
  options.row.to = to;
  options.row.steps = steps;
  options.row.transient_periods = transient_periods;
  options.row.recorded_periods = recorded_periods;
  options.row.start = StartFromName(each_from);
  options.row.chunk_values = chunk_values;
  options.row.full_transient = full_transient;
  options.parameter2 = parameter2;
  options.from2 = from2;
  options.to2 = to2;
  options.steps2 = steps2;
  const ParameterMapTask task(system, options);
  const std::vector<GridCell> cells = RunAll(task, threads, progress);
  py::dict out = CellArrays(cells, static_cast<py::ssize_t>(task.Values2().size()),
                            static_cast<py::ssize_t>(task.Values1().size()));
  out["values"] = MoveToArray(std::vector<double>(task.Values1()));
  out["values2"] = MoveToArray(std::vector<double>(task.Values2()));
  return out;
}

py::dict BasinsPy(const System& system, const std::string& coordinate1, double from1, double to1,
                  int steps1, const std::string& coordinate2, double from2, double to2, int steps2,
                  int transient_periods, int recorded_periods, int threads, double orbit_tolerance,
                  bool full_transient, const py::object& progress) {
  BasinsOptions options;
  options.run.transient_periods = transient_periods;
  options.run.recorded_periods = recorded_periods;
  options.run.full_transient = full_transient;
  options.coordinate1 = coordinate1;
  options.from1 = from1;
  options.to1 = to1;
  options.steps1 = steps1;
  options.coordinate2 = coordinate2;
  options.from2 = from2;
  options.to2 = to2;
  options.steps2 = steps2;
  options.orbit_tolerance = orbit_tolerance;
  const BasinsTask task(system, options);
  const std::vector<GridCell> cells = RunAll(task, threads, progress);
  const auto rows = static_cast<py::ssize_t>(task.Values2().size());
  const auto columns = static_cast<py::ssize_t>(task.Values1().size());
  py::dict out = CellArrays(cells, rows, columns);
  BasinsResult basins = IdentifyAttractors(cells, system.ForcingPeriod(), options.orbit_tolerance);
  std::vector<std::int64_t> attractor(basins.attractor.begin(), basins.attractor.end());
  out["attractor"] = MoveToArray<std::int64_t, 2>(std::move(attractor), {rows, columns});
  py::list attractors;
  for (const Attractor& a : basins.attractors) {
    std::vector<double> phases, speeds;
    for (const AttractorImpact& impact : a.orbit) {
      phases.push_back(impact.phase);
      speeds.push_back(impact.velocity);
    }
    attractors.append(py::dict(py::arg("kind") = ToString(a.kind), py::arg("p") = a.p,
                               py::arg("q") = a.q, py::arg("cells") = a.cells,
                               py::arg("phases") = MoveToArray(std::move(phases)),
                               py::arg("speeds") = MoveToArray(std::move(speeds))));
  }
  out["attractors"] = attractors;
  out["values"] = MoveToArray(std::vector<double>(task.Values1()));
  out["values2"] = MoveToArray(std::vector<double>(task.Values2()));
  return out;
}

/// The defaults of basins and BasinsOptions: the library's, but for the
/// coordinates, which are the command line's (`impactkit basins` --coord
/// x2 --coord2 v2, the paper's contact mass) rather than BasinsOptions' x1
/// and v1, so that a call without them computes what the command line does.
BasinsOptions BasinsDefaults() {
  BasinsOptions options;
  options.coordinate1 = "x2";
  options.coordinate2 = "v2";
  return options;
}

/// impactkit.MapOptions: the keywords of parameter_map (but system), over
/// ParameterMapOptions (the row's sweep in its `row`).
void BindMapOptions(py::module_& module, const ParameterMapOptions& defaults) {
  OptionSetBinding<ParameterMapOptions>(defaults)
      .Field(
          "parameter", [](auto& o) -> auto& { return o.row.parameter; },
          "The row parameter, swept along each row: a name of System.parameter_names().")
      .Required(
          "from_", [](auto& o) -> auto& { return o.row.from; }, "One end of its range.")
      .Required(
          "to", [](auto& o) -> auto& { return o.row.to; }, "The other end (either order).")
      .Required(
          "steps", [](auto& o) -> auto& { return o.row.steps; },
          "K >= 1 values per row, both ends included.")
      .Field("parameter2", &ParameterMapOptions::parameter2,
             "The column parameter, one value per row: not the row parameter.")
      .Required("from2", &ParameterMapOptions::from2, "One end of its range.")
      .Required("to2", &ParameterMapOptions::to2, "The other (either order; ascending rows).")
      .Required("steps2", &ParameterMapOptions::steps2, "L >= 1 rows, both ends included.")
      .Field(
          "transient_periods", [](auto& o) -> auto& { return o.row.transient_periods; },
          "Forcing periods run and discarded at each value (>= 0).")
      .Field(
          "recorded_periods", [](auto& o) -> auto& { return o.row.recorded_periods; },
          "Forcing periods recorded at each value (>= 1).")
      .Field(
          "threads", [](auto& o) -> auto& { return o.row.threads; },
          "Worker threads (>= 1); the result does not depend on it.")
      .Converted(
          "each_from", [](const ParameterMapOptions& o) { return StartName(o.row.start); },
          [](ParameterMapOptions& o, const std::string& name) {
            o.row.start = StartFromName(name);
          },
          "Where each value of a row starts: 'previous' (the previous value's final state) "
          "or 'rest'.")
      .Field(
          "chunk_values", [](auto& o) -> auto& { return o.row.chunk_values; },
          "Consecutive values per chunk of a row (>= 0; 0: one chunk). Part of the result's "
          "definition: change it and the chunk boundaries move.")
      .Field(
          "full_transient", [](auto& o) -> auto& { return o.row.full_transient; },
          "Run every cell's whole transient: no early end at an orbit confirmed by a Newton "
          "solve (the same class from the same start; docs/grids.md).")
      .Bind(module, "MapOptions",
            "The keywords of impactkit.parameter_map (but system), with its defaults: the "
            "library's ParameterMapOptions (analysis/parameter_map.hpp). The ranges and steps "
            "have none: impactkit.parameter_map(system, **impactkit.MapOptions(from_=1.7, "
            "to=1.9, steps=3, from2=0.6, to2=0.8, steps2=2)) passes a set.");
}

/// impactkit.BasinsOptions: the keywords of basins (but system), over
/// BasinsOptions (the cells' run in its `run`).
void BindBasinsOptions(py::module_& module, const BasinsOptions& defaults) {
  OptionSetBinding<BasinsOptions>(defaults)
      .Field("coordinate", &BasinsOptions::coordinate1,
             "The state coordinate that varies along a row: 'x1'..'xN' or 'v1'..'vN' (the "
             "others at rest).")
      .Required("from_", &BasinsOptions::from1, "One end of its range.")
      .Required("to", &BasinsOptions::to1, "The other end (either order).")
      .Required("steps", &BasinsOptions::steps1, "K >= 1 values per row.")
      .Field("coordinate2", &BasinsOptions::coordinate2,
             "The state coordinate that varies from row to row (ascending).")
      .Required("from2", &BasinsOptions::from2, "One end of its range.")
      .Required("to2", &BasinsOptions::to2, "The other end (either order).")
      .Required("steps2", &BasinsOptions::steps2, "L >= 1 rows.")
      .Field(
          "transient_periods", [](auto& o) -> auto& { return o.run.transient_periods; },
          "Forcing periods run and discarded from each start (>= 0).")
      .Field(
          "recorded_periods", [](auto& o) -> auto& { return o.run.recorded_periods; },
          "Forcing periods recorded from each start (>= 1).")
      .Field(
          "threads", [](auto& o) -> auto& { return o.run.threads; },
          "Worker threads (>= 1); the result does not depend on it.")
      .Field("orbit_tolerance", &BasinsOptions::orbit_tolerance,
             "Relative distance under which two impacts are the same: phases within "
             "tolerance * T, speeds within tolerance * max(1, |v|).")
      .Field(
          "full_transient", [](auto& o) -> auto& { return o.run.full_transient; },
          "Run every start's whole transient: no early end at an orbit confirmed by a Newton "
          "solve (the same class from the same start; docs/grids.md).")
      .Bind(module, "BasinsOptions",
            "The keywords of impactkit.basins (but system), with its defaults: the library's "
            "BasinsOptions (analysis/basins.hpp), but for the coordinates, the command line's. "
            "The ranges and steps have none: impactkit.basins(system, "
            "**impactkit.BasinsOptions(from_=-0.5, to=0.1, steps=4, from2=-0.5, to2=0.5, "
            "steps2=3)) passes a set.");
}

}  // namespace

void BindGrid(py::module_& module) {
  // The defaults are the library's (a map's rows are sweeps), as the
  // command line's are: those of the functions' keywords and of MapOptions
  // and BasinsOptions, from the same structs.
  const ParameterMapOptions kMap;
  const SweepOptions& kRow = kMap.row;
  const BasinsOptions kBasins = BasinsDefaults();
  BindMapOptions(module, kMap);
  BindBasinsOptions(module, kBasins);
  // The categories of the tables' motion class (impactkit/_tables.py).
  module.attr("_motion_kinds") = MotionKindNames();
  module.def(
      "parameter_map", &ParameterMapPy, py::arg("system"), py::kw_only(),
      py::arg("parameter") = kRow.parameter, py::arg("from_"), py::arg("to"), py::arg("steps"),
      py::arg("parameter2") = kMap.parameter2, py::arg("from2"), py::arg("to2"), py::arg("steps2"),
      py::arg("transient_periods") = kRow.transient_periods,
      py::arg("recorded_periods") = kRow.recorded_periods, py::arg("threads") = kRow.threads,
      py::arg("each_from") = StartName(kRow.start), py::arg("chunk_values") = kRow.chunk_values,
      py::arg("full_transient") = kRow.full_transient, py::arg("progress") = false,
      R"(A two-parameter map, as `impactkit map` computes it: each row is the sweep
of `parameter` (steps values from from_ to to) at one of the steps2
values of `parameter2` (ascending), each cell's motion classified. Returns
a dict of arrays of shape (steps2, steps): 'kind' (names), 'kind_code'
(index into 'kinds'), 'p', 'q' (0 where undefined), 'max_velocity', 'range_xN',
'lyapunov' (NaN where undefined), and 'values', 'values2'. threads does not
change the result. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.MapOptions's: `parameter_map(system, **impactkit.MapOptions(...))`
passes a set.)");
  module.def("basins", &BasinsPy, py::arg("system"), py::kw_only(),
             py::arg("coordinate") = kBasins.coordinate1, py::arg("from_"), py::arg("to"),
             py::arg("steps"), py::arg("coordinate2") = kBasins.coordinate2, py::arg("from2"),
             py::arg("to2"), py::arg("steps2"),
             py::arg("transient_periods") = kBasins.run.transient_periods,
             py::arg("recorded_periods") = kBasins.run.recorded_periods,
             py::arg("threads") = kBasins.run.threads,
             py::arg("orbit_tolerance") = kBasins.orbit_tolerance,
             py::arg("full_transient") = kBasins.run.full_transient, py::arg("progress") = false,
             R"(Basins of attraction, as `impactkit basins` computes them: a grid of
starts over two state coordinates ('x1'..'xN', 'v1'..'vN'; the others at
rest), each run to its attractor and the attractors identified by their
orbits. Returns the cell arrays of parameter_map (shape (steps2, steps))
and 'attractor' (index into 'attractors', a list of dicts with kind, p,
q, cells, and the orbit's impact 'phases' and 'speeds'). Releases the GIL;
Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.BasinsOptions's: `basins(system, **impactkit.BasinsOptions(...))`
passes a set.)");
}

}  // namespace impactkit::python
