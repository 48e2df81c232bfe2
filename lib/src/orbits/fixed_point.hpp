#pragma once
/// \file fixed_point.hpp (private)
/// A periodic orbit of k section events in q forcing periods as a zero of
///
///     U(x) = P^k(x) − x − q T e_t
///
/// on any section map (section_map.hpp: the impact map or the release
/// map), with U's Jacobian D P^k − I, analytic or by central differences;
/// solved by Newton (KINSOL) and, if asked, Levenberg–Marquardt (Ceres)
/// from the guess. The one solve of FindOrbit on either section.

#include <Eigen/Dense>
#include <string>

#include "impactkit/core/termination.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/section_map.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

class FixedPointProblem {
 public:
  /// `map` must outlive this. `analytic`: the map's own Jacobian, else
  /// central differences (FiniteDifferenceJacobian).
  FixedPointProblem(const SectionMap& map, int k, int q, bool analytic)
      : map_(map), k_(k), shift_(q * map.GetSystem().ForcingPeriod()), analytic_(analytic) {}

  /// U(x); false where the map fails or U is not finite.
  bool Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const;
  /// D P^k(x) − I; false where the map fails.
  bool Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const;
  const SectionMap& Map() const { return map_; }
  int Events() const { return k_; }

 private:
  const SectionMap& map_;
  int k_;
  double shift_;  ///< q T
  bool analytic_;
  /// Newton asks for the Jacobian where it has just asked for the
  /// residual: the analytic one costs little beside the map, so both come
  /// at once and the Jacobian is kept for that call.
  mutable Eigen::VectorXd cached_x_;
  mutable Eigen::MatrixXd cached_jacobian_;
};

/// What SolveFixedPoint did.
struct FixedPointSolve {
  SolveSummary solve;          ///< the last solver's (Levenberg–Marquardt's when it ran)
  int iterations = 0;          ///< Newton's plus Levenberg–Marquardt's
  bool used_fallback = false;  ///< Levenberg–Marquardt ran
  Eigen::VectorXd x;           ///< the solver's last point, its time in [0, T)
};

/// Newton on U from `guess`, then (if `least_squares_fallback` and Newton
/// did not converge) Levenberg–Marquardt from `guess`. A guess the map
/// cannot follow is kFailure, the message saying why ("the map failed at
/// the seed: after 0 of 1 impacts, lost impact ...").
FixedPointSolve SolveFixedPoint(const FixedPointProblem& problem, const Eigen::VectorXd& guess,
                                const NewtonOptions& newton, bool least_squares_fallback);

/// FindOrbit on the release section (sticking_orbit.cpp), the options
/// valid: the fixed point of P_R^k from the release state `guess`.
OrbitSummary FindStickingOrbit(const System& system, const Eigen::VectorXd& guess,
                               const OrbitOptions& options, PeriodicOrbit* orbit);

/// "<termination>: residual 1.23e-12 after n iterations" for a summary's
/// first words; without the residual where none was computed (the map
/// failed at the seed).
std::string SolveReport(Termination termination, double residual, int iterations);

}  // namespace impactkit
