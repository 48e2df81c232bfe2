// impactkit.find_orbit and impactkit.Orbit: the start orbit of
// analysis/start_orbit.hpp (either section, orbits/orbit.hpp).
#include "impactkit/orbits/orbit.hpp"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "impactkit/analysis/start_orbit.hpp"

namespace impactkit::python {
namespace {

JacobianMethod JacobianFromName(const std::string& name) {
  if (name == "analytic") return JacobianMethod::kAnalytic;
  if (name == "finite_difference") return JacobianMethod::kFiniteDifference;
  throw InvalidInput("jacobian must be 'analytic' or 'finite_difference', got '" + name + "'");
}

PeriodicOrbit FindOrbitPy(const System& system, std::optional<int> p, std::optional<int> q,
                          std::optional<int> releases, std::optional<Eigen::VectorXd> seed,
                          int stop, const std::string& jacobian, double residual_tolerance,
                          int max_iterations, bool least_squares_fallback, int transient) {
  StartOrbitRequest request;
  request.p = p;
  request.q = q;
  request.releases = releases;
  request.guess = std::move(seed);
  request.stop = stop;
  request.transient = transient;
  request.solver.jacobian = JacobianFromName(jacobian);
  request.solver.newton.residual_tolerance = residual_tolerance;
  request.solver.newton.max_iterations = max_iterations;
  request.solver.least_squares_fallback = least_squares_fallback;
  const StartOrbit start = WithoutGil([&] { return FindStartOrbit(system, request); });
  // No seed of the kind asked for at these values: the request, not the
  // solver, is what to change.
  if (!start.seeded) throw InvalidInput(start.summary.message);
  if (start.summary.termination != Termination::kConverged) {
    ThrowNumericalError(start.summary.BriefReport());
  }
  // The orbit holds, but a simulation does not see all its impacts: say so.
  if (start.summary.unresolved_impacts > 0 &&
      PyErr_WarnEx(PyExc_RuntimeWarning, start.summary.BriefReport().c_str(), 1) != 0) {
    throw py::error_already_set();
  }
  return start.orbit;
}

/// One field of a sticking orbit's stuck phases, as a numpy array of shape (k,).
template <typename Get>
auto StuckField(const PeriodicOrbit& orbit, Get get) {
  std::vector<std::invoke_result_t<Get, const StuckPhase&>> values;
  for (const StuckPhase& stuck : orbit.stuck) values.push_back(get(stuck));
  return MoveToArray(std::move(values));
}

/// One field of the orbit's impacts, as a numpy array of shape (p,).
template <auto Field>
auto ImpactField(const PeriodicOrbit& orbit) {
  using Value = std::remove_cvref_t<decltype(std::declval<OrbitImpact>().*Field)>;
  std::vector<Value> values;
  for (const OrbitImpact& impact : orbit.impacts) values.push_back(impact.*Field);
  return MoveToArray(std::move(values));
}

}  // namespace

void BindOrbit(py::module_& module) {
  py::class_<PeriodicOrbit>(module, "Orbit",
                            "A periodic orbit: P(p, q), p impacts in q forcing periods, a fixed "
                            "point of the impact map, or a sticking orbit P(inf, q), a fixed "
                            "point of the release map; with its multipliers.")
      .def_property_readonly(
          "section", [](const PeriodicOrbit& o) { return ToString(o.section); },
          "'impact' (P(p, q) on the impact map) or 'release' (a sticking orbit on the release "
          "map).")
      .def_readonly("p", &PeriodicOrbit::p,
                    "Impacts per orbit (of a sticking orbit: those simulated before its "
                    "accumulations).")
      .def_readonly("q", &PeriodicOrbit::q, "Forcing periods per orbit.")
      .def_readonly("releases", &PeriodicOrbit::releases,
                    "Sticking phases per orbit (0 for an impacting orbit).")
      .def_property_readonly(
          "stick_phases",
          [](const PeriodicOrbit& o) {
            return StuckField(o, [](const StuckPhase& s) { return s.stick_phase; });
          },
          "Each sticking phase's start t* (the chatter's accumulation point) mod T, shape (k,).")
      .def_property_readonly(
          "release_phases",
          [](const PeriodicOrbit& o) {
            return StuckField(o, [](const StuckPhase& s) { return s.release_phase; });
          },
          "Each sticking phase's release mod T, shape (k,).")
      .def_property_readonly(
          "stuck_durations",
          [](const PeriodicOrbit& o) {
            return StuckField(o, [](const StuckPhase& s) { return s.Duration(); });
          },
          "Each sticking phase's duration, release - t*, shape (k,).")
      .def_property_readonly(
          "stuck_stops",
          [](const PeriodicOrbit& o) {
            return StuckField(o, [](const StuckPhase& s) { return s.stop; });
          },
          "The stop (0-based, System.stops) each sticking phase holds the mass at, shape (k,).")
      .def_property_readonly(
          "contact_margin",
          [](const PeriodicOrbit& o) -> std::optional<double> {
            if (!o.Sticks()) return std::nullopt;
            return o.contacts.contact_margin;
          },
          "Sticking orbits: the least stop force Fs(t*) at an accumulation point (None for an "
          "impacting orbit).")
      .def_readonly("omega", &PeriodicOrbit::omega, "The forcing frequency.")
      .def_property_readonly(
          "eta", [](const PeriodicOrbit& o) { return o.eta; },
          "The fixed point: eta = (x without x_c, tau, v) just before an impact, tau in [0, T); "
          "of a sticking orbit s = (x without x_c, v without v_c, t) at a release.")
      .def_property_readonly(
          "jacobian", [](const PeriodicOrbit& o) { return o.jacobian; },
          "D P^k at eta: the section map's k iterations.")
      .def_property_readonly(
          "multipliers", [](const PeriodicOrbit& o) { return o.multipliers; },
          "Eigenvalues of the Jacobian (complex), by decreasing modulus; of a sticking orbit "
          "those on the release surface (2N - 2).")
      .def_readonly("stable", &PeriodicOrbit::stable, "Every |multiplier| < 1.")
      .def_readonly("residual", &PeriodicOrbit::residual, "max |U(eta)|.")
      .def_property_readonly("impact_times", ImpactField<&OrbitImpact::t>,
                             "Times of the p impacts from eta on.")
      .def_property_readonly("impact_phases", ImpactField<&OrbitImpact::phase>,
                             "Forcing phases (t mod T) of the p impacts.")
      .def_property_readonly("impact_velocities", ImpactField<&OrbitImpact::velocity>,
                             "Impact speeds (towards the stop) of the p impacts.")
      .def_property_readonly(
          "impact_stops", ImpactField<&OrbitImpact::stop>,
          "The stop (0-based, System.stops) each of the p impacts is at; eta is at the first.")
      .def_property_readonly(
          "clearance", [](const PeriodicOrbit& o) { return o.contacts.clearance; },
          "xs minus the largest interior maximum of x_c in a flight (None if no flight has "
          "one): the grazing monitor of a new contact.")
      .def("__repr__", [](const PeriodicOrbit& o) {
        return "impactkit.Orbit(" + OrbitName(o) +
               ", omega=" + py::repr(py::float_(o.omega)).cast<std::string>() +
               (o.stable ? ", stable)" : ", unstable)");
      });

  const StartOrbitRequest kStart;  // the defaults are the library's, as the command line's are
  module.def("find_orbit", &FindOrbitPy, py::arg("system"), py::kw_only(),
             py::arg("p") = py::none(), py::arg("q") = py::none(), py::arg("releases") = py::none(),
             py::arg("seed") = py::none(), py::arg("stop") = 0, py::arg("jacobian") = "analytic",
             py::arg("residual_tolerance") = kStart.solver.newton.residual_tolerance,
             py::arg("max_iterations") = kStart.solver.newton.max_iterations,
             py::arg("least_squares_fallback") = kStart.solver.least_squares_fallback,
             py::arg("transient") = kStart.transient,
             R"(The periodic orbit of `system` by Newton (KINSOL), with a
Levenberg-Marquardt fallback: an impacting orbit P(p, q), a fixed point of
the impact map, or a sticking orbit P(inf, q) with `releases` sticking
phases in q forcing periods, a fixed point of the release map.

seed: an impact state eta (size 2N, v_c > 0) at stop `stop` (0-based; its
mass is the one left out of eta), or with `releases` a release state s
(size 2N - 1: x and v of the other masses, then t) from that stop; p (or
releases) and q default to 1. Without a seed, a simulation from rest
(transient forcing periods, then a window) gives it: where the motion sticks
periodically (and p is not given), its last release, with the releases and
q after which it repeats; else its last impact, at whichever stop it is,
with the period it shows (p and q, if given, go together). The rule is
the library's, shared with `impactkit orbit` (analysis/start_orbit.hpp).
Raises ValueError for bad input (a release seed the stop still pushes on,
no seed of the kind asked for in the simulated motion),
NumericalError when Newton does not converge.
Warns (RuntimeWarning) when an impact of the orbit is below the arrival
resolution: near a grazing, a simulation sees a touch there, not an impact.
Releases the GIL.)");
}

}  // namespace impactkit::python
