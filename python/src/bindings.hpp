#pragma once
/// \file bindings.hpp
/// The parts of the `impactkit` Python module, one Bind function per library
/// area (each in its own source), and what they share: arrays handed to
/// numpy without copies, the exception for numerical failures, and the
/// Ctrl-C check of long calls. The module has no numerics of its own.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "impactkit/analysis/sweep.hpp"
#include "impactkit/continuation/continuation.hpp"

namespace impactkit::python {

namespace py = pybind11;

void BindSystem(py::module_& module);
void BindSimulate(py::module_& module);
void BindOrbit(py::module_& module);
void BindContinuation(py::module_& module);
void BindAnalysis(py::module_& module);
void BindDiagram(py::module_& module);
void BindGrid(py::module_& module);
void BindCurve(py::module_& module);

/// impactkit.NumericalError (a RuntimeError): a computation that did not
/// converge or could not go on. Created by the module before any Bind.
py::object& NumericalErrorType();
/// Raises NumericalError(message).
[[noreturn]] void ThrowNumericalError(const std::string& message);

/// Thrown out of a library callback when Python has a pending signal
/// (Ctrl-C): it unwinds the library call, and the binding, holding the GIL
/// again, re-raises the Python error (KeyboardInterrupt).
struct Interrupted : std::exception {};
/// From a library callback running without the GIL: takes the GIL, runs
/// the signal handlers and throws Interrupted if one raised. Only Python's
/// main thread sees signals; elsewhere it returns.
void CheckInterrupt();
/// The control of a library run called from Python. At each progress
/// report Ctrl-C raises KeyboardInterrupt (through Interrupted), and the
/// caller's `progress` is shown: True draws a tqdm bar (tqdm.auto: a widget
/// in Jupyter) where tqdm is installed, nothing where it is not; a callable
/// is called with {stage, done, total, parameter, parameter2} (None where
/// the run has no point), and what it raises reaches the caller. Made and
/// destroyed holding the GIL (outside WithoutGil); each report takes it.
class InterruptibleRun : public RunControl {
 public:
  explicit InterruptibleRun(const py::object& progress);
  /// Closes the bar.
  ~InterruptibleRun();
  InterruptibleRun(const InterruptibleRun&) = delete;
  InterruptibleRun& operator=(const InterruptibleRun&) = delete;

 private:
  void Show(const Progress& progress);

  py::object callback_ = py::none();   ///< the caller's callable, or None
  py::object bar_class_ = py::none();  ///< tqdm.auto.tqdm when a bar is asked for and installed
  py::object bar_ = py::none();        ///< the bar of the stage running
  std::string bar_stage_;
};
/// Runs `call` without the GIL; an Interrupted from it becomes the pending
/// Python exception.
template <class Call>
auto WithoutGil(Call&& call) {
  try {
    py::gil_scoped_release release;
    return call();
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
}

/// The user's test functions from {name: callable(Orbit) -> float}. The
/// library calls them without the GIL (and a diagram from its threads):
/// each call takes it, and the last copy of a callable lets it go holding
/// it. An exception the callable raises ends the library call with it.
std::vector<UserTest> UserTestsFrom(const std::optional<py::dict>& tests);

/// A grazing's normal form (with its prediction) as the dict files carry
/// under `normal_form` (io/branch_output.hpp's GrazingNormalFormJson), or
/// None.
py::object NormalFormDict(const std::optional<GrazingNormalForm>& form);

/// The `each_from` keyword of sweep and parameter_map (and of their option
/// sets): 'previous' or 'rest' (kFixed: Python gives no fixed state, so it
/// is rest). StartFromName throws InvalidInput (ValueError) for another name.
SweepStart StartFromName(const std::string& each_from);
std::string StartName(SweepStart start);

/// The values of `data` as a numpy array of the given shape, without a
/// copy: the vector moves to the heap and the array's base owns it.
template <class T, std::size_t Rank>
py::array_t<T> MoveToArray(std::vector<T>&& data, const std::array<py::ssize_t, Rank>& shape) {
  auto* owned = new std::vector<T>(std::move(data));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::vector<py::ssize_t>(shape.begin(), shape.end()), owned->data(), owner);
}
template <class T>
py::array_t<T> MoveToArray(std::vector<T>&& data) {
  const auto size = static_cast<py::ssize_t>(data.size());
  return MoveToArray<T, 1>(std::move(data), {size});
}

/// One value per item of `items`, as an array of T: a column of a branch's
/// points, a curve's points, a diagram's edges.
template <class T, class Items, class Get>
py::array_t<T> Column(const Items& items, Get get) {
  std::vector<T> values;
  values.reserve(items.size());
  for (const auto& item : items) values.push_back(static_cast<T>(get(item)));
  return MoveToArray(std::move(values));
}

}  // namespace impactkit::python
