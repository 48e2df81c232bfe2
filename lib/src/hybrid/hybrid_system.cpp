#include "impactkit/hybrid/hybrid_system.hpp"

#include <bit>
#include <cmath>

#include "core/symmetric_eigen.hpp"
#include "dynamics/subsystem.hpp"

namespace impactkit {

HybridSystem::HybridSystem(const System& system) : system_(system) {
  // Validate() would decompose the flows only to check them; they are
  // decomposed here once, and their constructors reject the resonances.
  ValidateParameters(system_);
  for (int k = 0; k < system_.StopCount(); ++k) stops_.emplace_back(system_, k);
  free_ = std::make_unique<const Mode>(system_, stops_, 0);
  held_ = std::make_unique<LazyMode[]>(stops_.size());
  inverse_mass_ = detail::SymmetricInverse(system_.mass);
  time_scale_ = free_->Flow().ShortestPeriod();
}

const Mode& HybridSystem::Holding(StopSet held) const {
  if (held == 0) return *free_;
  // (A held mode may have no coordinates left: N = 1, or every mass held.)
  if (std::has_single_bit(held)) {
    LazyMode& single = held_[std::countr_zero(held)];
    // A throw leaves the flag unset: the next call throws the same.
    std::call_once(single.once,
                   [&] { single.mode = std::make_unique<const Mode>(system_, stops_, held); });
    return *single.mode;
  }
  const std::lock_guard<std::mutex> lock(combined_mutex_);
  std::unique_ptr<const Mode>& mode = combined_[held];
  if (!mode) mode = std::make_unique<const Mode>(system_, stops_, held);
  return *mode;
}

void HybridSystem::PrepareHeldModes() const {
  for (int k = 0; k < StopCount(); ++k) Holding(StopBit(k));
}

Eigen::VectorXd HybridSystem::Acceleration(double t, const Eigen::VectorXd& x,
                                           const Eigen::VectorXd& v) const {
  return inverse_mass_ * (system_.forcing * std::cos(system_.omega * t) - system_.damping * v -
                          system_.stiffness * x);
}

Eigen::VectorXd HybridSystem::VectorField(double t, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& v) const {
  Eigen::VectorXd f(2 * system_.Dof());
  f << v, Acceleration(t, x, v);
  return f;
}

Eigen::VectorXd HybridSystem::Held(int stop, const Eigen::VectorXd& full) const {
  return WithoutIndex(full, stops_[stop].Dof());
}

Eigen::VectorXd HybridSystem::Full(int stop, const Eigen::VectorXd& held, double value) const {
  return EmbedAtStop(held, stops_[stop].Dof(), value);
}

}  // namespace impactkit
