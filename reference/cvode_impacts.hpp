#pragma once
/// \file cvode_impacts.hpp
/// Reference integrator of the impact oscillator built on SUNDIALS CVODE,
/// independent of the library's closed-form flow: it reads the fields of
/// impactkit::System and nothing else. For tests and as a benchmark peer.
///
/// Method: variable-order Adams-Moulton (orders up to 12) with Newton
/// iterations on a dense direct solver and the exact, constant Jacobian.
/// Adams rather than BDF because the problem is lightly damped and
/// oscillatory, not stiff: BDF of order 3 to 5 is not stable near the
/// imaginary axis and would crawl at low order, while high-order Adams
/// reaches rtol = 1e-12 with long steps. Observed global error: ~1e-10 after
/// 100 time units, growing about linearly.
///
/// Impacts are roots of each stop's g = s (x_c - xs) crossed upwards (one root
/// function per stop, CVodeRootInit with
/// CVodeSetRootDirection(+1)); CVODE returns at the root, the impact law is
/// applied, and the integrator restarts there (CVodeReInit).

#include <Eigen/Dense>

#include "impactkit/model/system.hpp"
#include "reference_run.hpp"

namespace impactkit::reference {

struct CvodeOptions {
  double rtol = 1e-12;
  double atol = 1e-14;
  double max_step = 0;  ///< largest step; 0: no limit
  long max_impacts = 1000000;
  /// Stop (chatter_detected) when two impacts are closer than this, or the
  /// next flight is predicted to be (2 |v_c+| / a_c), or to stay within 100
  /// position tolerances of the stop (see oscillator_model.hpp).
  double min_interimpact = 1e-9;
};

/// Integrates the impact oscillator from (x0, v0) at t0 up to t_end, or until
/// impacts accumulate. A start with x_c >= xs and v_c > 0 is an impact at t0.
ReferenceRun CvodeImpacts(const System& s, Eigen::VectorXd x0, Eigen::VectorXd v0, double t0,
                          double t_end, const CvodeOptions& o);

/// Integrates the smooth linear system M x'' + C x' + K x = A cos(Ω t) + f0
/// (no stop) from (x, v) at t0 to t1 in place; t1 < t0 integrates backwards.
void CvodeLinearFlow(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                     const Eigen::VectorXd& A, const Eigen::VectorXd& f0, double omega, double t0,
                     Eigen::VectorXd& x, Eigen::VectorXd& v, double t1, double rtol = 1e-12,
                     double atol = 1e-14);

}  // namespace impactkit::reference
