// impactkit.System: model/system.hpp, model/parameters.hpp and the system
// files of io/system_file.hpp.
#include "impactkit/model/system.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit::python {
namespace {

/// Sets a named parameter only if the changed system is valid, so that a
/// ValueError leaves the Python object as it was.
void SetValidated(System& system, const std::string& name, double value) {
  System changed = system;
  SetParameter(changed, name, value);
  Validate(changed);
  system = std::move(changed);
}

/// A stop as Python sees it: a dict with the file's keys, dof 0-based.
py::dict StopDict(const StopParameters& stop) {
  py::dict entry(py::arg("dof") = stop.dof,
                 py::arg("side") = stop.side == StopSide::kUpper ? "upper" : "lower");
  for (const StopParameterRow& row : kStopParameterRows) {
    entry[py::str(std::string(row.key))] = stop.*row.member;
  }
  return entry;
}

/// "dof, side, position, restitution": the keys of a stop dict.
std::string StopDictKeys() {
  std::string keys = "dof, side";
  for (const StopParameterRow& row : kStopParameterRows) keys += ", " + std::string(row.key);
  return keys;
}

StopParameters StopFromDict(const py::dict& entry, int index) {
  const std::string where = "stops[" + std::to_string(index) + "]";
  for (const auto& [key, unused] : entry) {
    const std::string name = py::str(key);
    const bool known = name == "dof" || name == "side" ||
                       std::any_of(kStopParameterRows.begin(), kStopParameterRows.end(),
                                   [&](const StopParameterRow& row) { return row.key == name; });
    Require(known, where + ": unknown key '" + name + "'; allowed: " + StopDictKeys());
  }
  Require(entry.contains("dof"), where + " needs 'dof' (0-based)");
  StopParameters stop;
  stop.dof = entry["dof"].cast<int>();
  const std::string side =
      entry.contains("side") ? entry["side"].cast<std::string>() : std::string("upper");
  Require(side == "upper" || side == "lower",
          where + ": side must be 'upper' (x <= position) or 'lower', got '" + side + "'");
  stop.side = side == "upper" ? StopSide::kUpper : StopSide::kLower;
  for (const StopParameterRow& row : kStopParameterRows) {
    const std::string key(row.key);
    if (entry.contains(key)) {
      stop.*row.member = entry[key.c_str()].cast<double>();
    } else {
      Require(!row.required, where + " needs '" + key + "'");
    }
  }
  return stop;
}

}  // namespace

void BindSystem(py::module_& module) {
  py::class_<System>(module, "System",
                     "An impact oscillator: M x'' + C x' + K x = A cos(omega t) while x_c < xs, "
                     "v_c -> -r v_c at the stop. Build it with System.paper(), System.chain(), "
                     "System.general() or System.from_file().")
      .def(py::init([] { return PaperSystem(); }), "The paper's system (Wagg & Bishop 2001).")
      .def_static("paper", &PaperSystem, py::arg("omega") = 1.0,
                  "The paper's system: N = 2, m = k = 1, c = 0.1, A = (0.5, 0), xs = 0.1, "
                  "r = 0.7.")
      .def_static(
          "chain",
          [](int n, double m, double k, double c, std::optional<Eigen::VectorXd> forcing,
             double omega, double xs, double r) {
            Eigen::VectorXd a = Eigen::VectorXd::Zero(std::max(n, 0));
            if (n > 0) a(0) = 0.5;
            System system = UniformChain({n, m, k, c}, forcing.value_or(a), omega, xs, r);
            Validate(system);
            return system;
          },
          py::kw_only(), py::arg("n") = 2, py::arg("m") = 1.0, py::arg("k") = 1.0,
          py::arg("c") = 0.1, py::arg("forcing") = py::none(), py::arg("omega") = 1.0,
          py::arg("xs") = 0.1, py::arg("r") = 0.7,
          "The uniform chain of n masses (the paper's case for n = 2); forcing defaults to "
          "0.5 on mass 1.")
      .def_static(
          "general",
          [](const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
             const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing, double omega,
             double xs, double r, std::optional<int> contact_dof) {
            // 0-based here, as numpy indexes (the library's message would
            // name the 1-based range of the files and the command line).
            const auto n = static_cast<int>(mass.rows());
            Require(!contact_dof || (*contact_dof >= 0 && *contact_dof < n),
                    "contact_dof must be in [0, " + std::to_string(n - 1) + "] (0-based), got " +
                        std::to_string(contact_dof.value_or(0)));
            System system =
                GeneralSystem(mass, damping, stiffness, forcing, omega, xs, r, contact_dof);
            Validate(system);
            return system;
          },
          py::arg("mass"), py::arg("damping"), py::arg("stiffness"), py::arg("forcing"),
          py::kw_only(), py::arg("omega") = 1.0, py::arg("xs") = 0.1, py::arg("r") = 0.7,
          py::arg("contact_dof") = py::none(),
          "A general system: symmetric M (positive definite), C, K; contact_dof (0-based) "
          "defaults to the last mass.")
      .def_static("from_file", &ReadSystemFile, py::arg("path"),
                  "Reads a system file (.json or .toml, docs/system-files.md).")
      .def_property_readonly("dof", &System::Dof, "Number of masses N.")
      .def_property_readonly(
          "mass", [](const System& s) { return s.mass; }, "M (a copy).")
      .def_property_readonly(
          "damping", [](const System& s) { return s.damping; }, "C (a copy).")
      .def_property_readonly(
          "stiffness", [](const System& s) { return s.stiffness; }, "K (a copy).")
      .def_property_readonly(
          "forcing", [](const System& s) { return s.forcing; }, "A (a copy).")
      .def_property_readonly(
          "stops",
          [](const System& s) {
            py::list stops;
            for (const StopParameters& stop : s.stops) stops.append(StopDict(stop));
            return stops;
          },
          "The stops: a list of {dof (0-based), side ('upper': x <= position, 'lower'), "
          "position, restitution}.")
      .def(
          "with_stops",
          [](const System& s, const std::vector<py::dict>& entries) {
            System copy = s;
            copy.stops.clear();
            for (std::size_t k = 0; k < entries.size(); ++k) {
              copy.stops.push_back(StopFromDict(entries[k], static_cast<int>(k)));
            }
            Validate(copy);
            return copy;
          },
          py::arg("stops"),
          "A copy with these stops: dicts {dof (0-based), position, side='upper', "
          "restitution=0.7}; ValueError if they are invalid.")
      .def_property_readonly(
          "is_chain", [](const System& s) { return s.chain.has_value(); },
          "True for a uniform chain (then m, k, c, n are parameters).")
      .def_property_readonly("forcing_period", &System::ForcingPeriod, "T = 2 pi / omega.")
      .def("parameter_names", &ParameterNames,
           "Names accepted by get/set: omega, xs, r, A1..AN, and m, k, c, n for chains.")
      .def(
          "get", [](const System& s, const std::string& name) { return GetParameter(s, name); },
          py::arg("name"), "The value of a named parameter (ValueError for an unknown name).")
      .def("set", &SetValidated, py::arg("name"), py::arg("value"),
           "Sets a named parameter; ValueError (system unchanged) if the result is invalid.")
      .def(
          "with_parameter",
          [](const System& s, const std::string& name, double value) {
            System copy = s;
            SetValidated(copy, name, value);
            return copy;
          },
          py::arg("name"), py::arg("value"), "A copy with one named parameter changed.")
      .def(
          "__getitem__",
          [](const System& s, const std::string& name) { return GetParameter(s, name); },
          "system['omega']: the same as get.")
      .def("__setitem__", &SetValidated, "system['omega'] = 1.2: the same as set.")
      .def("validate", &Validate, "Raises ValueError naming the first invalid field.")
      .def("to_json", &SystemToJson, "The system in the JSON form System.from_file reads.")
      .def("__copy__", [](const System& s) { return s; })
      .def(
          "__deepcopy__", [](const System& s, py::dict) { return s; }, py::arg("memo"))
      .def("__repr__", [](const System& s) { return "impactkit.System(" + SystemToJson(s) + ")"; });
}

}  // namespace impactkit::python
