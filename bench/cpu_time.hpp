#pragma once
/// \file cpu_time.hpp
/// CPU seconds of this process: the benchmarks report rates per CPU-second,
/// unaffected by other work on the machine's other core.

#include <ctime>

namespace impactkit::bench {

inline double CpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

}  // namespace impactkit::bench
