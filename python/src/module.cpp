// The compiled part of the `impactkit` Python package, `impactkit._impactkit`:
// a thin layer over the C++ library. impactkit/__init__.py re-exports every
// name, and the classes and functions say they are impactkit's (their
// __module__, the names in signatures and messages), as before the package.
//
// Errors: the library's InvalidInput is a std::invalid_argument, which
// pybind11 raises as ValueError with the same message; numerical failures
// (no convergence) raise impactkit.NumericalError, a RuntimeError; a file
// that cannot be written (OutputError) raises OSError.
#include <Python.h>

#include <cmath>

#include "bindings.hpp"
#include "impactkit/io/branch_output.hpp"
#include "impactkit/io/output_file.hpp"

namespace impactkit::python {

py::object& NumericalErrorType() {
  // Leaked on purpose: the type lives as long as the interpreter, and
  // destroying it at exit would need the GIL after finalisation.
  static py::object* type = nullptr;
  if (type == nullptr) {
    type = new py::object(py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc("impactkit.NumericalError",
                                  "A computation that did not converge or could not go on "
                                  "(the message is the library's summary).",
                                  PyExc_RuntimeError, nullptr)));
  }
  return *type;
}

void ThrowNumericalError(const std::string& message) {
  PyErr_SetString(NumericalErrorType().ptr(), message.c_str());
  throw py::error_already_set();
}

void CheckInterrupt() {
  py::gil_scoped_acquire acquire;
  if (PyErr_CheckSignals() != 0) throw Interrupted();
}

InterruptibleRun::InterruptibleRun(const py::object& progress)
    : RunControl([this](const Progress& report) { Show(report); }) {
  if (PyCallable_Check(progress.ptr()) != 0) {
    callback_ = progress;
    return;
  }
  Require(progress.is_none() || py::isinstance<py::bool_>(progress),
          "progress must be True, False or a callable, got " + std::string(py::repr(progress)));
  if (!progress.is_none() && progress.cast<bool>()) {
    try {
      bar_class_ = py::module_::import("tqdm.auto").attr("tqdm");
    } catch (const py::error_already_set&) {
      // No tqdm: the run goes without a bar, as promised.
    }
  }
}

InterruptibleRun::~InterruptibleRun() {
  if (!bar_.is_none()) bar_.attr("close")();
}

void InterruptibleRun::Show(const Progress& report) {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw Interrupted();
  const std::string stage(report.stage);
  if (!callback_.is_none()) {
    // Where the run is, None where it is not a point's (a sweep's values).
    auto where = [](double value) {
      return std::isfinite(value) ? py::object(py::float_(value)) : py::object(py::none());
    };
    callback_(py::dict(py::arg("stage") = stage, py::arg("done") = report.done,
                       py::arg("total") = report.total,
                       py::arg("parameter") = where(report.parameter),
                       py::arg("parameter2") = where(report.parameter2)));
  }
  if (bar_class_.is_none()) return;
  if (bar_.is_none() || bar_stage_ != stage) {  // a new stage (a swept diagram's) has its bar
    if (!bar_.is_none()) bar_.attr("close")();
    bar_ = bar_class_(py::arg("total") = report.total > 0 ? py::object(py::int_(report.total))
                                                          : py::object(py::none()),
                      py::arg("desc") = stage, py::arg("leave") = false);
    bar_stage_ = stage;
  }
  bar_.attr("update")(report.done - bar_.attr("n").cast<std::int64_t>());
}

py::object NormalFormDict(const std::optional<GrazingNormalForm>& form) {
  if (!form) return py::none();
  return py::module_::import("json").attr("loads")(GrazingNormalFormJson(*form));
}

std::vector<UserTest> UserTestsFrom(const std::optional<py::dict>& tests) {
  std::vector<UserTest> converted;
  if (!tests) return converted;
  for (const auto& [key, value] : *tests) {
    Require(PyCallable_Check(value.ptr()) != 0,
            "user_tests: the value of '" + std::string(py::str(key)) + "' is not callable");
    // Shared, so that the library's copies of the test never touch the
    // callable's reference count without the GIL.
    const std::shared_ptr<py::function> function(
        new py::function(py::reinterpret_borrow<py::function>(value)), [](py::function* f) {
          py::gil_scoped_acquire gil;
          delete f;
        });
    converted.push_back({std::string(py::str(key)), [function](const PeriodicOrbit& orbit) {
                           py::gil_scoped_acquire gil;
                           return (*function)(orbit).cast<double>();
                         }});
  }
  return converted;
}

}  // namespace impactkit::python

PYBIND11_MODULE(_impactkit, module) {
  using namespace impactkit::python;
  // pybind11 names each class and function after the scope's __module__
  // when it has one: impactkit.System, not impactkit._impactkit.System.
  module.attr("__module__") = "impactkit";
  module.doc() =
      "impactkit: exact simulation, periodic orbits, continuation and analysis of "
      "multi-degree-of-freedom impact oscillators (Python interface to the C++ library).";
  module.attr("__version__") = IMPACTKIT_VERSION;
  module.attr("NumericalError") = NumericalErrorType();
  // A file that cannot be written (no such directory, no permission, a full
  // disk) is the operating system's error, as Python's own open() says.
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const impactkit::OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  BindSystem(module);
  BindSimulate(module);
  BindOrbit(module);
  BindContinuation(module);
  BindAnalysis(module);
  BindDiagram(module);
  BindGrid(module);
  BindCurve(module);
}
