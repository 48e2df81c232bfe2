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
    const SimulationSummary summary =
        observer ? simulator_.Run(state, t_end, *observer) : simulator_.Run(state, t_end);
    events_ += summary.impacts + summary.chatter_jumps + summary.releases;
    status_ = summary.termination;
    return status_ == Termination::kCompleted;
  }

  double Period() const { return period_; }
  std::int64_t Events() const { return events_; }
  Termination Status() const { return status_; }

 private:
  Simulator simulator_;
  double period_;
  std::int64_t events_ = 0;
  Termination status_ = Termination::kCompleted;
};

/// Per-period max - min of x_i.
std::vector<double> Ranges(const std::vector<PeriodExtrema>& periods, int i) {
  std::vector<double> ranges;
  ranges.reserve(periods.size());
  for (const PeriodExtrema& e : periods) ranges.push_back(e.max(i) - e.min(i));
  return ranges;
}

/// One value from `state` (time reset to 0); `state` ends where the run
/// ended. False if the simulator stopped early.
bool RunValue(const System& system, const SweepOptions& options, HybridState& state,
              SweepPoint* point) {
  ValueRun run(system, options);
  const int transient = options.transient_periods;
  const int end = transient + options.recorded_periods;
  const int window = std::max(options.recorded_periods, 2 * options.classify.period.max_q + 1);
  const int first_classified = std::max(0, end - window);
  state.t = 0.0;

  SteadyWindowRecorder steady(run.Period());
  ExtremaRecorder extrema(run.Period());
  ObserverList recorded;
  recorded.Add(steady);
  recorded.Add(extrema);

  const bool reached = run.RunTo(state, first_classified, nullptr) &&
                       run.RunTo(state, transient, &steady) && run.RunTo(state, end, &recorded);
  point->termination = run.Status();
  point->events = run.Events();
  const double t_record = static_cast<double>(transient) * run.Period();
  for (const ImpactView i : steady.Impacts()) {
    if (i.t >= t_record) point->impacts.push_back(SweepImpact{i.t, i.phase, i.velocity, i.stop});
  }
  if (!steady.Impacts().empty() && steady.Impacts().back().t >= t_record) {
    point->last_impact = steady.Impacts().back().Owned();
  }
  const std::vector<PeriodExtrema> periods = extrema.CompletePeriods();
  point->range_contact = Ranges(periods, system.stops[0].dof);
  point->range_first = Ranges(periods, 0);
  if (reached) {
    point->classification = ClassifyMotion(system, steady.Strobe(), steady.Impacts(),
                                           steady.ChatterEnds(), options.classify);
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
    have_state = RunValue(plan.systems[k], options, state, &point);
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
