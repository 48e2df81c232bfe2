#pragma once
/// \file curve_problem.hpp (private)
/// The defining system F(X) = 0 of a two-parameter curve (curve.hpp), with
/// its Jacobian, the bordered corrector and the tangent. U's rows come from
/// BranchProblem in each parameter; the defining rows are differenced.

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>

#include "continuation/branch_problem.hpp"
#include "continuation/defining_function.hpp"
#include "impactkit/continuation/curve.hpp"

namespace impactkit::detail {

/// A grazing curve is followed at this clearance, just inside the region
/// where its orbit exists: at clearance 0 within rounding the event search
/// sees a touch (an impact slower than min_speed, or a tiny extra impact)
/// as often as not, and the map fails. It is the tolerance to which a
/// branch locates a grazing (continuation.cpp), and moves the curve by
/// 1e-10 / |∂clearance/∂μ| in μ.
constexpr double kGrazingMargin = 1e-10;

class CurveProblem {
 public:
  /// The orbit's impacts η are at options.orbit.map.stop (its section).
  /// `grazing_flight`, `grazing_stop`: for a grazing curve, the impact
  /// whose flight holds the touch and the stop touched. `response`: a
  /// grazing curve of the non-impacting response instead (where P(1,q)'s
  /// impact vanishes): X = (μ1, μ2) and the one equation s xs − |X_c| = 0
  /// at the stop the response comes closest to at the start. Throws
  /// InvalidInput for a parameter or stop the system lacks.
  CurveProblem(const System& base, const CurveOptions& options, SpecialPointType type,
               int grazing_flight, int grazing_stop, bool response = false);

  /// Unknowns: 2N + 2, 2N + 3 for a grazing by a new contact, 2 for the
  /// response's grazing.
  int Size() const { return size_; }
  bool IsGrazing() const { return type_ == SpecialPointType::kGrazing; }
  /// X holds t* (a grazing of an impacting orbit).
  bool HasContactTime() const { return IsGrazing() && !response_; }

  /// X from its parts (t* ignored unless grazing), and back.
  Eigen::VectorXd Join(const Eigen::VectorXd& eta, double contact_time, double mu1,
                       double mu2) const;
  Eigen::VectorXd Eta(const Eigen::VectorXd& x) const { return x.head(eta_size_); }
  static double Mu1(const Eigen::VectorXd& x) { return x(x.size() - 2); }
  static double Mu2(const Eigen::VectorXd& x) { return x(x.size() - 1); }

  /// Grazing: the stop touched (for the response's grazing, the stop the
  /// response comes closest to at the start).
  int TouchedStop() const { return touched_stop_; }
  /// Grazing: t*, the time of the touch.
  double ContactTime(const Eigen::VectorXd& x) const { return x(eta_size_); }
  /// The system the problem was built on (at the start's parameters) and
  /// its options.
  const System& Base() const { return base_; }
  const CurveOptions& Options() const { return options_; }

  /// The system at (μ1, μ2); throws InvalidInput if not valid.
  System SystemAt(double mu1, double mu2) const;

  /// F(X) (size Size() − 1); false where the map fails or, for grazing,
  /// where t* is not inside its flight.
  bool Residual(const Eigen::VectorXd& x, Eigen::VectorXd* f) const;
  /// dF/dX; `step_scale` multiplies the difference steps of the defining
  /// rows (CompareCurveJacobian).
  bool Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian, double step_scale = 1.0) const;

  /// The fold/PD borders from the singular vectors of D P ∓ I at X
  /// (between corrector solves only: F must not change during one).
  void UpdateBorders(const Eigen::VectorXd& x);

  /// F(X) = 0 with c · X = value, from `guess`; empty without convergence.
  std::optional<Eigen::VectorXd> Correct(const Eigen::VectorXd& guess, const Eigen::VectorXd& c,
                                         double value, const NewtonOptions& newton,
                                         int* iterations) const;
  /// The unit null vector of dF/dX, continuing `previous` (or from the SVD).
  std::optional<Eigen::VectorXd> Tangent(const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& previous) const;
  /// Grazing: the grazing orbit at X, at (μ1, μ2): its touch at t* (or the
  /// response's closest approach) and its impacts; empty if the map fails.
  std::optional<GrazingOrbit> GrazingOrbitAt(const Eigen::VectorXd& x) const;
  /// The curve point at a converged X; empty if the map fails there.
  std::optional<CurvePoint> Describe(const Eigen::VectorXd& x,
                                     const Eigen::VectorXd& previous) const;

 private:
  const BranchProblem& Along1(double mu2) const;  ///< U in (η, μ1) at μ2
  const BranchProblem& Along2(double mu1) const;  ///< U in (η, μ2) at μ1
  /// The defining rows at X (size 1, or 2 for grazing), and U if `u` (not
  /// for grazing, whose rows do not apply the map); false if the map fails.
  bool Defining(const Eigen::VectorXd& x, Eigen::VectorXd* g, Eigen::VectorXd* u = nullptr) const;
  /// The defining rows' gradient by central differences (steps scaled);
  /// with U's Jacobian, only between maps that follow X's impacts.
  bool DefiningGradient(const Eigen::VectorXd& x, double step_scale, Eigen::MatrixXd* gradient,
                        const Eigen::MatrixXd* u_jacobian = nullptr) const;
  /// Grazing: a guess beyond the grazing (where U has no value), moved
  /// back inside; any other guess unchanged.
  Eigen::VectorXd Inside(const Eigen::VectorXd& x) const;
  /// The multiplier a fold (+1) or period doubling (−1) curve holds.
  /// Grazing: the impact state that starts the flight holding the touch,
  /// and the stop that impact is at.
  struct FlightStart {
    Eigen::VectorXd eta;
    int stop = 0;
  };
  std::optional<FlightStart> GrazingFlightStart(const ImpactMap& map,
                                                const Eigen::VectorXd& eta) const;
  /// Grazing: t* lies after the flight's start and before its next impact.
  bool TouchInsideFlight(const Eigen::VectorXd& x) const;
  /// Grazing: its GrazingLimit(±1) at X into *point; false if the map fails.
  bool GrazingLimits(const Eigen::VectorXd& x, CurvePoint* point) const;

  System base_;
  CurveOptions options_;
  NamedParameter mu1_, mu2_;  ///< options_.parameter and parameter2, resolved
  SpecialPointType type_;
  int grazing_flight_;
  bool response_;
  int touched_stop_;
  int eta_size_, size_;
  SigmaBorders borders_;
  /// A branch problem in one parameter at a value of the other, kept
  /// while that value does not change.
  struct CachedBranch {
    std::unique_ptr<BranchProblem> problem;
    double fixed_at = 0.0;
  };
  /// U in (η, `free`) with `fixed` at `value`, from *cache when it is there.
  const BranchProblem& Along(const NamedParameter& fixed, double value, const NamedParameter& free,
                             CachedBranch* cache) const;
  mutable CachedBranch along1_, along2_;
};

}  // namespace impactkit::detail
