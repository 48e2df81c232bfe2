#include "impactkit/analysis/swept_diagram.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <optional>
#include <thread>

#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {
namespace {

/// One window's motion on both: the same P(p, q), or sticking with the
/// same q (the impacts before its chatter ends may change across it).
bool SameMotion(const SweepPoint& a, const SweepPoint& b) {
  const MotionKind kind = a.classification.kind;
  if (kind != b.classification.kind || a.classification.period.q != b.classification.period.q) {
    return false;
  }
  return kind == MotionKind::kSticking ||
         (kind == MotionKind::kPeriodic && a.classification.period.p == b.classification.period.p);
}

/// The sticking orbit of a sticking window at one of its values: seeded by
/// its own simulation (the sweep keeps no release), refined on the release
/// map; none if either fails.
std::optional<PeriodicOrbit> StickingOrbitAt(const System& at, int transient) {
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(at, transient);
  if (!seed) return std::nullopt;
  PeriodicOrbit found;
  if (FindOrbit(at, seed->state, OrbitOptionsFor(*seed), &found).termination !=
      Termination::kConverged) {
    return std::nullopt;
  }
  return found;
}

/// Whether the interval between two neighbouring sweep values is swept
/// again: their motions differ, or either has no period (chaotic,
/// unresolved), where a window narrower than the spacing may lie.
bool Refines(const SweepPoint& a, const SweepPoint& b) {
  auto periodless = [](const SweepPoint& p) {
    return p.classification.kind == MotionKind::kChaotic ||
           p.classification.kind == MotionKind::kUnresolved;
  };
  const Classification &ca = a.classification, &cb = b.classification;
  const bool same = ca.kind == cb.kind && ca.period.p == cb.period.p && ca.period.q == cb.period.q;
  return !same || periodless(a) || periodless(b);
}

/// A stretch of consecutive refined intervals: sweep points first..last.
struct Stretch {
  std::size_t first = 0, last = 0;
};

std::vector<Stretch> RefinedStretches(const std::vector<SweepPoint>& points) {
  std::vector<Stretch> stretches;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    if (!Refines(points[k], points[k + 1])) continue;
    if (!stretches.empty() && stretches.back().last == k) {
      stretches.back().last = k + 1;
    } else {
      stretches.push_back({k, k + 1});
    }
  }
  return stretches;
}

/// The stretch swept at `factor` times the resolution, sequentially in
/// sweep order from `warmup_values` values before it (as many as the range
/// holds); returns its values strictly between the sweep's, in sweep
/// order.
std::vector<SweepPoint> SweepStretch(const System& system, const SweepOptions& sweep,
                                     const std::vector<SweepPoint>& points, Stretch stretch,
                                     const SweepRefineOptions& options, const RunControl& control) {
  const double begin = points[stretch.first].value, end = points[stretch.last].value;
  const int intervals = static_cast<int>(stretch.last - stretch.first) * options.factor;
  const double step = (end - begin) / intervals;  // signed: sweep order
  const double lower = std::min(sweep.from, sweep.to), upper = std::max(sweep.from, sweep.to);
  int warmup = 0;
  while (warmup < options.warmup_values) {
    const double before = begin - (warmup + 1) * step;
    if (before < lower || before > upper) break;
    ++warmup;
  }
  SweepOptions fine = sweep;
  fine.from = begin - warmup * step;
  fine.to = end;
  fine.steps = warmup + intervals + 1;
  fine.chunk_values = 0;  // one chunk: each value from the previous one's state
  fine.threads = 1;
  const SweepResult swept = RunSweep(system, fine, control);
  std::vector<SweepPoint> between;
  for (int m = 1; m < intervals; ++m) {
    const std::size_t index = static_cast<std::size_t>(warmup + m);
    if (m % options.factor != 0 && index < swept.points.size()) {
      between.push_back(swept.points[index]);
    }
  }
  return between;
}

}  // namespace

bool SweepSeedOptions::IsValid(std::string* error) const {
  if (min_values < 1 || max_p < 1) {
    if (error) {
      *error = fmt::format("min_values and max_p must be >= 1, got {} and {}", min_values, max_p);
    }
    return false;
  }
  return orbit.IsValid(error);
}

bool SweepRefineOptions::IsValid(std::string* error) const {
  if (factor < 1 || warmup_values < 0) {
    if (error) {
      *error = fmt::format(
          "the refinement's factor must be >= 1 and its warm-up values >= 0, got "
          "{} and {}",
          factor, warmup_values);
    }
    return false;
  }
  return true;
}

std::vector<SweepPoint> RefineSweep(const System& system, const SweepOptions& sweep_options,
                                    const SweepResult& sweep, const SweepRefineOptions& options,
                                    const RunControl& control) {
  std::string error;
  Require(options.IsValid(&error), error);
  const std::vector<SweepPoint>& points = sweep.points;
  const std::vector<Stretch> stretches =
      options.factor > 1 ? RefinedStretches(points) : std::vector<Stretch>{};
  std::vector<std::vector<SweepPoint>> refined(stretches.size());
  std::vector<std::exception_ptr> errors(stretches.size());
  const std::int64_t total = static_cast<std::int64_t>(points.size()) + [&] {
    std::int64_t added = 0;
    for (const Stretch& s : stretches) added += (s.last - s.first) * (options.factor - 1);
    return added;
  }();
  std::atomic<std::size_t> next{0};
  std::atomic<std::int64_t> done{static_cast<std::int64_t>(points.size())};
  // Each stretch is computed the same on whichever thread: the points do
  // not depend on the threads. Their own progress is not reported (the
  // stretches run at once); the refinement's is, stretch by stretch.
  const RunControl quiet(RunControl::ProgressCallback{}, control);
  auto work = [&] {
    for (std::size_t k; (k = next++) < stretches.size() && !control.Cancelled();) {
      try {
        refined[k] = SweepStretch(system, sweep_options, points, stretches[k], options, quiet);
      } catch (...) {
        errors[k] = std::current_exception();  // rethrown after the join
      }
      done += static_cast<std::int64_t>(refined[k].size());
      control.Report({.stage = "sweep", .done = done, .total = total});
    }
  };
  std::vector<std::thread> workers;
  const int threads = std::min<int>(sweep_options.threads, static_cast<int>(stretches.size()));
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();
  for (std::thread& t : workers) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  if (control.Cancelled()) return points;
  std::vector<SweepPoint> merged;
  std::size_t stretch = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    merged.push_back(points[k]);
    if (stretch == stretches.size() || k < stretches[stretch].first) continue;
    // The stretch's values after point k: those of its interval (k, k + 1).
    const std::vector<SweepPoint>& values = refined[stretch];
    const std::size_t per = static_cast<std::size_t>(options.factor - 1);
    const std::size_t from = (k - stretches[stretch].first) * per;
    for (std::size_t m = from; m < std::min(from + per, values.size()); ++m) {
      merged.push_back(values[m]);
    }
    if (k + 1 == stretches[stretch].last) ++stretch;
  }
  return merged;
}

std::vector<DiagramSeed> SeedsFromSweep(const System& system, const SweepOptions& sweep_options,
                                        const SweepResult& sweep, const SweepSeedOptions& options) {
  std::string error;
  Require(options.IsValid(&error), error);
  std::vector<DiagramSeed> seeds;
  const std::vector<SweepPoint>& points = sweep.points;
  std::size_t from = 0;
  while (from < points.size()) {
    std::size_t to = from + 1;
    while (to < points.size() && SameMotion(points[from], points[to])) ++to;
    const SweepPoint& middle = points[(from + to - 1) / 2];
    const MotionPeriod& period = points[from].classification.period;
    const MotionKind kind = points[from].classification.kind;
    const bool wide = static_cast<int>(to - from) >= options.min_values;
    const bool window = kind == MotionKind::kPeriodic && wide && period.p >= 1 &&
                        period.p <= options.max_p && middle.last_impact;
    if (kind == MotionKind::kSticking && wide) {
      System at = system;
      SetParameter(at, sweep_options.parameter, middle.value);
      if (std::optional<PeriodicOrbit> found =
              StickingOrbitAt(at, sweep_options.transient_periods)) {
        seeds.push_back(
            {at, *found,
             fmt::format("sweep window P(inf,{}) {} {:.6g}..{:.6g}", period.q,
                         sweep_options.parameter, points[from].value, points[to - 1].value)});
      }
    }
    if (window) {
      System at = system;
      SetParameter(at, sweep_options.parameter, middle.value);
      const Impact& last = *middle.last_impact;
      OrbitOptions orbit = options.orbit;
      orbit.p = static_cast<int>(period.p);
      orbit.q = period.q;
      PeriodicOrbit found;
      orbit.map.stop = last.stop;
      const Eigen::VectorXd eta = ImpactMap(at, orbit.map).ToEta(last.t, last.x, last.v);
      if (FindOrbit(at, eta, orbit, &found).termination == Termination::kConverged) {
        seeds.push_back(
            {at, found,
             fmt::format("sweep window P({},{}) {} {:.6g}..{:.6g}", period.p, period.q,
                         sweep_options.parameter, points[from].value, points[to - 1].value)});
      }
    }
    from = to;
  }
  return seeds;
}

bool SweptDiagramOptions::IsValid(std::string* error) const {
  SweepOptions swept = sweep;
  swept.parameter = diagram.continuation.parameter;
  swept.from = diagram.continuation.Lower();
  swept.to = diagram.continuation.Upper();
  return diagram.IsValid(error) && refine.IsValid(error) && seeds.IsValid(error) &&
         swept.IsValid(error);
}

SweptDiagram TraceSweptDiagram(const System& system, const std::vector<DiagramSeed>& seeds,
                               const SweptDiagramOptions& options, const RunControl& control) {
  std::string error;
  Require(options.IsValid(&error), error);
  SweepOptions sweep = options.sweep;
  sweep.parameter = options.diagram.continuation.parameter;
  sweep.from = options.diagram.continuation.Lower();
  sweep.to = options.diagram.continuation.Upper();
  SweptDiagram result;
  result.sweep = RunSweep(system, sweep, control);
  if (result.sweep.termination == Termination::kStopped) {
    result.diagram.parameter = sweep.parameter;
    result.diagram.termination = Termination::kStopped;
    result.diagram.message = result.sweep.message;
    return result;
  }
  const std::size_t swept_values = result.sweep.points.size();
  const auto refine_start = std::chrono::steady_clock::now();
  result.sweep.points = RefineSweep(system, sweep, result.sweep, options.refine, control);
  result.sweep.seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - refine_start).count();
  result.refined_values = static_cast<int>(result.sweep.points.size() - swept_values);
  if (control.Cancelled()) {
    result.diagram.parameter = sweep.parameter;
    result.diagram.termination = Termination::kStopped;
    result.diagram.message = Describe(Termination::kStopped);
    return result;
  }
  result.seeds = seeds;
  for (DiagramSeed& seed : SeedsFromSweep(system, sweep, result.sweep, options.seeds)) {
    result.seeds.push_back(std::move(seed));
  }
  Require(!result.seeds.empty(),
          fmt::format("no seed for the diagram: the sweep of {} over [{}, {}] shows no periodic "
                      "window and none was given",
                      sweep.parameter, sweep.from, sweep.to));
  result.diagram = TraceDiagram(result.seeds, options.diagram, control);
  return result;
}

}  // namespace impactkit
