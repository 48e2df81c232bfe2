#pragma once
/// \file branch_problem.hpp (private)
/// The curve U(η, μ) = P_I^p(η; μ) - η - q T(μ) e_τ = 0 of one P(p, q)
/// family, as a function of X = (η, μ): the impact map's SectionCurve
/// (section_curve.hpp), for pseudo-arclength continuation (continuation.hpp).

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "continuation/section_curve.hpp"
#include "impactkit/continuation/branch_point.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit::detail {

/// The impact map's SectionCurve with what an impacting family adds: its
/// points' orbits and test functions, and whether it could be a shorter
/// orbit traversed several times.
class BranchProblem {
 public:
  /// Throws InvalidInput for a parameter the system lacks.
  BranchProblem(const System& base, std::string parameter, int p, int q,
                const ImpactMapOptions& map_options);

  int Size() const { return curve_.Size(); }  ///< 2N + 1
  int p() const { return curve_.Events(); }
  int q() const { return curve_.q(); }
  const std::string& Parameter() const { return curve_.Parameter(); }

  System SystemAt(double mu) const { return curve_.SystemAt(mu); }
  /// The impact map at μ, or null if μ is not valid for the system
  /// (SectionCurve::MapAt).
  const ImpactMap* MapAt(double mu) const {
    return static_cast<const ImpactMap*>(curve_.MapAt(mu));
  }

  static Eigen::VectorXd Join(const Eigen::VectorXd& eta, double mu) {
    return SectionCurve::Join(eta, mu);
  }
  static double Mu(const Eigen::VectorXd& x) { return SectionCurve::Mu(x); }
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

  /// The smallest prime dividing both p and q (the orbit could be a shorter
  /// one traversed that many times), or 1 when they are coprime.
  int RepeatDivisor() const { return repeat_divisor_; }

 private:
  SectionCurve curve_;
  int repeat_divisor_ = 1;
};

}  // namespace impactkit::detail
