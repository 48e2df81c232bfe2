#include "impactkit/analysis/swept_diagram.hpp"

#include <fmt/format.h>

#include "impactkit/core/errors.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {
namespace {

bool SamePeriodicMotion(const SweepPoint& a, const SweepPoint& b) {
  return b.classification.kind == MotionKind::kPeriodic &&
         a.classification.kind == MotionKind::kPeriodic &&
         a.classification.period.p == b.classification.period.p &&
         a.classification.period.q == b.classification.period.q;
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
    while (to < points.size() && SamePeriodicMotion(points[from], points[to])) ++to;
    const SweepPoint& middle = points[(from + to - 1) / 2];
    const MotionPeriod& period = points[from].classification.period;
    const bool window = points[from].classification.kind == MotionKind::kPeriodic &&
                        static_cast<int>(to - from) >= options.min_values && period.p >= 1 &&
                        period.p <= options.max_p && middle.last_impact;
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
  swept.from = diagram.continuation.lower;
  swept.to = diagram.continuation.upper;
  return diagram.IsValid(error) && seeds.IsValid(error) && swept.IsValid(error);
}

SweptDiagram TraceSweptDiagram(const System& system, const std::vector<DiagramSeed>& seeds,
                               const SweptDiagramOptions& options,
                               const SweptDiagramProgress& progress) {
  std::string error;
  Require(options.IsValid(&error), error);
  SweepOptions sweep = options.sweep;
  sweep.parameter = options.diagram.continuation.parameter;
  sweep.from = options.diagram.continuation.lower;
  sweep.to = options.diagram.continuation.upper;
  SweptDiagram result;
  result.sweep = RunSweep(system, sweep, [&](int done, int total) {
    if (progress) progress("sweep", done, total);
  });
  result.seeds = seeds;
  for (DiagramSeed& seed : SeedsFromSweep(system, sweep, result.sweep, options.seeds)) {
    result.seeds.push_back(std::move(seed));
  }
  Require(!result.seeds.empty(),
          fmt::format("no seed for the diagram: the sweep of {} over [{}, {}] shows no periodic "
                      "window and none was given",
                      sweep.parameter, sweep.from, sweep.to));
  result.diagram =
      TraceDiagram(result.seeds, options.diagram, [&](int branches, const BranchPoint&) {
        if (progress) progress("diagram", branches, 0);
      });
  return result;
}

}  // namespace impactkit
