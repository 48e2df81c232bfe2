// impactkit.continue_curve, Curve and Codim2Point: continuation/curve.hpp.
#include "impactkit/continuation/curve.hpp"

#include <fmt/format.h>
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/io/curve_output.hpp"
#include "impactkit/model/parameters.hpp"
#include "option_sets.hpp"

namespace impactkit::python {
namespace {

Curve ContinueCurvePy(const System& system, const Branch& branch, const SpecialPoint& special,
                      const std::string& parameter2, double from, double to, double from2,
                      double to2, double initial_step, double min_step, double max_step,
                      int max_points, bool locate_codim2, const std::optional<py::dict>& user_tests,
                      const py::object& progress) {
  CurveOptions options;
  options.user_tests = UserTestsFrom(user_tests);
  options.parameter = branch.parameter;
  options.parameter2 = parameter2;
  options.from = from;
  options.to = to;
  options.from2 = from2;
  options.to2 = to2;
  options.initial_step = initial_step;
  options.min_step = min_step;
  options.max_step = max_step;
  options.max_points = max_points;
  options.locate_codim2 = locate_codim2;
  options.orbit.p = branch.p;
  options.orbit.q = branch.q;
  System at = system;
  SetParameter(at, branch.parameter, special.parameter);
  const InterruptibleRun run(progress);
  return WithoutGil([&] {
    Curve curve = ContinueCurve({at, special}, options, run);
    PredictGrazings(at, &curve);
    return curve;
  });
}

void BindCodim2(py::module_& module) {
  py::class_<Codim2Point>(module, "Codim2Point",
                          "A codimension-two point met along a curve: where it meets another "
                          "curve, or a resonance of its multipliers.")
      .def_property_readonly(
          "type", [](const Codim2Point& c) { return ToString(c.type); },
          "'fold_flip', 'cusp', 'resonance_1_1' … 'resonance_1_4', 'fold_grazing', "
          "'period_doubling_grazing', 'neimark_sacker_grazing', 'double_grazing', "
          "'resonant_grazing_fold', 'resonant_grazing_period_doubling', "
          "'sticking_onset', 'user_test'.")
      .def_readonly("user_test", &Codim2Point::user_test,
                    "A user test's zero: the test's name (its key in user_tests).")
      .def_property_readonly(
          "parameter", [](const Codim2Point& c) { return c.point.parameter; }, "mu1 there.")
      .def_property_readonly(
          "parameter2", [](const Codim2Point& c) { return c.point.parameter2; }, "mu2 there.")
      .def_readonly("defining_residual", &Codim2Point::defining_residual,
                    "|the curve's defining function| there.")
      .def_readonly("second_residual", &Codim2Point::second_residual,
                    "|the second test function| there.")
      .def_property_readonly(
          "normal_form", [](const Codim2Point& c) { return NormalFormDict(c.normal_form); },
          "A point located on a grazing curve: the grazing orbit's normal form there, "
          "unfolded in mu1, with its prediction (as SpecialPoint.normal_form); else None.")
      .def_readonly("normal_form_note", &Codim2Point::normal_form_note,
                    "Why such a point has no normal form, or where a bifurcation curve's grazing "
                    "end has it.")
      .def("describe", &Codim2Point::Describe, py::arg("name1"), py::arg("name2"),
           "One line, as the command line prints it.");
}

void BindCurveClass(py::module_& module) {
  py::class_<Curve>(module, "Curve",
                    "A two-parameter curve of fold, period-doubling, Neimark-Sacker or grazing "
                    "points: its points as arrays, from the mu2-decreasing end to the "
                    "mu2-increasing end, and its codimension-two points.")
      .def_property_readonly(
          "type", [](const Curve& c) { return ToString(c.type); },
          "'fold', 'period_doubling', 'neimark_sacker' or 'grazing'.")
      .def_readonly("parameter", &Curve::parameter, "mu1's name.")
      .def_readonly("parameter2", &Curve::parameter2, "mu2's name.")
      .def_readonly("p", &Curve::p, "Impacts per orbit (0: a non-impacting response's grazing).")
      .def_readonly("q", &Curve::q, "Forcing periods per orbit.")
      .def_property_readonly(
          "values",
          [](const Curve& c) {
            return Column<double>(c.points, [](auto& p) { return p.parameter; });
          },
          "mu1 at each point, shape (n,).")
      .def_property_readonly(
          "values2",
          [](const Curve& c) {
            return Column<double>(c.points, [](auto& p) { return p.parameter2; });
          },
          "mu2 at each point, shape (n,).")
      .def_property_readonly(
          "orbits",
          [](const Curve& c) {
            py::list orbits;
            for (const CurvePoint& p : c.points) orbits.append(py::cast(p.orbit));
            return orbits;
          },
          "The orbit at each point (a list of Orbit; empty orbits when p = 0).")
      .def_readonly("codim2_points", &Curve::codim2_points, "In order along the curve.")
      .def_property_readonly(
          "begin", [](const Curve& c) { return ToString(c.begin); },
          "Why the first point is the first: 'parameter_bound', 'grazing', 'sticking', "
          "'max_points', 'corrector_failed' or 'closed' (a loop, traced once round).")
      .def_property_readonly(
          "end", [](const Curve& c) { return ToString(c.end); }, "Why the last point is the last.")
      .def_readonly("begin_message", &Curve::begin_message, "The beginning in words.")
      .def_readonly("end_message", &Curve::end_message, "The end in words.")
      .def_readonly("seconds", &Curve::seconds, "Wall time.")
      .def(
          "to_json", [](const Curve& c) { return CurvesJson({c}); },
          "The curve as a curves file (docs/curves-json.md, without the system), as text: what "
          "`impactkit curve --json` writes, and `impactkit map --curves` reads.")
      .def(
          "write_csv",
          [](const Curve& c, const std::filesystem::path& path) {
            CsvWriter csv(path,
                          fmt::format("impactkit {} (Python): continue_curve in ({}, {})",
                                      IMPACTKIT_VERSION, c.parameter, c.parameter2),
                          CurveColumns(c));
            WriteCurveRows(csv, c);
            csv.Commit();
          },
          py::arg("path"),
          "Writes the curve as `impactkit curve --out` does: one row per point, the same "
          "columns (docs/cli.md), the provenance as comment lines after the header.")
      .def("__len__", [](const Curve& c) { return c.points.size(); })
      .def("__repr__", [](const Curve& c) {
        return "impactkit.Curve(" + ToString(c.type) + " of P(" + std::to_string(c.p) + "," +
               std::to_string(c.q) + ") in (" + c.parameter + ", " + c.parameter2 + "), " +
               std::to_string(c.points.size()) + " points)";
      });
}

/// impactkit.CurveOptions: the keywords of continue_curve (but the
/// positional ones and user_tests), over CurveOptions.
void BindCurveOptions(py::module_& module, const CurveOptions& defaults) {
  OptionSetBinding<CurveOptions>(defaults)
      .Field("parameter2", &CurveOptions::parameter2,
             "mu2, the second parameter (mu1 is the branch's): a name of "
             "System.parameter_names().")
      .Required("from_", &CurveOptions::from,
                "One end of mu1's range (either order): the curve stays within the ranges and "
                "ends on reaching one.")
      .Required("to", &CurveOptions::to, "The other end of mu1's range.")
      .Required("from2", &CurveOptions::from2, "One end of mu2's range (either order).")
      .Required("to2", &CurveOptions::to2, "The other end of mu2's range.")
      .Field("initial_step", &CurveOptions::initial_step,
             "Arclength step in X = (eta, [t*], mu1, mu2): the first.")
      .Field("min_step", &CurveOptions::min_step,
             "Arclength step in X = (eta, [t*], mu1, mu2): the floor.")
      .Field("max_step", &CurveOptions::max_step,
             "Arclength step in X = (eta, [t*], mu1, mu2): the ceiling.")
      .Field("max_points", &CurveOptions::max_points, "Points at most, per direction.")
      .Field("locate_codim2", &CurveOptions::locate_codim2,
             "Locate codimension-two points (the curve's end is always located).")
      .Bind(module, "CurveOptions",
            "The keywords of impactkit.continue_curve (but the positional ones and user_tests), "
            "with its defaults: the library's CurveOptions (continuation/curve.hpp). The ranges "
            "have none: impactkit.continue_curve(system, branch, point, "
            "**impactkit.CurveOptions(from_=0.5, to=3.0, from2=0.3, to2=0.95)) passes a set.");
}

}  // namespace

void BindCurve(py::module_& module) {
  BindCodim2(module);
  BindCurveClass(module);
  // The defaults are the library's, as the command line's are: those of the
  // function's keywords and of CurveOptions, from the same struct.
  const CurveOptions kCurve;
  BindCurveOptions(module, kCurve);
  module.def("continue_curve", &ContinueCurvePy, py::arg("system"), py::arg("branch"),
             py::arg("special_point"), py::kw_only(), py::arg("parameter2") = kCurve.parameter2,
             py::arg("from_"), py::arg("to"), py::arg("from2"), py::arg("to2"),
             py::arg("initial_step") = kCurve.initial_step, py::arg("min_step") = kCurve.min_step,
             py::arg("max_step") = kCurve.max_step, py::arg("max_points") = kCurve.max_points,
             py::arg("locate_codim2") = kCurve.locate_codim2, py::arg("user_tests") = py::none(),
             py::arg("progress") = false,
             R"(Follows a fold, period doubling, Neimark-Sacker or grazing point of
`branch` (continued for `system`) as the branch's parameter (mu1, within
between from_ and to) and `parameter2` (mu2, between from2 and to2) move, both
ways, locating codimension-two points (`impactkit curve`), and the zeros
of user_tests ({name: function(Orbit) -> float}) as 'user_test' points.
Returns a Curve.
Raises ValueError for bad input or a point the curve cannot start from.
Releases the GIL; Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.CurveOptions's (but user_tests):
`continue_curve(system, branch, special_point, **impactkit.CurveOptions(...))` passes a set.)");
}

}  // namespace impactkit::python
