/// CPU time per impact with two stops beside one, in the same run:
///  - the paper's system, and the same with a second stop it never reaches
///    (below mass 1 at -10): the same motion, so the ratio is the price of
///    watching a second stop;
///  - the paper's system with mass 2 in a clearance of 0.2 (a stop on each
///    side, both hit), beside CVODE with one root function per stop at the
///    loosest tolerance whose first 50 impacts lie within 1e-8 of ours.
/// Every figure is the median of three measurements, each repeated until
/// 0.5 s of CPU time.
///
///   ./build/bench/stops_bench [periods]      (default 10000)

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include "impact_timing.hpp"

namespace {

using namespace impactkit;
using bench::Measure;
using bench::OurImpactTimes;
using bench::Timed;

std::vector<double> CvodeTimes(const System& s, double tolerance, double t_end) {
  return bench::CvodeImpactTimes(s, {.rtol = tolerance, .atol = tolerance}, t_end);
}

/// The loosest CVODE tolerance whose first 50 impact times lie within 1e-8
/// of `exact`.
std::optional<double> CvodeTolerance(const System& s, const std::vector<double>& exact,
                                     double t_check) {
  for (double tol : {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13}) {
    const std::vector<double> times = CvodeTimes(s, tol, t_check);
    if (times.size() < 50 || exact.size() < 50) continue;
    double worst = 0.0;
    for (std::size_t i = 0; i < 50; ++i) worst = std::max(worst, std::abs(times[i] - exact[i]));
    if (worst <= 1e-8) return tol;
  }
  return std::nullopt;
}

void CompareStops(double omega, int periods) {
  const System one = PaperSystem(omega);
  System watched = one, clearance = one;
  watched.stops.push_back({0, StopSide::kLower, -10.0, 0.7});
  clearance.stops.push_back({1, StopSide::kLower, -0.1, 0.7});
  const double t_end = periods * one.ForcingPeriod();
  const Timed a = Measure([&](double t) { return OurImpactTimes(one, t); }, t_end);
  const Timed b = Measure([&](double t) { return OurImpactTimes(watched, t); }, t_end);
  const Timed c = Measure([&](double t) { return OurImpactTimes(clearance, t); }, t_end);
  const double t_check = 100 * one.ForcingPeriod();
  std::string peer = "not reached";
  if (const std::optional<double> tol =
          CvodeTolerance(clearance, OurImpactTimes(clearance, t_check), t_check)) {
    const Timed cvode = Measure([&](double t) { return CvodeTimes(clearance, *tol, t); }, t_end);
    peer = fmt::format("{:.3f} (tol {:.0e}, {:.1f}x)", cvode.MicrosecondsPerImpact(), *tol,
                       cvode.MicrosecondsPerImpact() / c.MicrosecondsPerImpact());
  }
  fmt::print("| {} | {:.3f} ({}) | {:.3f} ({:.2f}x) | {:.3f} ({}, {:.2f}x) | {} |\n", omega,
             a.MicrosecondsPerImpact(), a.impacts, b.MicrosecondsPerImpact(),
             b.MicrosecondsPerImpact() / a.MicrosecondsPerImpact(), c.MicrosecondsPerImpact(),
             c.impacts, c.MicrosecondsPerImpact() / a.MicrosecondsPerImpact(), peer);
}

}  // namespace

int main(int argc, char** argv) {
  const int periods = argc > 1 ? std::atoi(argv[1]) : 10000;
  if (periods < 100) {
    fmt::print(stderr, "usage: stops_bench [periods >= 100]\n");
    return 2;
  }
  fmt::print("{} forcing periods from rest; CPU µs per impact, median of 3\n\n", periods);
  fmt::print(
      "| Ω | one stop (impacts) | + a stop never reached (ratio) | clearance of 0.2, both "
      "stops hit (impacts, ratio) | CVODE, a root function per stop, first 50 within 1e-8 "
      "(tol, CVODE / ours) |\n");
  fmt::print("|---|---|---|---|---|\n");
  for (double omega : {0.8, 1.2, 1.6, 2.0}) CompareStops(omega, periods);
  return 0;
}
