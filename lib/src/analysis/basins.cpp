#include "impactkit/analysis/basins.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <tuple>

#include "impactkit/core/errors.hpp"

namespace impactkit {
namespace {

/// Values of one axis by the sweep's rule (both ends exact, ascending).
std::vector<double> AxisValues(double from, double to, int steps) {
  SweepOptions axis;
  axis.from = from;
  axis.to = to;
  axis.steps = steps;
  return SweepValues(axis);
}

double& Coordinate(HybridState& state, int coordinate) {
  const int n = static_cast<int>(state.x.size());
  return coordinate < n ? state.x(coordinate) : state.v(coordinate - n);
}

/// The impacts of the last q recorded periods of a motion with an orbit.
std::vector<AttractorImpact> OrbitOf(const SweepPoint& point, const GridCell& cell,
                                     const SweepOptions& run, double period) {
  std::vector<AttractorImpact> orbit;
  const bool has_orbit = cell.kind == MotionKind::kPeriodic || cell.kind == MotionKind::kSticking;
  if (!has_orbit || cell.q < 1) return orbit;
  const double t_from =
      static_cast<double>(run.transient_periods + run.recorded_periods - cell.q) * period;
  for (const SweepImpact& i : point.impacts) {
    if (i.t >= t_from) orbit.push_back({i.phase, i.velocity});
  }
  return orbit;
}

bool Near(const AttractorImpact& a, const AttractorImpact& b, double period, double tolerance) {
  const double d = std::abs(a.phase - b.phase);
  const double phase = std::min(d, period - d);  // phases wrap at T
  return phase <= tolerance * period &&
         std::abs(a.velocity - b.velocity) <= tolerance * std::max(1.0, std::abs(a.velocity));
}

/// Every impact of `a` near one of `b`.
bool Covers(const std::vector<AttractorImpact>& a, const std::vector<AttractorImpact>& b,
            double period, double tolerance) {
  return std::all_of(a.begin(), a.end(), [&](const AttractorImpact& i) {
    return std::any_of(b.begin(), b.end(),
                       [&](const AttractorImpact& j) { return Near(i, j, period, tolerance); });
  });
}

bool SameAttractor(const Attractor& a, const GridCell& cell, double period, double tolerance) {
  if (a.kind != cell.kind || a.p != cell.p || a.q != cell.q) return false;
  return Covers(a.orbit, cell.orbit, period, tolerance) &&
         Covers(cell.orbit, a.orbit, period, tolerance);
}

}  // namespace

int StateCoordinate(const System& system, const std::string& name) {
  const int n = system.Dof();
  if (name.size() >= 2 && (name[0] == 'x' || name[0] == 'v')) {
    int i = 0;
    const char* end = name.data() + name.size();
    const auto [last, error] = std::from_chars(name.data() + 1, end, i);
    if (error == std::errc() && last == end && i >= 1 && i <= n) {
      return (name[0] == 'x' ? 0 : n) + i - 1;
    }
  }
  throw InvalidInput(
      fmt::format("unknown state coordinate '{}'; allowed: x1..x{}, v1..v{}", name, n, n));
}

bool BasinsOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (coordinate1 == coordinate2) {
    return fail(
        fmt::format("the two coordinates are both '{}': a basin picture needs two", coordinate1));
  }
  for (const auto& [name, from, to, steps] :
       {std::tuple{coordinate1, from1, to1, steps1}, std::tuple{coordinate2, from2, to2, steps2}}) {
    if (steps < 1) return fail(fmt::format("steps of {} must be >= 1, got {}", name, steps));
    if (!std::isfinite(from) || !std::isfinite(to)) {
      return fail(fmt::format("the range of {} must be finite, got {} and {}", name, from, to));
    }
    if (steps > 1 && from == to) {
      return fail(fmt::format("the range of {} is {} to {}: {} steps need a range (or 1 step)",
                              name, from, to, steps));
    }
  }
  if (!(orbit_tolerance > 0.0 && orbit_tolerance < 1.0)) {
    return fail(fmt::format("orbit tolerance must be in (0, 1), got {}", orbit_tolerance));
  }
  return run.IsValid(error);
}

BasinsTask::BasinsTask(const System& system, BasinsOptions options)
    : system_(system), options_(std::move(options)) {
  std::string error;
  Require(options_.IsValid(&error), error);
  ValidateParameters(system_);
  StateCoordinate(system_, options_.coordinate1);
  StateCoordinate(system_, options_.coordinate2);
  values1_ = AxisValues(options_.from1, options_.to1, options_.steps1);
  values2_ = AxisValues(options_.from2, options_.to2, options_.steps2);
  for (std::int64_t cell = 0; cell < Cells(); ++cell) {
    try {
      ValidateState(system_, StartOf(cell));
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("basins start {} = {}, {} = {}: {}", options_.coordinate1,
                                     values1_[cell % values1_.size()], options_.coordinate2,
                                     values2_[cell / values1_.size()], e.what()));
    }
  }
}

std::int64_t BasinsTask::Cells() const {
  return static_cast<std::int64_t>(values1_.size()) * static_cast<std::int64_t>(values2_.size());
}

HybridState BasinsTask::StartOf(std::int64_t cell) const {
  HybridState state = options_.base ? *options_.base : RestState(system_);
  state.t = 0.0;
  const std::int64_t k = static_cast<std::int64_t>(values1_.size());
  Coordinate(state, StateCoordinate(system_, options_.coordinate1)) = values1_[cell % k];
  Coordinate(state, StateCoordinate(system_, options_.coordinate2)) = values2_[cell / k];
  return state;
}

std::vector<GridCell> BasinsTask::RunUnit(int unit) const {
  // Each start is a sweep of one value from a fixed state: the same run,
  // window and classification as any sweep value.
  SweepOptions run = options_.run;
  run.parameter = "omega";
  run.from = run.to = system_.omega;
  run.steps = 1;
  run.start = SweepStart::kFixed;
  run.threads = 1;
  const double period = system_.ForcingPeriod();
  std::vector<GridCell> cells;
  const std::int64_t k = static_cast<std::int64_t>(values1_.size());
  for (std::int64_t cell = unit * k; cell < (unit + 1) * k; ++cell) {
    run.fixed_state = StartOf(cell);
    const SweepPoint point = RunSweep(system_, run).points.front();
    cells.push_back(CellOf(cell, point));
    cells.back().orbit = OrbitOf(point, cells.back(), run, period);
  }
  return cells;
}

std::string BasinsTask::Identity() const {
  const BasinsOptions& o = options_;
  std::string text = fmt::format(
      "basins {} transient={} record={} max_q={} {}={}..{}/{} {}={}..{}/{} tolerance={}",
      SystemIdentity(system_), o.run.transient_periods, o.run.recorded_periods,
      o.run.classify.period.max_q, o.coordinate1, o.from1, o.to1, o.steps1, o.coordinate2, o.from2,
      o.to2, o.steps2, o.orbit_tolerance);
  if (o.base) {
    text +=
        fmt::format(" base_x={} base_v={}", fmt::join(o.base->x, ","), fmt::join(o.base->v, ","));
  }
  if (o.run.full_transient) text += " full_transient";
  return text;
}

BasinsResult IdentifyAttractors(const std::vector<GridCell>& cells, double period,
                                double orbit_tolerance) {
  BasinsResult result;
  result.attractor.reserve(cells.size());
  for (const GridCell& cell : cells) {
    auto found = std::find_if(
        result.attractors.begin(), result.attractors.end(),
        [&](const Attractor& a) { return SameAttractor(a, cell, period, orbit_tolerance); });
    if (found == result.attractors.end()) {
      result.attractors.push_back({cell.kind, cell.p, cell.q, cell.orbit, cell.index, 0});
      found = std::prev(result.attractors.end());
    }
    ++found->cells;
    result.attractor.push_back(static_cast<int>(found - result.attractors.begin()));
  }
  return result;
}

}  // namespace impactkit
