#include "impactkit/analysis/swept_diagram.hpp"

#include <fmt/format.h>

#include <optional>

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
  return diagram.IsValid(error) && seeds.IsValid(error) && swept.IsValid(error);
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
