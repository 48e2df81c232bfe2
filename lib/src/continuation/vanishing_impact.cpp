#include "continuation/vanishing_impact.hpp"

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace impactkit::detail {
namespace {

/// The secant iterations allowed.
constexpr int kMaxIterations = 60;
/// Converged when |clearance| is below this (lengths) ...
constexpr double kClearanceTolerance = 1e-13;
/// ... or the step in μ below this, relative to max(1, |μ|).
constexpr double kStepTolerance = 1e-14;

/// The reduced orbit's clearance at μ, seeded from the orbits found before
/// (linearly extrapolated in μ from the last two); empty where no
/// P(p − 1, q) orbit with a flight maximum is found. The extrapolation
/// matters: a long reduced orbit's multipliers reach 1e4 near the grazing,
/// and from the last orbit alone a step of 1e-6 in μ already leaves the
/// seed outside the map's reach (P(15,6) of the clearance example).
class ReducedOrbitClearance {
 public:
  ReducedOrbitClearance(const BranchProblem& problem, const OrbitOptions& options,
                        Eigen::VectorXd seed)
      : problem_(problem), options_(options), seed_(std::move(seed)) {}

  std::optional<double> operator()(double mu) {
    if (options_.p == 0) return NonImpactingClearance(problem_.SystemAt(mu));
    System system;
    try {
      system = problem_.SystemAt(mu);
    } catch (const InvalidInput&) {
      return std::nullopt;  // μ outside the parameter's range
    }
    // The extrapolated seed first, then the last orbit's (where the
    // impact phase τ wrapped round between the two).
    for (const Eigen::VectorXd& seed : Seeds(mu)) {
      PeriodicOrbit orbit;
      if (FindOrbit(system, seed, options_, &orbit).termination == Termination::kConverged &&
          orbit.contacts.clearance) {
        before_ = std::exchange(last_, Found{mu, orbit.eta});
        return *orbit.contacts.clearance;
      }
    }
    return std::nullopt;
  }

 private:
  struct Found {
    double mu;
    Eigen::VectorXd eta;
  };

  std::vector<Eigen::VectorXd> Seeds(double mu) const {
    if (!last_) return {seed_};
    if (!before_ || before_->mu == last_->mu) return {last_->eta};
    const double ratio = (mu - last_->mu) / (last_->mu - before_->mu);
    return {last_->eta + ratio * (last_->eta - before_->eta), last_->eta};
  }

  const BranchProblem& problem_;
  OrbitOptions options_;
  Eigen::VectorXd seed_;  ///< until an orbit is found
  std::optional<Found> last_, before_;
};

}  // namespace

namespace {

/// X = (K − Ω²M + iΩC)⁻¹ A, the non-impacting response's complex amplitude.
Eigen::VectorXcd ResponseAmplitude(const System& s) {
  using Complex = std::complex<double>;
  const double w = s.omega;
  const Eigen::MatrixXcd dynamic = s.stiffness.cast<Complex>() - w * w * s.mass.cast<Complex>() +
                                   Complex(0.0, w) * s.damping.cast<Complex>();
  return dynamic.partialPivLu().solve(s.forcing.cast<Complex>());
}

/// A stop's distance from its mass's rest position, less the amplitude.
double StopClearance(const StopParameters& stop, const Eigen::VectorXcd& x) {
  return stop.Sign() * stop.position - std::abs(x(stop.dof));
}

}  // namespace

double NonImpactingClearance(const System& s) {
  return NonImpactingClearance(s, NonImpactingTouchStop(s));
}

double NonImpactingClearance(const System& s, int stop) {
  return StopClearance(s.stops.at(static_cast<std::size_t>(stop)), ResponseAmplitude(s));
}

int NonImpactingTouchStop(const System& s) {
  const Eigen::VectorXcd x = ResponseAmplitude(s);
  int least = 0;
  for (int k = 1; k < s.StopCount(); ++k) {
    if (StopClearance(s.stops[k], x) < StopClearance(s.stops[least], x)) least = k;
  }
  return least;
}

std::optional<VanishingImpactPoint> LocateVanishingImpact(const BranchProblem& problem,
                                                          const BranchPoint& a,
                                                          const BranchPoint& b, int impact,
                                                          const OrbitOptions& orbit_options) {
  if (b.parameter == a.parameter) return std::nullopt;
  const double direction = b.parameter > a.parameter ? 1.0 : -1.0;
  const ImpactMap* map = problem.ImpactMapAt(b.parameter);
  if (!map) return std::nullopt;
  const MapResult path = map->Apply(b.orbit.eta, problem.Events(), false);
  if (path.termination != Termination::kCompleted) return std::nullopt;

  OrbitOptions reduced = orbit_options;
  reduced.p = problem.Events() - 1;
  reduced.q = problem.q();
  reduced.map.stop = path.stops[static_cast<std::size_t>(impact)];
  // The impact after the vanishing one starts the reduced orbit: its state
  // barely changes as v_k → 0 (the vanishing impact changes v_c by (1 + r) v_k).
  const Eigen::VectorXd seed = path.path[static_cast<std::size_t>(impact)];
  ReducedOrbitClearance clearance(problem, reduced, seed);

  // A first point where the reduced orbit exists (clearance > 0): b itself,
  // or the nearest found stepping out to either side. Which side the
  // reduced orbit lives on depends on the grazing (Nordmark's normal form).
  const double scale = std::max(1.0, std::abs(b.parameter));
  double mu1 = b.parameter;
  std::optional<double> c1 = clearance(mu1);
  for (double step = 1e-9 * scale; !(c1 && *c1 > 0) && step < 1e-2 * scale; step *= 4.0) {
    for (double side : {direction, -direction}) {
      mu1 = b.parameter + side * step;
      c1 = clearance(mu1);
      if (c1 && *c1 > 0) break;
    }
  }
  if (!(c1 && *c1 > 0)) return std::nullopt;
  // A second point, a small step away on whichever side the orbit continues.
  double mu0 = mu1;
  std::optional<double> c0;
  for (double side : {1.0, -1.0}) {
    mu0 = mu1 + side * 1e-7 * scale;
    c0 = clearance(mu0);
    if (c0 && *c0 != *c1) break;
  }
  if (!c0 || *c0 == *c1) return std::nullopt;

  // Secant towards the zero; a step that lands where the reduced orbit does
  // not exist (or jumps) is halved back towards the last good point.
  for (int k = 0; k < kMaxIterations; ++k) {
    if (std::abs(*c1) <= kClearanceTolerance) break;
    double delta = -*c1 * (mu1 - mu0) / (*c1 - *c0);
    if (std::abs(delta) <= kStepTolerance * scale) {
      mu1 += delta;  // the zero, extrapolated from the last two values
      c1 = 0.0;
      break;
    }
    std::optional<double> c;
    for (int halving = 0; halving < 30; ++halving, delta /= 2.0) {
      c = clearance(mu1 + delta);
      if (c && std::abs(*c) < std::abs(*c1) * 2.0) break;
      c.reset();
    }
    if (!c) return std::nullopt;
    mu0 = mu1;
    c0 = c1;
    mu1 += delta;
    c1 = c;
  }
  if (!(std::abs(*c1) <= 1e3 * kClearanceTolerance)) return std::nullopt;
  return VanishingImpactPoint{mu1, *c1};
}

}  // namespace impactkit::detail
