#pragma once
/// \file branch_problem.hpp (private)
/// The curve U(η, μ) = P^k(η; μ) - η - q T(μ) e_t = 0 of one family of
/// periodic orbits, impacting P(p, q) on the impact map or sticking on the
/// release map, as a function of X = (η, μ): the map's SectionCurve
/// (section_curve.hpp), for pseudo-arclength continuation (continuation.hpp).

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "continuation/section_curve.hpp"
#include "impactkit/continuation/branch_point.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit::detail {

/// A family's SectionCurve (the impact map's or the release map's) with
/// what a family of orbits adds: its points' orbits and test functions, and
/// whether it could be a shorter orbit traversed several times.
class BranchProblem {
 public:
  /// Impacting orbits P(p, q). Throws InvalidInput for a parameter the
  /// system lacks.
  BranchProblem(const System& base, std::string parameter, int p, int q,
                const ImpactMapOptions& map_options);
  /// Sticking orbits with `releases` sticking phases in q periods.
  BranchProblem(const System& base, std::string parameter, int releases, int q,
                const StickingMapOptions& map_options);

  OrbitSection Section() const { return section_; }
  int Size() const { return curve_.Size(); }  ///< the section's size + 1
  /// The section map's iterations per orbit: p impacts, or the releases.
  int Events() const { return curve_.Events(); }
  int q() const { return curve_.q(); }
  const std::string& Parameter() const { return curve_.Parameter(); }

  System SystemAt(double mu) const { return curve_.SystemAt(mu); }
  /// The section map at μ, or null if μ is not valid for the system
  /// (SectionCurve::MapAt).
  const SectionMap* MapAt(double mu) const { return curve_.MapAt(mu); }
  /// The impact map at μ: null also for a family of sticking orbits.
  const ImpactMap* ImpactMapAt(double mu) const {
    return section_ == OrbitSection::kImpact ? static_cast<const ImpactMap*>(MapAt(mu)) : nullptr;
  }
  /// The orbit through the fixed point `state` of the map at μ (its
  /// section's DescribeOrbit). Throws InvalidInput where the map fails.
  PeriodicOrbit OrbitAt(const Eigen::VectorXd& state, double mu) const;

  static Eigen::VectorXd Join(const Eigen::VectorXd& eta, double mu) {
    return SectionCurve::Join(eta, mu);
  }
  static double Mu(const Eigen::VectorXd& x) { return SectionCurve::Mu(x); }
  /// X = (η, μ) of a point of a branch.
  static Eigen::VectorXd PointX(const BranchPoint& point) {
    return Join(point.orbit.eta, point.parameter);
  }
  static Eigen::VectorXd Eta(const Eigen::VectorXd& x) { return SectionCurve::State(x); }

  bool Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const {
    return curve_.Residual(x, u);
  }
  bool MapJacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* dp) const {
    return curve_.MapJacobian(x, dp);
  }
  bool Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const {
    return curve_.Jacobian(x, jacobian);
  }
  std::optional<Eigen::VectorXd> Correct(const Eigen::VectorXd& guess, const Eigen::VectorXd& c,
                                         double value, const NewtonOptions& newton,
                                         int* iterations) const {
    return curve_.Correct(guess, c, value, newton, iterations);
  }
  std::optional<Eigen::VectorXd> Tangent(const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& previous) const {
    return curve_.Tangent(x, previous);
  }

  /// The branch point at X (a converged point): orbit, test functions and
  /// tangent (oriented along `previous`). Empty if the map fails there.
  std::optional<BranchPoint> Describe(const Eigen::VectorXd& x,
                                      const Eigen::VectorXd& previous) const;

  /// The repeat gap (BranchPoint::repeat_gap) of the state at X, on the
  /// branch or off it; empty where the map fails there or the family has no
  /// repeat divisor.
  std::optional<Eigen::VectorXd> RepeatGap(const Eigen::VectorXd& x) const;
  /// Whether, from X with repeat gap `gap`, the family's orbits head for
  /// the shorter orbit repeated along `direction`: g shrinks along it
  /// (g · Dg d < 0, Dg d by a forward difference over kGapDifference).
  /// Empty where the map fails at the difference's point.
  std::optional<bool> ApproachesRepeat(const Eigen::VectorXd& x, const Eigen::VectorXd& gap,
                                       const Eigen::VectorXd& direction) const;

  /// Whether a map failed since the last call because the release map's
  /// chatter stopped ending in sticking (SectionCurve::TakeStoppedSticking).
  bool TakeStoppedSticking() const { return curve_.TakeStoppedSticking(); }

  /// The smallest prime dividing both k and q (the orbit could be a shorter
  /// one traversed that many times), or 1 when they are coprime.
  int RepeatDivisor() const { return repeat_divisor_; }

 private:
  BranchProblem(OrbitSection section, SectionCurve curve);

  /// The arclength of ApproachesRepeat's difference: short enough that g
  /// is linear over it (steps are 1e-7 to 0.02 long), long enough that g's
  /// change over it (~1e-6, g' being of order 1) stands far above g's
  /// rounding (1e-13 to 1e-11 on long orbits).
  static constexpr double kGapDifference = 1e-6;

  OrbitSection section_;
  SectionCurve curve_;
  int repeat_divisor_ = 1;
};

/// The problem of a family of orbits on `section` at stop `stop` with k
/// events of its map in q periods, the map's options from `options`.
BranchProblem FamilyProblem(const System& system, const ContinuationOptions& options,
                            OrbitSection section, int stop, int k, int q);

}  // namespace impactkit::detail
