#pragma once
/// \file branch_problem.hpp (private)
/// The curve U(η, μ) = P_I^p(η; μ) - η - q T(μ) e_τ = 0 of one P(p, q)
/// family, as a function of X = (η, μ), with the bordered corrector and the
/// tangent that pseudo-arclength continuation needs (continuation.hpp).

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "impactkit/continuation/branch_point.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit::detail {

class BranchProblem {
 public:
  /// Throws InvalidInput for a parameter the system lacks.
  BranchProblem(const System& base, std::string parameter, int p, int q,
                const ImpactMapOptions& map_options);

  int Size() const { return size_; }  ///< 2N + 1
  int p() const { return p_; }
  int q() const { return q_; }
  const std::string& Parameter() const { return parameter_; }

  /// The system at μ; throws InvalidInput if μ is not a valid value.
  System SystemAt(double mu) const;
  /// The impact map at μ, or null if μ is not valid for the system. Cached
  /// for the last few μ (not thread-safe).
  const ImpactMap* MapAt(double mu) const;

  static Eigen::VectorXd Join(const Eigen::VectorXd& eta, double mu);
  static double Mu(const Eigen::VectorXd& x) { return x(x.size() - 1); }
  static Eigen::VectorXd Eta(const Eigen::VectorXd& x) { return x.head(x.size() - 1); }

  /// U(X) (size 2N); false where the map fails.
  bool Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const;
  /// D P^p at X (the map's Jacobian, U_η + I); false where the map fails.
  bool MapJacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* dp) const;
  /// [U_η U_μ] (2N x (2N + 1)); false where the map fails on every side.
  bool Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const;

  /// Solves U(X) = 0 with the constraint c · X = value from `guess`.
  /// Empty if Newton does not converge; *iterations gets its count.
  std::optional<Eigen::VectorXd> Correct(const Eigen::VectorXd& guess, const Eigen::VectorXd& c,
                                         double value, const NewtonOptions& newton,
                                         int* iterations) const;

  /// The unit null vector of [U_η U_μ] at X: oriented so that its dot
  /// product with `previous` is positive, or from the SVD when `previous`
  /// is empty (sign arbitrary). Empty if the Jacobian fails.
  std::optional<Eigen::VectorXd> Tangent(const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& previous) const;

  /// The branch point at X (a converged point): orbit, test functions and
  /// tangent (oriented along `previous`). Empty if the map fails there.
  std::optional<BranchPoint> Describe(const Eigen::VectorXd& x,
                                      const Eigen::VectorXd& previous) const;

  /// The smallest prime dividing both p and q (the orbit could be a shorter
  /// one traversed that many times), or 1 when they are coprime.
  int RepeatDivisor() const { return repeat_divisor_; }

 private:
  std::optional<MapResult> Image(const Eigen::VectorXd& x, bool with_jacobian) const;

  System base_;
  std::string parameter_;
  int p_, q_, size_;
  int repeat_divisor_ = 1;
  ImpactMapOptions map_options_;
  mutable std::vector<std::pair<double, std::unique_ptr<ImpactMap>>> maps_;  // newest last
  mutable Eigen::VectorXd cached_x_;  ///< where the two below were computed
  mutable Eigen::VectorXd cached_residual_;
  mutable Eigen::MatrixXd cached_map_jacobian_;
};

}  // namespace impactkit::detail
