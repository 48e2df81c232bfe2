#pragma once
/// \file simulate/run.hpp
/// The job of `impactkit simulate`: from an initial state, run a transient
/// of whole forcing periods and discard it, then record a window
///
///     [t1, t2] = [transient T, (transient + periods) T],   T = 2π/Ω,
///
/// so that stroboscopic points fall at forcing phase 0; then summarise the
/// window and write what was asked for.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/system_options.hpp"
#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit::cli {

/// What the flags ask for; checked by RunSimulate.
struct SimulateRequest {
  SystemOptions system;
  long transient = 200;           ///< forcing periods run and discarded (>= 0)
  long periods = 20;              ///< forcing periods recorded (>= 1)
  long samples_per_period = 200;  ///< time-series samples per forcing period (>= 1)
  std::vector<double> x0;         ///< initial positions at t = 0; empty: rest
  std::vector<double> v0;         ///< initial velocities at t = 0; empty: rest
  ChatterMethod chatter = ChatterMethod::kAccumulation;
  std::optional<double> chatter_threshold;  ///< only with ChatterMethod::kThreshold
  std::filesystem::path series;             ///< outputs; an empty path is not written
  std::filesystem::path impacts;
  std::filesystem::path plot;
  std::filesystem::path json;
};

/// The recorded window in time and in forcing periods.
struct Window {
  double begin = 0.0;   ///< t1
  double end = 0.0;     ///< t2
  double period = 0.0;  ///< T
  long first_period = 0;
  long periods = 0;
};

/// The recorders of the window, wired into one observer. Not movable: the
/// list points at its members.
struct WindowRecorders {
  WindowRecorders(const Window& window, std::optional<double> sample_interval);
  WindowRecorders(const WindowRecorders&) = delete;
  WindowRecorders& operator=(const WindowRecorders&) = delete;

  /// Impacts, stroboscopic points and chatter ends, as every steady-state
  /// analysis records them; the motion's period comes from them.
  SteadyWindowRecorder steady;
  StickingRecorder sticking;
  std::optional<TimeSeriesRecorder> series;  ///< only when a series or plot is asked for
  ObserverList all;
};

/// What the window shows.
struct WindowAnalysis {
  double impacts_per_period = 0.0;
  double sticking_fraction = 0.0;  ///< time stuck / window length
  long chatter_sequences = 0;
  /// Of those, the ones cut without accumulating (elastic chatter at a
  /// short bounce: SimulationSummary::chatter_cuts), over the window.
  std::int64_t chatter_cuts = 0;
  MotionPeriod motion;
  int searched_q = 0;  ///< periods up to this q were looked for
};

/// A finished run, as the summary and the output files see it.
struct SimulateResult {
  const SimulateRequest& request;
  const System& system;
  const Window& window;
  const WindowRecorders& recorders;
  const WindowAnalysis& analysis;
  const HybridState& initial_state;  ///< at t = 0
  const HybridState& final_state;    ///< at the end of the window
  double seconds = 0.0;              ///< transient and window together
};

/// The simulator options the request asks for.
SimulationOptions SimulationOptionsOf(const SimulateRequest& request);

/// Runs the job: prints the summary on stdout and writes the outputs.
/// Throws InvalidInput for bad input (before any simulation), OutputError,
/// PlotError or std::runtime_error when the run fails.
void RunSimulate(const SimulateRequest& request);

}  // namespace impactkit::cli
