#include "impactkit/analysis/sticking_seed.hpp"

#include <fmt/format.h>

#include <cmath>

#include "dynamics/subsystem.hpp"

namespace impactkit {

void ReleaseRecorder::OnSegment(const Segment& segment) {
  if (!segment.Stuck()) return;
  segment.StateAt(segment.End(), &x_, &v_);
  stuck_end_ = segment.End();
}

void ReleaseRecorder::OnRelease(const Release& release) {
  // Released where it stuck: no stuck segment.
  if (release.t_release != stuck_end_) return;
  const int dof = system_.stops[release.stop].dof;
  Eigen::VectorXd s(2 * x_.size() - 1);
  s << WithoutIndex(x_, dof), WithoutIndex(v_, dof), release.t_release;
  releases_.push_back({release.stop, s});
}

std::optional<StickingSeed> ReleaseRecorder::Seed(double period, int max_q) const {
  if (releases_.empty()) return std::nullopt;
  // The release map goes from a release to the next from any stop; its
  // section is the last release's stop, and the repetition a release from
  // that stop k releases earlier.
  const int stop = releases_.back().stop;
  const Eigen::VectorXd& last = releases_.back().state;
  const Eigen::Index t = last.size() - 1;
  // Largest |entry| of the state part (none for N = 1: the section is t).
  auto largest = [t](const Eigen::VectorXd& v) {
    return t > 0 ? v.head(t).cwiseAbs().maxCoeff() : 0.0;
  };
  const double scale = 1.0 + largest(last);
  for (std::size_t k = 1; k < releases_.size(); ++k) {
    const auto& [from, earlier] = releases_[releases_.size() - 1 - k];
    if (from != stop) continue;
    const double periods = (last(t) - earlier(t)) / period;
    const long q = std::lround(periods);
    if (q < 1 || q > max_q || std::abs(periods - q) > 1e-6) continue;
    if (largest(last - earlier) > 1e-6 * scale) continue;
    return StickingSeed{stop, static_cast<int>(k), static_cast<int>(q), last};
  }
  return std::nullopt;
}

std::optional<StickingSeed> SeedStickingFromSimulation(const System& system, int transient,
                                                       int max_q,
                                                       const SimulationOptions& options) {
  if (transient < 0 || max_q < 1) {
    throw InvalidInput(
        fmt::format("transient must be >= 0 and max_q >= 1, got {} and {}", transient, max_q));
  }
  const Simulator simulator(system, options);
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  simulator.Run(state, transient * period);
  ReleaseRecorder recorder(system);
  simulator.Run(state, (transient + 2 * max_q + 1) * period, recorder);
  return recorder.Seed(period, max_q);
}

OrbitOptions OrbitOptionsFor(const StickingSeed& seed) {
  OrbitOptions options;
  options.release_map.stop = seed.stop;
  options.releases = seed.releases;
  options.q = seed.q;
  return options;
}

}  // namespace impactkit
