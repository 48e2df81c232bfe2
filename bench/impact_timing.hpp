#pragma once
/// \file impact_timing.hpp
/// CPU time per impact of a run that returns its impact times: the median
/// of three measurements, each repeating the run until 0.5 s of CPU time;
/// and the impact times of our simulator and of the CVODE reference from
/// rest. Shared by the simulator benchmarks.

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "cpu_time.hpp"
#include "cvode_impacts.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit::bench {

/// A run to t_end that returns its impact times.
using ImpactTimes = std::function<std::vector<double>(double t_end)>;

struct Timed {
  std::size_t impacts = 0;
  double seconds = 0.0;  ///< CPU seconds per run
  double MicrosecondsPerImpact() const { return 1e6 * seconds / impacts; }
};

inline Timed Measure(const ImpactTimes& run, double t_end) {
  std::array<Timed, 3> samples;
  for (Timed& sample : samples) {
    int repeats = 0;
    const double start = CpuSeconds();
    do {
      sample.impacts = run(t_end).size();
      ++repeats;
    } while (CpuSeconds() - start < 0.5);
    sample.seconds = (CpuSeconds() - start) / repeats;
  }
  std::sort(samples.begin(), samples.end(),
            [](const Timed& a, const Timed& b) { return a.seconds < b.seconds; });
  return samples[1];
}

/// Our impact times from rest up to t_end.
inline std::vector<double> OurImpactTimes(const System& s, double t_end) {
  ImpactRecorder recorder;
  HybridState state = RestState(s);
  Simulator(s).Run(state, t_end, recorder);
  std::vector<double> times;
  for (const ImpactView i : recorder.Impacts()) times.push_back(i.t);
  return times;
}

/// CVODE's impact times from rest up to t_end (reference/cvode_impacts.hpp).
inline std::vector<double> CvodeImpactTimes(const System& s, const reference::CvodeOptions& o,
                                            double t_end) {
  const reference::ReferenceRun run =
      reference::CvodeImpacts(s, RestState(s).x, RestState(s).v, 0.0, t_end, o);
  std::vector<double> times;
  for (const auto& i : run.impacts) times.push_back(i.t);
  return times;
}

}  // namespace impactkit::bench
