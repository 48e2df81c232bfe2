#include "impactkit/analysis/sticking_seed.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "dynamics/subsystem.hpp"

namespace impactkit {
namespace {

/// The section state (x, v without the contact DOF, t) at every release.
class ReleaseRecorder : public Observer {
 public:
  explicit ReleaseRecorder(int contact_dof) : contact_dof_(contact_dof) {}

  void OnSegment(const Segment& segment) override {
    if (!segment.Stuck()) return;
    segment.StateAt(segment.End(), &x_, &v_);
    stuck_end_ = segment.End();
  }
  void OnRelease(const Release& release) override {
    // Released where it stuck: no stuck segment.
    if (release.t_release != stuck_end_) return;
    Eigen::VectorXd s(2 * x_.size() - 1);
    s << WithoutIndex(x_, contact_dof_), WithoutIndex(v_, contact_dof_), release.t_release;
    releases_.push_back(s);
  }
  const std::vector<Eigen::VectorXd>& Releases() const { return releases_; }

 private:
  int contact_dof_;
  Eigen::VectorXd x_, v_;
  double stuck_end_ = -1.0;
  std::vector<Eigen::VectorXd> releases_;
};

}  // namespace

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
  ReleaseRecorder recorder(system.stops[0].dof);
  simulator.Run(state, (transient + 2 * max_q + 1) * period, recorder);
  const std::vector<Eigen::VectorXd>& releases = recorder.Releases();
  if (releases.empty()) return std::nullopt;
  // A motion that sticks: its orbit is the release map's, written for one
  // stop (orbits/sticking_map.hpp).
  system.SoleStop("the sticking orbit of a motion that sticks (the release map)");
  const Eigen::VectorXd& last = releases.back();
  const Eigen::Index t = last.size() - 1;
  // Largest |entry| of the state part (none for N = 1: the section is t).
  auto largest = [t](const Eigen::VectorXd& v) {
    return t > 0 ? v.head(t).cwiseAbs().maxCoeff() : 0.0;
  };
  const double scale = 1.0 + largest(last);
  for (std::size_t k = 1; k < releases.size(); ++k) {
    const Eigen::VectorXd& earlier = releases[releases.size() - 1 - k];
    const double periods = (last(t) - earlier(t)) / period;
    const long q = std::lround(periods);
    if (q < 1 || q > max_q || std::abs(periods - q) > 1e-6) continue;
    if (largest(last - earlier) > 1e-6 * scale) continue;
    return StickingSeed{static_cast<int>(k), static_cast<int>(q), last};
  }
  return std::nullopt;
}

}  // namespace impactkit
