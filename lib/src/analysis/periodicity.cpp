#include "impactkit/analysis/periodicity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace impactkit {
namespace {

double Distance(const SampleView& a, const SampleView& b) {
  return std::max((a.x - b.x).cwiseAbs().maxCoeff(), (a.v - b.v).cwiseAbs().maxCoeff());
}

double Scale(const SampleLog& strobe) {
  double scale = 1e-3;
  for (const SampleView s : strobe) {
    scale = std::max({scale, s.x.cwiseAbs().maxCoeff(), s.v.cwiseAbs().maxCoeff()});
  }
  return scale;
}

/// Largest relative distance between points q periods apart, or the first
/// one found above `limit` (a q that fails is then rejected after a few
/// comparisons instead of a pass over the whole window: over a window that
/// is not periodic every q up to max_q failed after a full pass, 12 % of
/// `impactkit simulate`'s instructions).
double Mismatch(const SampleLog& strobe, int q, double scale, double limit) {
  double worst = 0.0;
  for (std::size_t k = 0; k + q < strobe.size() && worst <= limit; ++k) {
    worst = std::max(worst, Distance(strobe[k + q], strobe[k]) / scale);
  }
  return worst;
}

long CountIn(const std::vector<double>& times, double begin, double end) {
  return std::count_if(times.begin(), times.end(), [&](double t) { return t >= begin && t < end; });
}

}  // namespace

std::string MotionPeriod::ToString() const {
  if (!periodic) return fmt::format("no period up to q = {}", searched_q);
  return sticking ? fmt::format("P(inf,{})", q) : fmt::format("P({},{})", p, q);
}

MotionPeriod DetectPeriod(const SampleLog& strobe, const std::vector<double>& impact_times,
                          const std::vector<double>& chatter_end_times,
                          const PeriodOptions& options) {
  MotionPeriod result;
  if (strobe.size() < 3) return result;
  const double scale = Scale(strobe);
  result.searched_q = std::min<int>(options.max_q, static_cast<int>((strobe.size() - 1) / 2));
  for (int q = 1; q <= result.searched_q; ++q) {
    const double mismatch = Mismatch(strobe, q, scale, options.tolerance);
    if (mismatch > options.tolerance) continue;
    const double end = strobe.back().t, begin = strobe[strobe.size() - 1 - q].t;
    result.periodic = true;
    result.q = q;
    result.p = CountIn(impact_times, begin, end);
    result.sticking = CountIn(chatter_end_times, begin, end) > 0;
    result.mismatch = mismatch;
    return result;
  }
  return result;
}

}  // namespace impactkit
