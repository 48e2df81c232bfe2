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

namespace impactkit::python {
namespace {

/// Every unit of `task` on `threads` threads, the cells in index order.
/// Ctrl-C is checked after each unit.
std::vector<GridCell> RunAll(const GridTask& task, int threads) {
  Require(threads >= 1, "threads must be >= 1, got " + std::to_string(threads));
  return WithoutGil([&] {
    std::atomic<int> next{0};
    std::vector<GridCell> cells;
    RunUnits(
        task, threads,
        [&] {
          const int unit = next++;
          return unit < task.Units() ? unit : -1;
        },
        [&](int, std::vector<GridCell>& done) {
          cells.insert(cells.end(), done.begin(), done.end());
          CheckInterrupt();
        });
    return InIndexOrder(std::move(cells), task.Cells());
  });
}

/// The cells as (rows, columns) arrays: the kind by name and by its index in
/// `kinds`, and p, q, max_v, range_xN, lyapunov (NaN where undefined).
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
  py::list kinds;
  for (const MotionKind k : {MotionKind::kPeriodic, MotionKind::kSticking, MotionKind::kChaotic,
                             MotionKind::kNonImpacting, MotionKind::kUnresolved}) {
    kinds.append(ToString(k));
  }
  py::dict out;
  out["kinds"] = kinds;
  out["kind_code"] = MoveToArray(std::move(kind), shape);
  out["kind"] = py::module_::import("numpy").attr("array")(names).attr("reshape")(rows, columns);
  out["p"] = MoveToArray(std::move(p), shape);
  out["q"] = MoveToArray(std::move(q), shape);
  out["max_v"] = MoveToArray(std::move(max_v), shape);
  out["range_xN"] = MoveToArray(std::move(range), shape);
  out["lyapunov"] = MoveToArray(std::move(lyapunov), shape);
  return out;
}

SweepStart StartFromName(const std::string& each_from) {
  if (each_from == "previous") return SweepStart::kPrevious;
  if (each_from == "rest") return SweepStart::kFixed;
  throw InvalidInput("each_from must be 'previous' or 'rest', got '" + each_from + "'");
}

py::dict ParameterMapPy(const System& system, const std::string& parameter, double from, double to,
                        int steps, const std::string& parameter2, double from2, double to2,
                        int steps2, int transient_periods, int recorded_periods, int threads,
                        const std::string& each_from, int chunk_values) {
  ParameterMapOptions options;
  options.row.parameter = parameter;
  options.row.from = from;
  options.row.to = to;
  options.row.steps = steps;
  options.row.transient_periods = transient_periods;
  options.row.recorded_periods = recorded_periods;
  options.row.start = StartFromName(each_from);
  options.row.chunk_values = chunk_values;
  options.parameter2 = parameter2;
  options.from2 = from2;
  options.to2 = to2;
  options.steps2 = steps2;
  const ParameterMapTask task(system, options);
  const std::vector<GridCell> cells = RunAll(task, threads);
  py::dict out = CellArrays(cells, static_cast<py::ssize_t>(task.Values2().size()),
                            static_cast<py::ssize_t>(task.Values1().size()));
  out["values"] = MoveToArray(std::vector<double>(task.Values1()));
  out["values2"] = MoveToArray(std::vector<double>(task.Values2()));
  return out;
}

py::dict BasinsPy(const System& system, const std::string& coordinate1, double from1, double to1,
                  int steps1, const std::string& coordinate2, double from2, double to2, int steps2,
                  int transient_periods, int recorded_periods, int threads,
                  double orbit_tolerance) {
  BasinsOptions options;
  options.run.transient_periods = transient_periods;
  options.run.recorded_periods = recorded_periods;
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
  const std::vector<GridCell> cells = RunAll(task, threads);
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

}  // namespace

void BindGrid(py::module_& module) {
  // The defaults are the library's (a map's rows are sweeps), as the
  // command line's are.
  const SweepOptions kRun;
  module.def("parameter_map", &ParameterMapPy, py::arg("system"), py::kw_only(),
             py::arg("parameter") = "omega", py::arg("from_"), py::arg("to"), py::arg("steps"),
             py::arg("parameter2") = "r", py::arg("from2"), py::arg("to2"), py::arg("steps2"),
             py::arg("transient_periods") = kRun.transient_periods,
             py::arg("recorded_periods") = kRun.recorded_periods, py::arg("threads") = 1,
             py::arg("each_from") = "previous", py::arg("chunk_values") = kRun.chunk_values,
             R"(A two-parameter map, as `impactkit map` computes it: each row is the sweep
of `parameter` (steps values from from_ to to) at one of the steps2
values of `parameter2` (ascending), each cell's motion classified. Returns
a dict of arrays of shape (steps2, steps): 'kind' (names), 'kind_code'
(index into 'kinds'), 'p', 'q' (0 where undefined), 'max_v', 'range_xN',
'lyapunov' (NaN where undefined), and 'values', 'values2'. threads does not
change the result. Releases the GIL; Ctrl-C raises KeyboardInterrupt.)");
  module.def("basins", &BasinsPy, py::arg("system"), py::kw_only(), py::arg("coordinate") = "x2",
             py::arg("from_"), py::arg("to"), py::arg("steps"), py::arg("coordinate2") = "v2",
             py::arg("from2"), py::arg("to2"), py::arg("steps2"),
             py::arg("transient_periods") = kRun.transient_periods,
             py::arg("recorded_periods") = kRun.recorded_periods, py::arg("threads") = 1,
             py::arg("orbit_tolerance") = BasinsOptions{}.orbit_tolerance,
             R"(Basins of attraction, as `impactkit basins` computes them: a grid of
starts over two state coordinates ('x1'..'xN', 'v1'..'vN'; the others at
rest), each run to its attractor and the attractors identified by their
orbits. Returns the cell arrays of parameter_map (shape (steps2, steps))
and 'attractor' (index into 'attractors', a list of dicts with kind, p,
q, cells, and the orbit's impact 'phases' and 'speeds'). Releases the GIL;
Ctrl-C raises KeyboardInterrupt.)");
}

}  // namespace impactkit::python
