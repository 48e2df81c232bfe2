#pragma once
/// \file section_curve.hpp (private)
/// The curve of one family of periodic orbits in a named parameter μ: k
/// events of a section map (orbits/section_map.hpp) in q forcing periods,
///
///     U(x, μ) = P^k(x; μ) − x − q T(μ) e_t = 0,
///
/// as a function of X = (x, μ), with what pseudo-arclength continuation
/// needs of it: the map at μ, U and [U_x U_μ], the bordered corrector and
/// the tangent. Impacting families (the impact map, branch_problem.hpp)
/// and sticking families (the release map, sticking_branch.cpp) are this
/// curve on their maps.

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/section_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit::detail {

class SectionCurve {
 public:
  /// Makes the family's section map of a system (throws InvalidInput for
  /// one it cannot handle).
  using MapMaker = std::function<std::unique_ptr<SectionMap>(const System&)>;

  /// `state_size`: the size of the map's section coordinates. Throws
  /// InvalidInput for a parameter the system lacks.
  SectionCurve(const System& base, std::string parameter, int k, int q, int state_size,
               MapMaker make_map);

  int Size() const { return size_; }  ///< the section's size + 1
  int Events() const { return k_; }
  int q() const { return q_; }
  const std::string& Parameter() const { return parameter_.Name(); }

  static Eigen::VectorXd Join(const Eigen::VectorXd& state, double mu);
  static double Mu(const Eigen::VectorXd& x) { return x(x.size() - 1); }
  static Eigen::VectorXd State(const Eigen::VectorXd& x) { return x.head(x.size() - 1); }

  /// The system at μ; throws InvalidInput if μ is not a valid value.
  System SystemAt(double mu) const;
  /// The map at μ, or null if μ is not valid for the system. Cached for the
  /// last few μ, so that the three maps of one Jacobian (μ, μ ± h) stay
  /// valid together (not thread-safe).
  const SectionMap* MapAt(double mu) const;

  /// U(X); false where the map fails.
  bool Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const;
  /// D P^k at X (the map's Jacobian, U_x + I); false where the map fails.
  bool MapJacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* dp) const;
  /// [U_x U_μ]; false where the map fails here or on both sides of μ.
  /// U_μ is the map's SectionMap::ParameterRate between μ ± h (one-sided
  /// where the map fails on one side: at the edge of the parameter's range,
  /// or the family's end) less q dT/dμ.
  bool Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const;
  /// Solves U(X) = 0 with the constraint c · X = value from `guess`. Empty
  /// if Newton does not converge; *iterations gets its count.
  std::optional<Eigen::VectorXd> Correct(const Eigen::VectorXd& guess, const Eigen::VectorXd& c,
                                         double value, const NewtonOptions& newton,
                                         int* iterations) const;
  /// The unit tangent of the curve at X (ArclengthTangent): continuing
  /// `previous`, or from the SVD when `previous` is empty (sign
  /// arbitrary). Empty if the Jacobian fails.
  std::optional<Eigen::VectorXd> Tangent(const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& previous) const;
  /// Whether a map failed since the last call (at a trial point of the
  /// corrector, say) because the release map's chatter stopped ending in
  /// sticking (SectionImage::stops_sticking); and forget it.
  bool TakeStoppedSticking() const { return std::exchange(stopped_sticking_, false); }

 private:
  System base_;
  NamedParameter parameter_;
  int k_, q_, size_;
  MapMaker make_map_;
  mutable std::vector<std::pair<double, std::unique_ptr<SectionMap>>> maps_;  // newest last
  mutable Eigen::VectorXd cached_x_;  ///< where the two below were computed
  mutable Eigen::VectorXd cached_residual_;
  /// P^k there with its Jacobian and steps (ParameterRate reuses them).
  mutable SectionImage cached_image_;
  mutable bool stopped_sticking_ = false;
};

}  // namespace impactkit::detail
