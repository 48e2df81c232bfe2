/// A 200-point P(1,1) period-doubling curve of the paper's system in
/// (Ω, r), r from 0.3 to 0.95, codimension-two tests on — beside the way it
/// is done by hand: at each of the same r values, the period doubling
/// located in Ω by secant steps on det(D P + I) of FindOrbit's orbit, each
/// seeded from the previous r. Both in the same run.
///
///   ./build/bench/curve_bench

#include <fmt/format.h>

#include <cmath>

#include "cpu_time.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

/// Mean CPU seconds of `job` over at least one second of repeats.
template <typename Job>
double Time(Job job) {
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    job();
    ++repeats;
  } while (CpuSeconds() - start < 1.0);
  return (CpuSeconds() - start) / repeats;
}

/// The peer's period doubling in Ω at r, from (omega, eta); false if lost.
bool SecantPeriodDoubling(System system, double* omega, Eigen::VectorXd* eta) {
  OrbitOptions options;
  auto test = [&](double w, double* value) {
    system.omega = w;
    PeriodicOrbit orbit;
    if (FindOrbit(system, *eta, options, &orbit).termination != Termination::kConverged) {
      return false;
    }
    *eta = orbit.eta;
    *value = (orbit.jacobian + Eigen::MatrixXd::Identity(4, 4)).determinant();
    return true;
  };
  double w0 = *omega, w1 = *omega + 1e-4, f0 = 0.0, f1 = 0.0;
  if (!test(w0, &f0) || !test(w1, &f1)) return false;
  for (int k = 0; k < 50 && std::abs(w1 - w0) > 1e-12; ++k) {
    const double w2 = w1 - f1 * (w1 - w0) / (f1 - f0);
    w0 = w1;
    f0 = f1;
    w1 = w2;
    if (!test(w1, &f1)) return false;
  }
  *omega = w1;
  return true;
}

}  // namespace

int main() {
  const System system = PaperSystem(1.6);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
  if (!seed) return 1;
  OrbitOptions orbit_options;
  PeriodicOrbit start;
  if (FindOrbit(system, seed->eta, orbit_options, &start).termination != Termination::kConverged) {
    return 1;
  }
  ContinuationOptions search;
  search.from = 1.0;
  search.to = 2.0;
  const std::optional<SpecialPoint> pd =
      LocateSpecialPoint({system, start, {}}, search, SpecialPointType::kPeriodDoubling);
  if (!pd) return 1;
  System at = system;
  at.omega = pd->parameter;
  CurveOptions options;
  options.parameter2 = "r";
  options.from = 1.0;
  options.to = 2.0;
  options.from2 = 0.3;
  options.to2 = 0.95;
  // Steps that make about 200 points over r in [0.3, 0.95].
  options.initial_step = options.max_step = 0.0033;
  Curve curve;
  const double seconds = Time([&] { curve = ContinueCurve({at, *pd}, options); });

  int failures = 0;
  const double peer = Time([&] {
    failures = 0;
    double omega = curve.points.front().parameter;
    Eigen::VectorXd eta = curve.points.front().orbit.eta;
    for (const CurvePoint& point : curve.points) {
      System here = system;
      SetParameter(here, "r", point.parameter2);
      if (!SecantPeriodDoubling(here, &omega, &eta)) ++failures;
    }
  });
  fmt::print("| job | points | codim-2 points | CPU seconds |\n|---|---|---|---|\n");
  fmt::print(
      "| ContinueCurve, P(1,1) period doubling in (Ω, r), r 0.3 to 0.95 | {} | {} | {:.4f} |\n",
      curve.points.size(), curve.codim2_points.size(), seconds);
  fmt::print("| secant on det(DP + I) in Ω at the same r values | {} ({} failed) | — | {:.4f} |\n",
             curve.points.size(), failures, peer);
  return 0;
}
