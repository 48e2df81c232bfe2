#pragma once
/// \file odeint_impacts.hpp
/// Reference integrator of the impact oscillator built on Boost.Odeint, in the
/// classic step-and-check-sign style (Boost's find_crossing example): dense
/// output Dormand-Prince 5(4), g = x_c - xs checked at each step end, the
/// crossing located by bisection on the dense output, the stepper restarted
/// at the impact. Independent of the library: it reads the fields of
/// impactkit::System and nothing else. A benchmark peer and a second opinion
/// for tests.
///
/// Known limit: a grazing pair of crossings inside one step leaves g < 0 at
/// both ends and goes unnoticed, as in any integrator of this kind.

#include <Eigen/Dense>

#include "impactkit/model/system.hpp"
#include "reference_run.hpp"

namespace impactkit::reference {

struct OdeintOptions {
  double abs_tol = 1e-12;
  double rel_tol = 1e-12;
  double crossing_tol = 1e-12;  ///< width of the final bracket of an impact time
  long max_impacts = 1000000;
  /// Stop (chatter_detected) when two impacts are closer than this, or the
  /// next flight is predicted to be (2 |v_c+| / a_c), or to stay within 100
  /// position tolerances of the stop (see oscillator_model.hpp).
  double min_interimpact = 1e-9;
};

/// Integrates the impact oscillator from (x0, v0) at t0 up to t_end, or until
/// impacts accumulate. A start with x_c >= xs and v_c > 0 is an impact at t0.
/// Impact times are the left end of the final bracket (before the stop, within
/// crossing_tol of the crossing of the dense output).
ReferenceRun OdeintImpacts(const System& s, Eigen::VectorXd x0, Eigen::VectorXd v0, double t0,
                           double t_end, const OdeintOptions& o);

}  // namespace impactkit::reference
