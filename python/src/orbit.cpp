// impactkit.find_orbit and impactkit.Orbit: orbits/orbit.hpp, seeded by
// analysis/orbit_seed.hpp when no seed is given.
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
#include "impactkit/analysis/orbit_seed.hpp"

namespace impactkit::python {
namespace {

JacobianMethod JacobianFromName(const std::string& name) {
  if (name == "analytic") return JacobianMethod::kAnalytic;
  if (name == "finite_difference") return JacobianMethod::kFiniteDifference;
  throw InvalidInput("jacobian must be 'analytic' or 'finite_difference', got '" + name + "'");
}

PeriodicOrbit FindOrbitPy(const System& system, std::optional<int> p, std::optional<int> q,
                          std::optional<Eigen::VectorXd> seed, int stop,
                          const std::string& jacobian, double residual_tolerance,
                          int max_iterations, bool least_squares_fallback, int transient) {
  OrbitOptions options;
  options.jacobian = JacobianFromName(jacobian);
  options.newton.residual_tolerance = residual_tolerance;
  options.newton.max_iterations = max_iterations;
  options.least_squares_fallback = least_squares_fallback;
  PeriodicOrbit orbit;
  const OrbitSummary summary = WithoutGil([&] {
    Eigen::VectorXd guess;
    if (seed) {
      guess = *seed;
      Require(stop >= 0 && stop < system.StopCount(),
              "stop must be in [0, " + std::to_string(system.StopCount() - 1) +
                  "] (0-based), got " + std::to_string(stop));
      options.map.stop = stop;
      options.p = p.value_or(1);
      options.q = q.value_or(1);
    } else {
      Require(transient >= 0, "transient must be >= 0, got " + std::to_string(transient));
      const std::optional<OrbitSeed> found = SeedFromSimulation(system, transient);
      Require(found.has_value(), "no seed: the simulation from rest has no impact");
      Require((p && q) || (found->motion.periodic && !found->motion.sticking),
              "no p and q given, and the simulation from rest shows " + found->motion.ToString() +
                  "; give p and q");
      guess = found->eta;
      options.map.stop = found->stop;
      options.p = p.value_or(static_cast<int>(found->motion.p));
      options.q = q.value_or(found->motion.q);
    }
    return FindOrbit(system, guess, options, &orbit);
  });
  if (summary.termination != Termination::kConverged) ThrowNumericalError(summary.BriefReport());
  // The orbit holds, but a simulation does not see all its impacts: say so.
  if (summary.unresolved_impacts > 0 &&
      PyErr_WarnEx(PyExc_RuntimeWarning, summary.BriefReport().c_str(), 1) != 0) {
    throw py::error_already_set();
  }
  return orbit;
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
                            "A periodic orbit P(p, q): p impacts in q forcing periods, a fixed "
                            "point of the impact map with its multipliers.")
      .def_readonly("p", &PeriodicOrbit::p, "Impacts per orbit.")
      .def_readonly("q", &PeriodicOrbit::q, "Forcing periods per orbit.")
      .def_readonly("omega", &PeriodicOrbit::omega, "The forcing frequency.")
      .def_property_readonly(
          "eta", [](const PeriodicOrbit& o) { return o.eta; },
          "The fixed point eta = (x without x_c, tau, v) just before an impact, tau in [0, T).")
      .def_property_readonly(
          "jacobian", [](const PeriodicOrbit& o) { return o.jacobian; }, "D P_I^p at eta.")
      .def_property_readonly(
          "multipliers", [](const PeriodicOrbit& o) { return o.multipliers; },
          "Eigenvalues of the Jacobian (complex), by decreasing modulus.")
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
        return "impactkit.Orbit(P(" + std::to_string(o.p) + "," + std::to_string(o.q) +
               "), omega=" + py::repr(py::float_(o.omega)).cast<std::string>() +
               (o.stable ? ", stable)" : ", unstable)");
      });

  module.def("find_orbit", &FindOrbitPy, py::arg("system"), py::kw_only(),
             py::arg("p") = py::none(), py::arg("q") = py::none(), py::arg("seed") = py::none(),
             py::arg("stop") = 0, py::arg("jacobian") = "analytic",
             py::arg("residual_tolerance") = 1e-11, py::arg("max_iterations") = 50,
             py::arg("least_squares_fallback") = true, py::arg("transient") = 500,
             R"(The periodic orbit P(p, q) of `system` by Newton (KINSOL), with a
Levenberg-Marquardt fallback.

seed: an impact state eta (size 2N, v_c > 0) at stop `stop` (0-based; its
mass is the one left out of eta); p and q default to 1. Without a seed, the
last impact of a simulation from rest (transient forcing periods, then a
window) is the seed, at whichever stop it is, and p and q default to the
period it shows.
Raises ValueError for bad input, NumericalError when Newton does not converge.
Warns (RuntimeWarning) when an impact of the orbit is below the arrival
resolution: near a grazing, a simulation sees a touch there, not an impact.
Releases the GIL.)");
}

}  // namespace impactkit::python
