#include "impactkit/analysis/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "analysis/settling.hpp"
#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/core/parameter_grid.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {
namespace {

/// Throws InvalidInput(`what`) prefixed with where in the sweep it arose.
[[noreturn]] void ThrowAt(const std::string& name, double value, const InvalidInput& error) {
  throw InvalidInput(fmt::format("sweep of {} at {}: {}", name, value, error.what()));
}

/// `system` with the swept parameter set to `value`, its parameters checked
/// up front; the resonances are rejected where each value's simulator
/// decomposes its flows (once per value).
System SystemAt(const System& base, const std::string& name, double value) {
  System system = base;
  SetParameter(system, name, value);
  try {
    ValidateParameters(system);
  } catch (const InvalidInput& error) {
    ThrowAt(name, value, error);
  }
  return system;
}

bool Fits(const System& system, const HybridState& state) {
  if (state.x.size() != system.Dof() || state.v.size() != system.Dof()) return false;
  try {
    ValidateState(system, state);
  } catch (const InvalidInput&) {
    return false;
  }
  return true;
}

/// Everything that all chunks share, read-only.
struct SweepPlan {
  const SweepOptions& options;
  std::vector<double> values;
  std::vector<System> systems;  ///< one per value
  int chunk_size = 1;
  int chunks = 1;
};

HybridState FixedState(const SweepPlan& plan, int k) {
  HybridState state =
      plan.options.fixed_state ? *plan.options.fixed_state : RestState(plan.systems[k]);
  state.t = 0.0;
  return state;
}

Simulator SimulatorAt(const System& system, const SweepOptions& options) {
  try {
    return Simulator(system, options.simulation);
  } catch (const InvalidInput& error) {
    ThrowAt(options.parameter, GetParameter(system, options.parameter), error);
  }
}

class ValueRun {
 public:
  ValueRun(const System& system, const SweepOptions& options)
      : simulator_(SimulatorAt(system, options)), period_(system.ForcingPeriod()) {}

  /// Advances to period `k` (t = k T); false if the simulator stopped early.
  bool RunTo(HybridState& state, int k, Observer* observer) {
    const double t_end = static_cast<double>(k) * period_;
    if (!(t_end > state.t)) return true;
    const double t_begin = state.t;
    const SimulationSummary summary =
        observer ? simulator_.Run(state, t_end, *observer) : simulator_.Run(state, t_end);
    periods_run_ += static_cast<int>(std::lround((state.t - t_begin) / period_));
    events_ += summary.impacts + summary.chatter_jumps + summary.releases;
    status_ = summary.termination;
    return status_ == Termination::kCompleted;
  }

  /// Moves the clock of a state at a whole period on to period `k`
  /// without running: the forcing is T-periodic, so a state on an orbit of
  /// q periods, moved by a multiple of q, is where the run would have been.
  void Skip(HybridState& state, int k) const { state.t = static_cast<double>(k) * period_; }

  double Period() const { return period_; }
  std::int64_t Events() const { return events_; }
  int PeriodsRun() const { return periods_run_; }
  Termination Status() const { return status_; }

 private:
  Simulator simulator_;
  double period_;
  std::int64_t events_ = 0;
  int periods_run_ = 0;
  Termination status_ = Termination::kCompleted;
};

/// Per-period max - min of x_i.
std::vector<double> Ranges(const std::vector<PeriodExtrema>& periods, int i) {
  std::vector<double> ranges;
  ranges.reserve(periods.size());
  for (const PeriodExtrema& e : periods) ranges.push_back(e.max(i) - e.min(i));
  return ranges;
}

/// The early certainty's windows (sweep.hpp, docs/theory.md §10): 2 min(max_q,
/// 8) + 1 periods, so that a window stays short beside the transient,
/// compared to the classification's tolerance.
ProbeOptions ProbeOptionsFor(const SweepOptions& options, int end) {
  ProbeOptions probe;
  probe.period = {std::min(options.classify.period.max_q, 8), options.classify.period.tolerance};
  probe.end = end;
  return probe;
}

/// A value's periods: [0, transient) discarded, [transient, end) recorded,
/// [first_classified, end) classified (sweep.hpp).
struct ValuePeriods {
  explicit ValuePeriods(const SweepOptions& options)
      : transient(options.transient_periods),
        end(transient + options.recorded_periods),
        first_classified(std::max(
            0, end - std::max(options.recorded_periods, 2 * options.classify.period.max_q + 1))) {}
  int transient, end, first_classified;
};

/// Runs the transient to period `end` under a TransientProbe. Once it
/// confirms an orbit, runs on until the state has settled on it, at a
/// whole period before `end`, and sets `settled`; otherwise runs to `end`.
/// False if the simulator stopped early.
bool SettleTransient(const System& system, const SweepOptions& options, ValueRun& run,
                     HybridState& state, int end, std::optional<Settling>* settled) {
  TransientProbe probe(system, run.Period(), ProbeOptionsFor(options, end));
  if (run.RunTo(state, end, &probe)) return true;
  if (!probe.Settled()) return false;  // the simulator stopped early
  // Stopped after the event that followed the confirmation.
  const int settled_at =
      static_cast<int>(std::ceil(state.t / run.Period())) + probe.Settled()->periods;
  if (settled_at >= end) return run.RunTo(state, end, nullptr);
  *settled = probe.Settled();
  return run.RunTo(state, settled_at, nullptr);
}

/// `simulated` (the values of periods [end - simulated.size(), end)) with
/// the periods [first, end - simulated.size()) before them filled by
/// copies of their last q: the values of periods [first, end).
std::vector<double> Repeated(const std::vector<double>& simulated, int q, int first, int end) {
  const int from = end - static_cast<int>(simulated.size());
  std::vector<double> values;
  values.reserve(end - first);
  for (int k = first; k < from; ++k) {
    const int offset = ((k - end) % q + q) % q;  // period k's place among the last q
    values.push_back(simulated[simulated.size() - q + offset]);
  }
  values.insert(values.end(), simulated.begin(), simulated.end());
  return values;
}

/// Runs from the current period `from` to the end, recording: impacts,
/// strobes and chatter from `from` on, per-period extrema of the recorded
/// part. Fills `point` and classifies. A value settled on an orbit of q > 0
/// periods may start after the recorded window's start (RunValue): the
/// recorded periods before `from` are then copies of the last q simulated,
/// which the orbit repeats to the settling accuracy (and, should the
/// extrema not cover every simulated period, the motion is left
/// unclassified, so that the value is run again whole). False if the
/// simulator stopped early.
bool RecordWindow(const System& system, const SweepOptions& options, ValueRun& run,
                  HybridState& state, const ValuePeriods& periods, int q, SweepPoint* point) {
  SteadyWindowRecorder steady(run.Period());
  ExtremaRecorder extrema(run.Period());
  ObserverList recorded;
  recorded.Add(steady);
  recorded.Add(extrema);
  const int from =
      std::max(periods.transient, static_cast<int>(std::lround(state.t / run.Period())));
  const bool reached =
      run.RunTo(state, periods.transient, &steady) && run.RunTo(state, periods.end, &recorded);
  const double t_record = periods.transient * run.Period();
  const double t_from = from * run.Period(), span = q * run.Period();
  // Copies of the last q periods' impacts moved back by whole spans into
  // [t_record, t_from), in time order.
  for (int m = q > 0 ? (periods.end - periods.transient) / q + 1 : 0; m >= 1; --m) {
    for (const ImpactView i : steady.Impacts()) {
      const double t = i.t - m * span;
      if (i.t >= periods.end * run.Period() - span && t >= t_record && t < t_from) {
        point->impacts.push_back(SweepImpact{t, i.phase, i.velocity, i.stop});
      }
    }
  }
  for (const ImpactView i : steady.Impacts()) {
    if (i.t >= t_record) point->impacts.push_back(SweepImpact{i.t, i.phase, i.velocity, i.stop});
  }
  if (!steady.Impacts().empty() && steady.Impacts().back().t >= t_record) {
    point->last_impact = steady.Impacts().back().Owned();
  }
  const std::vector<PeriodExtrema> extremes = extrema.CompletePeriods();
  point->range_contact = Ranges(extremes, system.stops[0].dof);
  point->range_first = Ranges(extremes, 0);
  const bool copied = from > periods.transient;
  if (copied && static_cast<int>(extremes.size()) != periods.end - from) return reached;
  if (copied) {
    point->range_contact = Repeated(point->range_contact, q, periods.transient, periods.end);
    point->range_first = Repeated(point->range_first, q, periods.transient, periods.end);
  }
  if (reached) {
    point->classification = ClassifyMotion(system, steady.Strobe(), steady.Impacts(),
                                           steady.ChatterEnds(), options.classify);
  }
  return reached;
}

/// The window shows the period the transient's early end was confirmed
/// on, or a divisor of it: near a period doubling the transient still
/// alternates when a probe window sees it, and the P(2,2) confirmed is the
/// P(1,1) run twice, which the window, settled, shows as such.
bool ShowsPeriod(const MotionPeriod& window, const MotionPeriod& confirmed) {
  return window.periodic && window.sticking == confirmed.sticking && confirmed.q % window.q == 0 &&
         window.p * confirmed.q == confirmed.p * window.q;
}

/// One value from `state` (time reset to 0); `state` ends where the run
/// ended. False if the simulator stopped early. Unless `full_transient`,
/// the transient may end early at a confirmed orbit of q periods
/// (SettleTransient); the clock then moves on by whole periods of the
/// orbit to the last 2q + 1 periods, which the period test needs, and only
/// those are simulated (RecordWindow). Should they not show the confirmed
/// period, the value is run again, whole.
bool RunValue(const System& system, const SweepOptions& options, bool full_transient,
              HybridState& state, SweepPoint* point) {
  const HybridState start = state;
  ValueRun run(system, options);
  const ValuePeriods periods(options);
  state.t = 0.0;
  std::optional<Settling> settled;
  bool reached = full_transient ? run.RunTo(state, periods.first_classified, nullptr)
                                : SettleTransient(system, options, run, state,
                                                  periods.first_classified, &settled);
  if (settled) {
    // Settled at period k < first_classified <= end - (2q + 1) (q <= 8 <= max_q).
    const int k = static_cast<int>(std::lround(state.t / run.Period()));
    run.Skip(state, k + (periods.end - 2 * settled->q - 1 - k) / settled->q * settled->q);
  }
  reached = reached &&
            RecordWindow(system, options, run, state, periods, settled ? settled->q : 0, point);
  point->termination = run.Status();
  point->events = run.Events();
  point->periods_run = run.PeriodsRun();
  if (settled && !(reached && ShowsPeriod(point->classification.period, settled->period))) {
    SweepPoint whole;
    whole.value = point->value;
    whole.restarted = point->restarted;
    state = start;
    const bool again = RunValue(system, options, true, state, &whole);
    whole.events += run.Events();
    whole.periods_run += run.PeriodsRun();
    *point = std::move(whole);
    return again;
  }
  return reached;
}

/// Values [begin, end) of the sweep, in order, into `points`.
void RunChunk(const SweepPlan& plan, int chunk, std::vector<SweepPoint>& points,
              const std::function<void()>& value_done) {
  const SweepOptions& options = plan.options;
  const int begin = chunk * plan.chunk_size;
  const int end = std::min<int>(begin + plan.chunk_size, static_cast<int>(plan.values.size()));
  const bool previous = options.start == SweepStart::kPrevious;
  HybridState state;
  bool have_state = false;
  if (previous && begin > 0) {
    // The warm-up: transients only, from the fixed state, on the way to `begin`.
    for (int k = std::max(0, begin - options.warmup_values); k < begin; ++k) {
      if (!have_state || !Fits(plan.systems[k], state)) state = FixedState(plan, k);
      ValueRun run(plan.systems[k], options);
      state.t = 0.0;
      have_state = run.RunTo(state, options.transient_periods, nullptr);
    }
  }
  for (int k = begin; k < end; ++k) {
    SweepPoint& point = points[k];
    point.value = plan.values[k];
    if (!previous || !have_state || !Fits(plan.systems[k], state)) {
      point.restarted = previous && k > 0;
      state = FixedState(plan, k);
    }
    have_state = RunValue(plan.systems[k], options, options.full_transient, state, &point);
    value_done();
  }
}

}  // namespace

std::string ToString(SweepStart start) {
  return start == SweepStart::kPrevious ? "previous" : "fixed";
}

std::string ToString(SweepDirection direction) {
  return direction == SweepDirection::kUp ? "up" : "down";
}

bool SweepOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (steps < 1) return fail(fmt::format("steps must be >= 1, got {}", steps));
  if (!std::isfinite(from) || !std::isfinite(to)) {
    return fail(fmt::format("from and to must be finite, got {} and {}", from, to));
  }
  if (steps > 1 && from == to) {
    return fail(
        fmt::format("from and to are both {}: {} steps need a range (or steps = 1)", from, steps));
  }
  if (transient_periods < 0) {
    return fail(fmt::format("transient periods must be >= 0, got {}", transient_periods));
  }
  if (recorded_periods < 1) {
    return fail(fmt::format("recorded periods must be >= 1, got {}", recorded_periods));
  }
  // RunSweep adds and doubles these in int: refuse what would overflow.
  if (transient_periods > std::numeric_limits<int>::max() - recorded_periods) {
    return fail(fmt::format("transient + recorded periods must be at most {}, got {} + {}",
                            std::numeric_limits<int>::max(), transient_periods, recorded_periods));
  }
  if (classify.period.max_q > (std::numeric_limits<int>::max() - 1) / 2) {
    return fail(fmt::format("max_q must be at most {}, got {}",
                            (std::numeric_limits<int>::max() - 1) / 2, classify.period.max_q));
  }
  if (threads < 1) return fail(fmt::format("threads must be >= 1, got {}", threads));
  if (chunk_values < 0) return fail(fmt::format("chunk_values must be >= 0, got {}", chunk_values));
  if (warmup_values < 0) {
    return fail(fmt::format("warmup_values must be >= 0, got {}", warmup_values));
  }
  return classify.IsValid(error) && simulation.IsValid(error);
}

std::string SweepResult::BriefReport() const {
  std::map<MotionKind, int> counts;
  int restarted = 0, stopped = 0;
  for (const SweepPoint& p : points) {
    ++counts[p.classification.kind];
    restarted += p.restarted;
    stopped += p.termination != Termination::kCompleted;
  }
  std::string kinds;
  for (const auto& [kind, count] : counts) {
    kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", count, ToString(kind));
  }
  std::string text =
      fmt::format("{} values in {} chunks, {:.2f} s: {}", points.size(), chunks, seconds, kinds);
  if (restarted > 0) text += fmt::format("; {} restarted from the fixed state", restarted);
  if (stopped > 0) text += fmt::format("; {} runs stopped early", stopped);
  return text;
}

std::vector<double> SweepValues(const SweepOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  if (options.steps == 1) return {options.from};
  std::vector<double> values = GridValues(std::min(options.from, options.to),
                                          std::max(options.from, options.to), options.steps);
  if (options.direction == SweepDirection::kDown) std::reverse(values.begin(), values.end());
  return values;
}

namespace {

/// Values per chunk of a sweep of `total` values.
int ChunkSize(const SweepOptions& options, int total) {
  return options.chunk_values == 0 ? total : std::min(options.chunk_values, total);
}

/// The systems of every value (checked before any work) and the chunks.
SweepPlan PlanSweep(const System& system, const SweepOptions& options) {
  SweepPlan plan{options, SweepValues(options), {}};
  GetParameter(system, options.parameter);  // throws for an unknown name
  plan.systems.reserve(plan.values.size());
  for (double value : plan.values) {
    plan.systems.push_back(SystemAt(system, options.parameter, value));
    if (options.fixed_state) {
      HybridState fixed = *options.fixed_state;
      fixed.t = 0.0;
      ValidateState(plan.systems.back(), fixed);
    }
  }
  const int total = static_cast<int>(plan.values.size());
  plan.chunk_size = ChunkSize(options, total);
  plan.chunks = (total + plan.chunk_size - 1) / plan.chunk_size;
  return plan;
}

}  // namespace

int SweepChunks(const SweepOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const int size = ChunkSize(options, options.steps);
  return (options.steps + size - 1) / size;
}

std::vector<SweepPoint> RunSweepChunk(const System& system, const SweepOptions& options,
                                      int chunk) {
  const SweepPlan plan = PlanSweep(system, options);
  Require(chunk >= 0 && chunk < plan.chunks,
          fmt::format("sweep chunk {} out of range [0, {})", chunk, plan.chunks));
  std::vector<SweepPoint> points(plan.values.size());
  RunChunk(plan, chunk, points, [] {});
  const int begin = chunk * plan.chunk_size;
  const int end = std::min<int>(begin + plan.chunk_size, static_cast<int>(points.size()));
  return {std::make_move_iterator(points.begin() + begin),
          std::make_move_iterator(points.begin() + end)};
}

SweepResult RunSweep(const System& system, const SweepOptions& options, const RunControl& control) {
  const auto start_time = std::chrono::steady_clock::now();
  const SweepPlan plan = PlanSweep(system, options);
  const int total = static_cast<int>(plan.values.size());

  SweepResult result;
  result.points.resize(total);
  result.chunks = plan.chunks;
  std::mutex mutex;
  int done = 0;
  auto value_done = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    control.Report({.stage = "sweep", .done = ++done, .total = total});
  };
  int next_chunk = 0;
  bool failed = false;
  std::exception_ptr error;
  // Chunks are taken in order, under the lock with the cancellation check,
  // and each taken one finishes: those done when the run is cancelled are
  // the leading ones.
  auto take = [&]() -> std::optional<int> {
    const std::lock_guard<std::mutex> lock(mutex);
    if (failed || control.Cancelled() || next_chunk == plan.chunks) return std::nullopt;
    return next_chunk++;
  };
  auto worker = [&] {
    while (const std::optional<int> chunk = take()) {
      try {
        RunChunk(plan, *chunk, result.points, value_done);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  const int threads = std::min(options.threads, plan.chunks);
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  result.termination = Termination::kCompleted;
  if (done < total) {
    result.points.resize(done);
    result.termination = Termination::kStopped;
    result.message =
        fmt::format("{} after {} of {} values", Describe(result.termination), done, total);
  }
  result.iterations = done;
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace impactkit
