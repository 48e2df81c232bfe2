#include "odeint_peer.hpp"

#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>

#include "impactkit/core/errors.hpp"

namespace impactkit::bench {
namespace {

namespace odeint = boost::numeric::odeint;

using State = std::array<double, 4>;  // (x1, x2, v1, v2)
using Matrix2 = std::array<std::array<double, 2>, 2>;

// y' = (v, M^{-1}(A cos Ωt - C v - K x)), with M^{-1}C, M^{-1}K and M^{-1}A
// formed once.
struct PaperRhs {
  Matrix2 minv_c, minv_k;
  std::array<double, 2> minv_a;
  double omega;

  void operator()(const State& y, State& dydt, double t) const {
    const double f = std::cos(omega * t);
    dydt[0] = y[2];
    dydt[1] = y[3];
    for (int i = 0; i < 2; ++i) {
      dydt[2 + i] = minv_a[i] * f - minv_c[i][0] * y[2] - minv_c[i][1] * y[3] -
                    minv_k[i][0] * y[0] - minv_k[i][1] * y[1];
    }
  }
};

Matrix2 Times(const Eigen::Matrix2d& a, const Eigen::MatrixXd& b) {
  const Eigen::Matrix2d p = a * b;
  return {{{p(0, 0), p(0, 1)}, {p(1, 0), p(1, 1)}}};
}

}  // namespace

PlainOdeintRun PlainOdeintImpacts(const System& s, double t_end, double tolerance) {
  Require(s.Dof() == 2, "the plain Odeint peer is written for two masses");
  const Eigen::Matrix2d minv = Eigen::Matrix2d(s.mass).inverse();
  const Eigen::Vector2d minv_a = minv * s.forcing;
  const PaperRhs rhs{
      Times(minv, s.damping), Times(minv, s.stiffness), {minv_a(0), minv_a(1)}, s.omega};
  Require(s.StopCount() == 1 && s.stops[0].side == StopSide::kUpper,
          "the plain Odeint peer is written for one upper stop");
  const StopParameters& stop = s.stops[0];
  const int c = stop.dof;
  // The impulse acts along M^{-1} e_c and sets v_c to -r v_c.
  const std::array<double, 2> impulse{minv(0, c) / minv(c, c), minv(1, c) / minv(c, c)};
  auto gap = [&](const State& y) { return y[c] - stop.position; };

  auto stepper =
      odeint::make_dense_output(tolerance, tolerance, odeint::runge_kutta_dopri5<State>());
  // A small fraction (1/65) of the paper system's shortest natural period,
  // 2π/1.618 = 3.9, is a sensible first try; the controller adapts it within
  // a few steps.
  stepper.initialize(State{0.0, 0.0, 0.0, 0.0}, 0.0, 0.06);
  PlainOdeintRun run;
  std::vector<double>& times = run.times;
  State y;
  // 50 bits: the root to ~1e-15 relative, far below the dense output's error.
  const boost::math::tools::eps_tolerance<double> root_tolerance(50);
  while (stepper.current_time() < t_end) {
    stepper.do_step(rhs);
    if (gap(stepper.previous_state()) >= 0.0 && gap(stepper.current_state()) > 0.0) {
      run.stopped = true;  // held at the stop: sticking
      break;
    }
    if (!(gap(stepper.previous_state()) < 0.0 && gap(stepper.current_state()) >= 0.0)) continue;
    auto gap_at = [&](double t) {
      stepper.calc_state(t, y);
      return gap(y);
    };
    std::uintmax_t max_iterations = 100;
    const auto [t_lo, t_hi] = boost::math::tools::toms748_solve(
        gap_at, stepper.previous_time(), stepper.current_time(), root_tolerance, max_iterations);
    const double t_impact = 0.5 * (t_lo + t_hi);
    if (t_impact >= t_end) break;
    if (!times.empty() && t_impact - times.back() < 1e-9) {
      run.stopped = true;  // chatter
      break;
    }
    times.push_back(t_impact);
    stepper.calc_state(t_impact, y);
    const double dv = -(1.0 + stop.restitution) * y[2 + c];
    y[2] += impulse[0] * dv;
    y[3] += impulse[1] * dv;
    y[c] = stop.position;
    // The acceleration jumps: restart, which also drops the stale stored
    // derivative, with the last step size.
    stepper.initialize(y, t_impact, stepper.current_time_step());
  }
  return run;
}

}  // namespace impactkit::bench
