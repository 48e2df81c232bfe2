// impactkit.trace_diagram, impactkit.swept_diagram, Diagram, DiagramNode,
// DiagramEdge, DiagramBranch: continuation/diagram.hpp, diagram_graph.hpp
// and analysis/swept_diagram.hpp.
#include "impactkit/continuation/diagram.hpp"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/analysis/swept_diagram.hpp"
#include "impactkit/io/diagram_output.hpp"
#include "impactkit/model/parameters.hpp"
#include "option_sets.hpp"

namespace impactkit::python {
namespace {

struct DiagramArguments {
  std::string parameter;
  double from, to, initial_step, max_step;
  int max_points, max_depth, max_branches, threads;
  bool switch_period_doubling, switch_grazing, switch_branch_points, switch_pitchforks;
};

DiagramOptions MakeOptions(const DiagramArguments& a) {
  DiagramOptions options;
  options.continuation.parameter = a.parameter;
  options.continuation.from = a.from;
  options.continuation.to = a.to;
  options.continuation.initial_step = a.initial_step;
  options.continuation.max_step = a.max_step;
  options.continuation.max_points = a.max_points;
  options.max_depth = a.max_depth;
  options.max_branches = a.max_branches;
  options.threads = a.threads;
  options.switch_period_doubling = a.switch_period_doubling;
  options.switch_grazing = a.switch_grazing;
  options.switch_branch_points = a.switch_branch_points;
  options.switch_pitchforks = a.switch_pitchforks;
  return options;
}

Diagram Trace(const std::vector<std::pair<System, PeriodicOrbit>>& starts,
              const std::string& parameter, double from, double to, double initial_step,
              double max_step, int max_points, int max_depth, int max_branches, int threads,
              bool switch_period_doubling, bool switch_grazing, bool switch_branch_points,
              bool switch_pitchforks, const std::optional<py::dict>& user_tests,
              const py::object& progress) {
  std::vector<DiagramSeed> seeds;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    seeds.push_back({starts[i].first, starts[i].second, "seed " + std::to_string(i + 1),
                     ContinuationDirection::kBoth});
  }
  DiagramOptions options = MakeOptions({parameter, from, to, initial_step, max_step, max_points,
                                        max_depth, max_branches, threads, switch_period_doubling,
                                        switch_grazing, switch_branch_points, switch_pitchforks});
  options.continuation.user_tests = UserTestsFrom(user_tests);
  const InterruptibleRun run(progress);
  return WithoutGil([&] {
    Diagram diagram = TraceDiagram(seeds, options, run);
    if (!starts.empty()) PredictGrazings(starts.front().first, &diagram);
    return diagram;
  });
}

/// The sweep-seeded network, as `impactkit diagram` traces it: the
/// library's recipe (SweptDiagramOptions) with the command's knobs.
struct SweptArguments {
  std::string parameter;
  double from, to;
  int sweep_values, sweep_transient, sweep_record, max_q, refine, max_depth, max_branches, threads;
};

Diagram Swept(const System& system, const SweptArguments& a, const py::object& progress) {
  SweptDiagramOptions options;
  options.diagram.continuation.parameter = a.parameter;
  options.diagram.continuation.from = a.from;
  options.diagram.continuation.to = a.to;
  options.diagram.max_depth = a.max_depth;
  options.diagram.max_branches = a.max_branches;
  options.diagram.threads = options.sweep.threads = a.threads;
  options.sweep.steps = a.sweep_values;
  options.sweep.transient_periods = a.sweep_transient;
  options.sweep.recorded_periods = a.sweep_record;
  options.sweep.classify.period.max_q = options.seeds.max_p = a.max_q;
  options.refine.factor = a.refine;
  System start = system;
  SetParameter(start, a.parameter, std::min(a.from, a.to));
  const InterruptibleRun run(progress);
  return WithoutGil([&] {
    Diagram diagram = TraceSweptDiagram(start, {}, options, run).diagram;
    PredictGrazings(start, &diagram);
    return diagram;
  });
}

void BindNode(py::module_& module) {
  py::class_<DiagramNode>(module, "DiagramNode",
                          "A node of a diagram: a special point, or where a branch ends for "
                          "another reason, or a seed followed one way.")
      .def_property_readonly("type", &DiagramNode::Name,
                             "'fold', 'period_doubling', 'neimark_sacker', 'grazing', "
                             "'sticking', 'branch_point', 'user_test', or 'parameter_bound', "
                             "'max_points', 'corrector_failed', 'start'.")
      .def_readonly("user_test", &DiagramNode::user_test,
                    "A user test's zero: the test's name (its key in user_tests).")
      .def_readonly("parameter", &DiagramNode::parameter, "The parameter value there.")
      .def_readonly("multiplier", &DiagramNode::multiplier,
                    "The critical multiplier (fold, period doubling, Neimark-Sacker; else 0).")
      .def_readonly("multipliers", &DiagramNode::multipliers,
                    "Every multiplier of the orbit there.")
      .def_readonly("monitor", &DiagramNode::monitor, "The test function or grazing monitor.")
      .def_readonly("vanishing_impact", &DiagramNode::vanishing_impact,
                    "Grazing/sticking: the impact that vanishes (-1 for a new contact).")
      .def_property_readonly(
          "normal_form", [](const DiagramNode& n) { return NormalFormDict(n.normal_form); },
          "A grazing's normal form and prediction, as SpecialPoint.normal_form; else None.")
      .def_readonly("p", &DiagramNode::p, "Impacts per orbit of the branch it was located on.")
      .def_readonly("q", &DiagramNode::q, "Forcing periods per orbit of that branch.")
      .def_readonly("branch", &DiagramNode::branch, "That branch, an index into branches.")
      .def_property_readonly(
          "eta", [](const DiagramNode& n) { return n.point.orbit.eta; },
          "The orbit's fixed point at the node.")
      .def("__repr__", [](const DiagramNode& n) {
        return "impactkit.DiagramNode(" + n.Name() + ", P(" + std::to_string(n.p) + "," +
               std::to_string(n.q) +
               "), parameter=" + py::repr(py::float_(n.parameter)).cast<std::string>() + ")";
      });
}

void BindBranch(py::module_& module) {
  py::class_<DiagramBranch>(module, "DiagramBranch", "A traced branch and how it was reached.")
      .def_readonly("branch", &DiagramBranch::branch, "The Branch itself.")
      .def_readonly("origin", &DiagramBranch::origin,
                    "'seed 1', 'period doubling at omega = 1.61', ...")
      .def_readonly("depth", &DiagramBranch::depth, "Switches from a seed (0 for a seed's).")
      .def_readonly("parent", &DiagramBranch::parent,
                    "The node it was started from (-1 for a seed).");
}

void BindGraph(py::module_& module) {
  py::class_<Diagram>(module, "Diagram",
                      "A connected bifurcation diagram: nodes (special points and branch "
                      "ends), edges (stretches of branches between consecutive nodes, as "
                      "arrays) and the branches traced.")
      .def_readonly("parameter", &Diagram::parameter, "The parameter's name.")
      .def_readonly("nodes", &Diagram::nodes, "A list of DiagramNode.")
      .def_readonly("branches", &Diagram::branches, "A list of DiagramBranch.")
      .def_property_readonly(
          "edge_from",
          [](const Diagram& d) { return Column<long>(d.edges, [](auto& e) { return e.from; }); },
          "Each edge's first node, shape (edges,).")
      .def_property_readonly(
          "edge_to",
          [](const Diagram& d) { return Column<long>(d.edges, [](auto& e) { return e.to; }); },
          "Each edge's last node, shape (edges,).")
      .def_property_readonly(
          "edge_branch",
          [](const Diagram& d) { return Column<long>(d.edges, [](auto& e) { return e.branch; }); },
          "Each edge's branch (index into branches), shape (edges,).")
      .def_property_readonly(
          "edge_first",
          [](const Diagram& d) { return Column<long>(d.edges, [](auto& e) { return e.first; }); },
          "The index of each edge's first point on its branch, shape (edges,).")
      .def_property_readonly(
          "edge_last",
          [](const Diagram& d) { return Column<long>(d.edges, [](auto& e) { return e.last; }); },
          "The index of each edge's last point on its branch (inclusive), shape (edges,).")
      .def_readonly("duplicate_starts", &Diagram::duplicate_starts,
                    "Starts not traced: their orbit lies on a branch traced already.")
      .def_readonly("failed_starts", &Diagram::failed_starts, "Starts that did not converge.")
      .def_property_readonly(
          "termination", [](const Diagram& d) { return ToString(d.termination); },
          "'completed' (every start was followed), 'max_points' (a depth or branch bound cut "
          "the network short) or 'stopped'.")
      .def_readonly("message", &Diagram::message, "Which bound cut it short, if one did.")
      .def_readonly("seconds", &Diagram::seconds, "Wall time.")
      .def(
          "to_json", [](const Diagram& d) { return DiagramJson(d); },
          "The diagram as JSON text: the document `impactkit diagram --json` writes, without "
          "its provenance, system and regimes (io/diagram_output.hpp).")
      .def("brief_report", &Diagram::BriefReport,
           "'7 branches, 15 nodes, 16 edges in 3.2 s (...)'.")
      .def("__repr__",
           [](const Diagram& d) { return "impactkit.Diagram(" + d.BriefReport() + ")"; });
}

/// impactkit.DiagramOptions: the keywords of trace_diagram (but the seeds
/// and user_tests), over DiagramOptions (the branches' in its continuation).
void BindDiagramOptions(py::module_& module, const DiagramOptions& defaults) {
  OptionSetBinding<DiagramOptions>(defaults)
      .Field(
          "parameter", [](auto& o) -> auto& { return o.continuation.parameter; },
          "The continued parameter: a name of System.parameter_names().")
      .Required(
          "from_", [](auto& o) -> auto& { return o.continuation.from; },
          "One end of the parameter's range (either order): every branch stays within it and "
          "ends on reaching an end.")
      .Required(
          "to", [](auto& o) -> auto& { return o.continuation.to; },
          "The other end of the parameter's range.")
      .Field(
          "initial_step", [](auto& o) -> auto& { return o.continuation.initial_step; },
          "Arclength step of every branch in (eta, parameter) space: the first.")
      .Field(
          "max_step", [](auto& o) -> auto& { return o.continuation.max_step; },
          "Arclength step of every branch in (eta, parameter) space: the ceiling.")
      .Field(
          "max_points", [](auto& o) -> auto& { return o.continuation.max_points; },
          "Points at most of every branch, per direction.")
      .Field("max_depth", &DiagramOptions::max_depth,
             "Switches from a seed's branch at most (0: the seeds' branches only).")
      .Field("max_branches", &DiagramOptions::max_branches, "Branches traced at most.")
      .Field("threads", &DiagramOptions::threads,
             "Branches of one generation traced at once (>= 1); the result does not depend on "
             "it.")
      .Field("switch_period_doubling", &DiagramOptions::switch_period_doubling,
             "Start the doubled branch at each period doubling.")
      .Field("switch_grazing", &DiagramOptions::switch_grazing,
             "Start the orbit with one impact more or fewer at each grazing.")
      .Field("switch_branch_points", &DiagramOptions::switch_branch_points,
             "Start the shorter orbit at a branch point.")
      .Field("switch_pitchforks", &DiagramOptions::switch_pitchforks,
             "Start both halves of the crossing branch at a pitchfork.")
      .Bind(module, "DiagramOptions",
            "The keywords of impactkit.trace_diagram (but the seeds and user_tests), with its "
            "defaults: the library's DiagramOptions (continuation/diagram.hpp). from_ and to "
            "have none: impactkit.trace_diagram(seeds, **impactkit.DiagramOptions(from_=1.5, "
            "to=1.8)) passes a set.");
}

}  // namespace

void BindDiagram(py::module_& module) {
  BindNode(module);
  BindBranch(module);
  BindGraph(module);
  // The defaults are the library's, as the command line's are: those of the
  // function's keywords and of DiagramOptions, from the same struct.
  const DiagramOptions kNetwork;
  const ContinuationOptions& kBranch = kNetwork.continuation;
  BindDiagramOptions(module, kNetwork);
  const SweptDiagramOptions kRecipe;
  module.def(
      "swept_diagram",
      [](const System& system, const std::string& parameter, double from, double to,
         int sweep_values, int sweep_transient, int sweep_record, int max_q, int refine,
         int max_depth, int max_branches, int threads, const py::object& progress) {
        return Swept(system,
                     {parameter, from, to, sweep_values, sweep_transient, sweep_record, max_q,
                      refine, max_depth, max_branches, threads},
                     progress);
      },
      py::arg("system"), py::kw_only(), py::arg("parameter") = kBranch.parameter, py::arg("from_"),
      py::arg("to"), py::arg("sweep_values") = kRecipe.sweep.steps,
      py::arg("sweep_transient") = kRecipe.sweep.transient_periods,
      py::arg("sweep_record") = kRecipe.sweep.recorded_periods,
      py::arg("max_q") = kRecipe.sweep.classify.period.max_q,
      py::arg("refine") = kRecipe.refine.factor, py::arg("max_depth") = kNetwork.max_depth,
      py::arg("max_branches") = kNetwork.max_branches, py::arg("threads") = kNetwork.threads,
      py::arg("progress") = false,
      R"(The connected bifurcation diagram over from_..to seeded by a sweep, as
`impactkit diagram` traces it (the library's TraceSweptDiagram and its
defaults): sweep_values values of sweep_transient + sweep_record forcing
periods (whole transients, periods up to max_q), swept again with `refine`
values per interval where neighbouring motions differ or are chaotic or
unresolved (1: no refinement), so that windows narrower than the spacing
seed branches too; each periodic or sticking window (two values or more,
at most max_q impacts) seeds a branch, and the network is traced from them
(see trace_diagram). threads: sweep threads and branches traced at once; the
result does not depend on it. Returns a Diagram. Raises ValueError for bad
input. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.)");
  module.def("trace_diagram", &Trace, py::arg("seeds"), py::kw_only(),
             py::arg("parameter") = kBranch.parameter, py::arg("from_"), py::arg("to"),
             py::arg("initial_step") = kBranch.initial_step, py::arg("max_step") = kBranch.max_step,
             py::arg("max_points") = kBranch.max_points, py::arg("max_depth") = kNetwork.max_depth,
             py::arg("max_branches") = kNetwork.max_branches, py::arg("threads") = kNetwork.threads,
             py::arg("switch_period_doubling") = kNetwork.switch_period_doubling,
             py::arg("switch_grazing") = kNetwork.switch_grazing,
             py::arg("switch_branch_points") = kNetwork.switch_branch_points,
             py::arg("switch_pitchforks") = kNetwork.switch_pitchforks,
             py::arg("user_tests") = py::none(), py::arg("progress") = false,
             R"(Traces the connected bifurcation diagram through `seeds`, a list of
(system, orbit) pairs: each seed's branch is followed both ways in the named
parameter between from_ and to, and at every period doubling, grazing,
branch point and pitchfork the branch that starts there, each branch once (the library's
TraceDiagram, as `impactkit diagram --start` does). Returns a Diagram.
threads: branches of one generation traced at once; the result does not
depend on it. user_tests: {name: function(Orbit) -> float}, located on
every branch as nodes 'user_test' (called from the tracing threads, each
call taking the GIL). Raises ValueError for bad input, and what a user test
raises. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.DiagramOptions's (but user_tests):
`trace_diagram(seeds, **impactkit.DiagramOptions(...))` passes a set.)");
}

}  // namespace impactkit::python
