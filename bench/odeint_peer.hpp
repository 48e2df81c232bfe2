#pragma once
/// \file odeint_peer.hpp
/// The benchmark's Boost.Odeint peer for the two-mass paper system, written
/// the way a competent user would: a fixed-size std::array state, dense-output
/// Dormand–Prince 5(4) with rtol = atol, the upward crossing of the stop
/// located by TOMS 748 (boost::math::tools::toms748_solve) on the step's dense
/// output, the impact law applied there and the stepper restarted with its
/// last step size. It is a speed peer, not a second opinion for the tests:
/// reference/odeint_impacts.cpp is that (any N, bisection to the last double).

#include <Eigen/Dense>
#include <vector>

#include "impactkit/model/system.hpp"

namespace impactkit::bench {

struct PlainOdeintRun {
  std::vector<double> times;  ///< impact times
  /// Stopped before t_end: two impacts closer than 1e-9 (chatter, which this
  /// method cannot follow) or the contact mass found beyond the stop at a
  /// step's end without an upward crossing (held there: sticking).
  bool stopped = false;
};

/// Impacts of the 2-DOF system s from rest up to t_end, at
/// rtol = atol = tolerance. Requires s.Dof() == 2.
PlainOdeintRun PlainOdeintImpacts(const System& s, double t_end, double tolerance);

}  // namespace impactkit::bench
