/// CPU time per impact of the exact simulator beside two peers that integrate
/// the same system at equal accuracy: SUNDIALS CVODE with its own rootfinding
/// (reference/cvode_impacts.cpp) and a plain Boost.Odeint dense-output
/// Dormand–Prince with TOMS 748 on the dense output (odeint_peer.hpp), both
/// at rtol = atol. Equal accuracy is taken at two levels: each peer runs at
/// the loosest tolerance of a ladder whose first 50 impact times lie within
/// 1e-8 (then 1e-11) of ours; our own distance from CVODE at its tightest is
/// printed beside. Then the cost growth with N. Every figure is the median of
/// three measurements, each repeated until 0.5 s of CPU time.
///
///   ./build/bench/simulate_bench [periods]      (default 10000)

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cvode_impacts.hpp"
#include "impact_timing.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "odeint_peer.hpp"

namespace {

using namespace impactkit;

using bench::CvodeImpactTimes;
using bench::Measure;
using bench::OurImpactTimes;
using bench::Timed;
using ImpactTimes = bench::ImpactTimes;
/// A peer's impact times at a tolerance, up to t_end.
using PeerAt = std::function<std::vector<double>(double tolerance, double t_end)>;

/// Largest |difference| over the first `count` impact times.
double MaxDifference(const std::vector<double>& a, const std::vector<double>& b,
                     std::size_t count) {
  if (a.size() < count || b.size() < count) return INFINITY;
  double worst = 0.0;
  for (std::size_t i = 0; i < count; ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

/// The loosest tolerance of the ladder whose first 50 impacts agree with
/// `exact` to `level`; none if even the tightest does not.
std::optional<double> LoosestAccurateTolerance(const std::vector<double>& exact, double level,
                                               double t_check, const PeerAt& peer) {
  for (double tol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14}) {
    if (MaxDifference(peer(tol, t_check), exact, 50) <= level) return tol;
  }
  return std::nullopt;
}

/// "µs (tol)" of a peer at equal accuracy, and its µs per impact (or NaN).
std::pair<std::string, double> PeerCell(const std::vector<double>& exact, double level,
                                        double t_check, double t_end, const PeerAt& peer) {
  const std::optional<double> tol = LoosestAccurateTolerance(exact, level, t_check, peer);
  if (!tol) return {"not reached", NAN};
  const Timed timed = Measure([&](double t) { return peer(*tol, t); }, t_end);
  return {fmt::format("{:.3f} (tol {:.0e}, {} impacts)", timed.MicrosecondsPerImpact(), *tol,
                      timed.impacts),
          timed.MicrosecondsPerImpact()};
}

void CompareWithPeers(double omega, int periods) {
  const System s = PaperSystem(omega);
  const double t_end = periods * s.ForcingPeriod();
  const double t_check = 100 * s.ForcingPeriod();
  const std::vector<double> exact = OurImpactTimes(s, t_check);
  // CVODE at its most accurate (rtol 1e-13, atol 1e-15), as in the tests.
  const reference::CvodeOptions tightest{.rtol = 1e-13, .atol = 1e-15};
  const double our_error = MaxDifference(exact, CvodeImpactTimes(s, tightest, t_check), 50);
  const Timed ours = Measure([&](double t) { return OurImpactTimes(s, t); }, t_end);
  const PeerAt cvode = [&](double tol, double t) {
    return CvodeImpactTimes(s, {.rtol = tol, .atol = tol}, t);
  };
  const PeerAt odeint = [&](double tol, double t) {
    return bench::PlainOdeintImpacts(s, t, tol).times;
  };
  for (double level : {1e-8, 1e-11}) {
    const auto [cvode_cell, cvode_us] = PeerCell(exact, level, t_check, t_end, cvode);
    const auto [odeint_cell, odeint_us] = PeerCell(exact, level, t_check, t_end, odeint);
    // NaN (a peer that never reached the level) drops out of std::fmin.
    const double faster_peer = std::fmin(cvode_us, odeint_us);
    const std::string speed_up =
        std::isnan(faster_peer)
            ? "no peer reached it"
            : fmt::format("{:.1f}x", faster_peer / ours.MicrosecondsPerImpact());
    fmt::print("| {} | {:.0e} | {:.3f} ({} impacts) | {} | {} | {} | {:.1e} |\n", omega, level,
               ours.MicrosecondsPerImpact(), ours.impacts, cvode_cell, odeint_cell, speed_up,
               our_error);
  }
}

/// Least-squares slope of log y against log x.
double GrowthExponent(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void ScalingWithDof(int periods) {
  fmt::print("\n| N | impacts | µs per forcing period | µs per impact |\n");
  fmt::print("|---|---|---|---|\n");
  std::vector<double> dofs, per_period, per_impact;
  for (int n : {2, 5, 10, 20, 50, 100, 200}) {
    Eigen::VectorXd forcing = Eigen::VectorXd::Zero(n);
    forcing(n - 1) = 0.5;  // on the contact mass, so every N impacts
    const System s = UniformChain({n, 1.0, 1.0, 0.1}, forcing, 1.4, 0.1, 0.7);
    const Timed ours =
        Measure([&](double t) { return OurImpactTimes(s, t); }, periods * s.ForcingPeriod());
    dofs.push_back(n);
    per_period.push_back(1e6 * ours.seconds / periods);
    per_impact.push_back(ours.MicrosecondsPerImpact());
    fmt::print("| {} | {} | {:.2f} | {:.2f} |\n", n, ours.impacts, per_period.back(),
               per_impact.back());
  }
  fmt::print(
      "\nGrowth exponent (least squares on log-log, all N): per period {:.2f}, "
      "per impact {:.2f}\n",
      GrowthExponent(dofs, per_period), GrowthExponent(dofs, per_impact));
}

}  // namespace

int main(int argc, char** argv) {
  const int periods = argc > 1 ? std::atoi(argv[1]) : 10000;
  if (periods < 100) {
    fmt::print(stderr, "usage: simulate_bench [periods >= 100]\n");
    return 2;
  }
  fmt::print(
      "{} forcing periods from rest, paper system; CPU µs per impact, median of 3; peers at "
      "rtol = atol = tol\n\n",
      periods);
  fmt::print(
      "| Ω | first 50 impacts within | impactkit | CVODE (Adams, rootfinding) | Odeint DOPRI5 + "
      "TOMS 748 | speed-up vs faster peer | our max |Δt| vs CVODE 1e-13 (first 50) |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  for (double omega : {0.6, 1.4, 1.75}) CompareWithPeers(omega, periods);
  ScalingWithDof(periods / 10);
  return 0;
}
