#pragma once
/// \file sweep.hpp
/// Brute-force bifurcation diagrams: one named parameter (model.hpp's
/// ParameterNames) stepped through K evenly spaced values, the system
/// simulated at each to steady state, the recorded window kept and its
/// motion classified (classify.hpp). The paper's Fig. 3 is the sweep of
/// omega from 0.1 to 2.5.
///
/// At each value k, with T_k its forcing period and the state's time reset
/// to 0 (the previous run ended at a whole number of periods, so the forcing
/// phase stays continuous):
///
///     start  <- previous value's final state (kPrevious) or the fixed state
///     run transient_periods T_k, unrecorded
///     run recorded_periods T_k: every impact, per-period max - min of the
///         contact mass's x and of x_1 (ExtremaRecorder)
///     classify on the last W = max(recorded_periods, 2 max_q + 1) periods
///         (the period search needs 2q + 1 stroboscopic points; the part of
///         W before the recorded window comes from the end of the transient)
///
/// Early certainty (unless full_transient; docs/theory.md §10). A probe
/// (analysis/settling.hpp) watches the transient before W, in windows of
/// 2 min(max_q, 8) + 1 periods, without interrupting it. Once a window
/// repeats as P(p, q) with impacts and FindOrbit confirms a stable orbit
/// through its last impact (or release) that the periods left would bring
/// the state within 1e-10 of, the value runs only until they have, moves
/// its clock on by whole periods of the orbit to the last 2q + 1 periods,
/// and simulates, records and classifies those; the recorded periods
/// before them are copies of their last q, which the orbit repeats. So the
/// numbers recorded agree with the whole run's to ~1e-10, not bit for bit.
/// Chaotic, unresolved and non-impacting transients (and, after three
/// failed confirmations, any other) run whole, with the same bits as
/// without the probe. Should the last 2q + 1 periods not show the
/// confirmed period (or a divisor of it), the value is run again from its
/// start with its whole transient.
///
/// Threads and determinism. Starting from the previous value is sequential,
/// so the sweep is cut into chunks of `chunk_values` consecutive values (in
/// sweep order) that do not depend on the number of threads; threads take
/// whole chunks. A chunk other than the first starts `warmup_values` values
/// before its first value, from the fixed state, and runs those values'
/// transients only: it reaches its first value on the branch a single
/// sequential sweep would have followed unless that branch appeared within
/// the last warmup_values steps. Every chunk is computed the same way
/// whatever thread runs it, so results are bit-identical for any thread
/// count. chunk_values = 0 makes the whole sweep one chunk (exactly
/// sequential, one thread). With kFixed every value is independent.
///
/// A value whose start state does not fit its system (a swept xs below the
/// contact mass, a changed n) starts from the fixed state and is flagged
/// `restarted`; so is a value after one whose run stopped early.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/classify.hpp"
#include "impactkit/core/run_control.hpp"
#include "impactkit/core/termination.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

enum class SweepStart {
  kPrevious,  ///< each value from the previous value's final state (default)
  kFixed,     ///< each value from SweepOptions::fixed_state
};

enum class SweepDirection {
  kUp,    ///< increasing parameter values
  kDown,  ///< decreasing parameter values
};

std::string ToString(SweepStart start);
std::string ToString(SweepDirection direction);

struct SweepOptions {
  std::string parameter = "omega";  ///< a name of ParameterNames(system)
  double from = 0.1;                ///< one end of the range
  double to = 2.5;                  ///< the other end (either order)
  int steps = 2401;                 ///< K >= 1 values, both ends included (K = 1: `from`)
  int transient_periods = 500;      ///< forcing periods run and discarded at each value (>= 0)
  int recorded_periods = 100;       ///< forcing periods recorded at each value (>= 1)
  SweepStart start = SweepStart::kPrevious;
  /// The state of kFixed, of the first value, and of every chunk's warm-up;
  /// rest (RestState) when empty. Its time is ignored (runs start at t = 0).
  std::optional<HybridState> fixed_state;
  SweepDirection direction = SweepDirection::kUp;
  int threads = 1;  ///< worker threads (>= 1); results do not depend on it
  /// Consecutive values per chunk (>= 0; 0: one chunk). Part of the result's
  /// definition: change it and the chunk boundaries move.
  int chunk_values = 100;
  /// Values before a chunk's first whose transients it runs first (>= 0).
  int warmup_values = 5;
  /// Run every value's whole transient, without the early certainty of
  /// the file comment. Either way a value is classified the same from the
  /// same start (every cell of the paper's basins and fixed-start maps,
  /// docs/grids.md); a settled value's numbers agree to ~1e-10, and so,
  /// from the previous value, does the next value's start, which a chaotic
  /// value after it amplifies (its numbers, and where its class depends on
  /// its path, its class, differ: docs/grids.md lists the paper's).
  bool full_transient = false;
  ClassifyOptions classify;
  SimulationOptions simulation;
  bool IsValid(std::string* error) const;
};

/// One impact of the recorded window.
struct SweepImpact {
  double t = 0.0;         ///< time since the start of this value's run
  double phase = 0.0;     ///< t mod T, in [0, T)
  double velocity = 0.0;  ///< impact speed towards the stop
  int stop = 0;           ///< which stop (an index into System::stops)
};

/// What was found at one parameter value.
struct SweepPoint {
  double value = 0.0;  ///< the parameter
  std::vector<SweepImpact> impacts;
  /// The recorded window's last impact with the full state: a seed for the
  /// orbit the window shows (diagram seeds, sweep_seeds.hpp).
  std::optional<Impact> last_impact;
  /// max - min over each recorded forcing period of x_c (the contact mass;
  /// x_N for the paper's chain: its Fig. 3(a)) and of x_1.
  std::vector<double> range_contact;
  std::vector<double> range_first;
  Classification classification;
  /// How the run ended (kCompleted unless the simulator stopped early; then
  /// the window is short and the classification kUnresolved).
  Termination termination = Termination::kCompleted;
  bool restarted = false;   ///< started from the fixed state (see the file comment)
  std::int64_t events = 0;  ///< impacts, chatter jumps and releases simulated at this value
  /// Forcing periods simulated at this value: transient + recorded, or
  /// fewer when the transient ended early at a confirmed orbit.
  int periods_run = 0;
};

/// Summary::termination: kCompleted, or kStopped (cancelled: `points` then
/// holds the chunks finished, a leading part of the sweep); iterations
/// counts the values done.
struct SweepResult : Summary {
  std::vector<SweepPoint> points;  ///< in sweep order (see `direction`)
  int chunks = 0;
  /// "2401 values in 49 chunks on 2 threads, 6.1 s: 1800 periodic, ...".
  std::string BriefReport() const;
};

/// The K values in sweep order.
std::vector<double> SweepValues(const SweepOptions& options);

/// Runs the sweep. Throws InvalidInput for invalid options, an unknown
/// parameter, a value that makes the system invalid (checked for all values
/// before any work), or a fixed state that does not fit the system.
/// Progress: stage "sweep", values done of K. Cancelling `control` lets the
/// chunks running finish and starts no other.
SweepResult RunSweep(const System& system, const SweepOptions& options,
                     const RunControl& control = {});

/// The number of chunks RunSweep cuts the sweep into (>= 1).
int SweepChunks(const SweepOptions& options);

/// The points of one chunk of the sweep, `chunk` in [0, SweepChunks), the
/// values of [chunk * size, ...) in sweep order: the very points RunSweep
/// computes for them, for drivers that share chunks out themselves (a
/// parameter map, processes). Throws as RunSweep.
std::vector<SweepPoint> RunSweepChunk(const System& system, const SweepOptions& options, int chunk);

}  // namespace impactkit
