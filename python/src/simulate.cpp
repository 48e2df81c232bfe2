// impactkit.simulate: hybrid/simulator.hpp and the recorders of
// hybrid/recorders.hpp, with every result as numpy arrays.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit::python {
namespace {

/// Samples of one run (2N + 2 numbers each, held in memory): 10^8 is
/// gigabytes, far beyond any plot; more is a mistyped dt.
constexpr double kMaxSamples = 1e8;

/// Impacts in flat row-major arrays, so that 10^6 of them reach numpy as a
/// handful of buffers (MoveToArray) instead of 10^6 Python objects.
class FlatImpactRecorder : public Observer {
 public:
  void OnImpact(const Impact& impact) override {
    t.push_back(impact.t);
    phase.push_back(impact.phase);
    velocity.push_back(impact.velocity);
    stop.push_back(impact.stop);
    x.insert(x.end(), impact.x.begin(), impact.x.end());
    v.insert(v.end(), impact.v.begin(), impact.v.end());
  }
  std::vector<double> t, phase, velocity, x, v;
  std::vector<int> stop;
};

/// Asks the simulator to stop when Python has a pending signal. The
/// simulator asks after every event, and at least every 1000 forcing periods
/// of a run without events; the GIL is taken at most every 0.1 s, which
/// keeps the check's cost out of the event loop.
class InterruptWatch : public Observer {
 public:
  bool ShouldStop() const override {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_check_ < std::chrono::milliseconds(100)) return false;
    last_check_ = now;
    CheckInterrupt();
    return false;
  }

 private:
  mutable std::chrono::steady_clock::time_point last_check_ = std::chrono::steady_clock::now();
};

/// Samples (t, x, v, stuck, event) as arrays of shapes (n,), (n, N), (n, N),
/// (n,), (n,); event "" on the time grid, else the event's name.
py::dict SampleArrays(const SampleLog& samples, int dof) {
  std::vector<double> t, x, v;
  for (const SampleView s : samples) {
    t.push_back(s.t);
    x.insert(x.end(), s.x.begin(), s.x.end());
    v.insert(v.end(), s.v.begin(), s.v.end());
  }
  const auto n = static_cast<py::ssize_t>(samples.size());
  py::array_t<bool> stuck(n);
  py::list events;
  for (py::ssize_t i = 0; i < n; ++i) {
    stuck.mutable_at(i) = samples[i].stuck;
    events.append(samples[i].kind == SampleKind::kGrid ? "" : ToString(samples[i].kind));
  }
  py::dict out;
  out["t"] = MoveToArray(std::move(t));
  out["x"] = MoveToArray<double, 2>(std::move(x), {n, dof});
  out["v"] = MoveToArray<double, 2>(std::move(v), {n, dof});
  out["stuck"] = stuck;
  // A numpy array of str, as the other fields are arrays.
  out["event"] = py::module_::import("numpy").attr("array")(events, "U13");
  return out;
}

SimulationOptions MakeOptions(const std::string& chatter, double chatter_span,
                              double chatter_threshold, double bounce_height_resolution,
                              std::int64_t max_events_per_period, std::int64_t max_events) {
  SimulationOptions options;
  if (chatter == "accumulation") {
    options.chatter = ChatterMethod::kAccumulation;
  } else if (chatter == "threshold") {
    options.chatter = ChatterMethod::kThreshold;
  } else {
    throw InvalidInput("chatter must be 'accumulation' or 'threshold', got '" + chatter + "'");
  }
  options.chatter_span = chatter_span;
  options.chatter_threshold = chatter_threshold;
  options.bounce_height_resolution = bounce_height_resolution;
  options.max_events_per_period = max_events_per_period;
  options.max_events = max_events;
  return options;
}

py::dict Simulate(const System& system, double t_end, std::optional<Eigen::VectorXd> x0,
                  std::optional<Eigen::VectorXd> v0, double record_from, double dt,
                  const std::string& chatter, double chatter_span, double chatter_threshold,
                  double bounce_height_resolution, std::int64_t max_events_per_period,
                  std::int64_t max_events, bool events) {
  const SimulationOptions options =
      MakeOptions(chatter, chatter_span, chatter_threshold, bounce_height_resolution,
                  max_events_per_period, max_events);
  const Simulator simulator(system, options);
  HybridState state = RestState(system);
  if (x0) state.x = *x0;
  if (v0) state.v = *v0;
  Require(std::isfinite(record_from) && record_from >= 0.0,
          fmt::format("record_from must be finite and >= 0, got {}", record_from));
  Require(std::isfinite(t_end) && t_end >= record_from,
          fmt::format("t_end must be finite and >= record_from = {}, got {}", record_from, t_end));
  Require(std::isfinite(dt) && dt >= 0.0,
          fmt::format("dt must be finite and >= 0 (0: no time series), got {}", dt));
  Require(dt == 0.0 || (t_end - record_from) / dt <= kMaxSamples,
          fmt::format("dt = {} gives {:.3g} samples from record_from to t_end; at most {:.0e} "
                      "(the series is held in memory)",
                      dt, (t_end - record_from) / dt, kMaxSamples));

  FlatImpactRecorder impacts;
  TimeSeriesRecorder series(record_from, dt > 0.0 ? dt : 1.0, events);
  StroboscopicRecorder strobe(system.ForcingPeriod());
  StickingRecorder sticking;
  InterruptWatch watch;
  ObserverList recorded;
  recorded.Add(impacts);
  if (dt > 0.0) recorded.Add(series);
  recorded.Add(strobe);
  recorded.Add(sticking);
  recorded.Add(watch);

  const SimulationSummary summary = WithoutGil([&] {
    simulator.Run(state, record_from, watch);
    return simulator.Run(state, t_end, recorded);
  });

  const int dof = system.Dof();
  const auto m = static_cast<py::ssize_t>(impacts.t.size());
  py::dict impact_arrays;
  impact_arrays["t"] = MoveToArray(std::move(impacts.t));
  impact_arrays["phase"] = MoveToArray(std::move(impacts.phase));
  impact_arrays["velocity"] = MoveToArray(std::move(impacts.velocity));
  impact_arrays["stop"] = MoveToArray(std::move(impacts.stop));
  impact_arrays["x"] = MoveToArray<double, 2>(std::move(impacts.x), {m, dof});
  impact_arrays["v"] = MoveToArray<double, 2>(std::move(impacts.v), {m, dof});

  std::vector<double> intervals;
  for (const StickingInterval& interval : sticking.Intervals()) {
    intervals.push_back(interval.begin);
    intervals.push_back(interval.end);
  }
  const auto k = static_cast<py::ssize_t>(sticking.Intervals().size());

  py::dict result;
  result["samples"] = SampleArrays(series.Samples(), dof);
  result["impacts"] = impact_arrays;
  result["strobe"] = SampleArrays(strobe.Points(), dof);
  result["sticking"] = MoveToArray<double, 2>(std::move(intervals), {k, 2});
  result["termination"] = ToString(summary.termination);
  result["chatter_jumps"] = summary.chatter_jumps;
  result["landings"] = summary.landings;
  result["chatter_cuts"] = summary.chatter_cuts;
  result["stuck_time"] = summary.stuck_time;
  result["seconds"] = summary.seconds;
  result["final_state"] = py::dict(py::arg("t") = state.t, py::arg("x") = state.x,
                                   py::arg("v") = state.v, py::arg("stuck") = state.Stuck());
  return result;
}

}  // namespace

void BindSimulate(py::module_& module) {
  const SimulationOptions kRun;  // the defaults are the library's, as the command line's are
  module.def("simulate", &Simulate, py::arg("system"), py::arg("t_end"), py::kw_only(),
             py::arg("x0") = py::none(), py::arg("v0") = py::none(), py::arg("record_from") = 0.0,
             py::arg("dt") = 0.0, py::arg("chatter") = "accumulation",
             py::arg("chatter_span") = kRun.chatter_span,
             py::arg("chatter_threshold") = kRun.chatter_threshold,
             py::arg("bounce_height_resolution") = kRun.bounce_height_resolution,
             py::arg("max_events_per_period") = kRun.max_events_per_period,
             py::arg("max_events") = kRun.max_events, py::arg("events") = false,
             R"(Simulates from (x0, v0) at t = 0 (rest by default) to t_end, exactly.

Nothing is recorded before record_from. Returns a dict of numpy arrays:
  samples   {t (n,), x (n, N), v (n, N), stuck (n,) bool, event (n,) str}
            every dt from record_from (empty when dt = 0); with events=True
            also each event, in time order: every impact twice at its instant
            ('impact_before', 'impact_after': v_c -> -r v_c), 'stick' and
            'release' (event '' on the grid)
  impacts   {t, phase, velocity (m,), stop (m,) int: which stop (0-based), x (m, N),
             v (m, N) just before impact}
  strobe    the state at every t = k T (forcing phase 0), as samples
  sticking  (k, 2) [begin, end] of each interval held at the stop
and termination ('completed', 'event_limit', 'work_limit', 'stalled', 'stopped'),
chatter_jumps, chatter_cuts (elastic chatter cut at a short bounce), landings (arrivals
at the stop too low to be impacts), stuck_time,
seconds, final_state. bounce_height_resolution (the rounding, by default) and max_events_per_period are
the height resolution and the work bound of docs/theory.md §4. Releases the GIL; Ctrl-C raises KeyboardInterrupt.)");
}

}  // namespace impactkit::python
