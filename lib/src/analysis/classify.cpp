#include "impactkit/analysis/classify.hpp"

#include <fmt/format.h>

#include <cmath>

#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {

std::string ToString(MotionKind kind) {
  switch (kind) {
    case MotionKind::kPeriodic:
      return "periodic";
    case MotionKind::kSticking:
      return "sticking";
    case MotionKind::kChaotic:
      return "chaotic";
    case MotionKind::kNonImpacting:
      return "non_impacting";
    case MotionKind::kUnresolved:
      return "unresolved";
  }
  return "unknown";
}

std::string MotionLabel(MotionKind kind, long p, int q) {
  switch (kind) {
    case MotionKind::kPeriodic:
      return fmt::format("P({},{})", p, q);
    case MotionKind::kSticking:
      return fmt::format("P(inf,{})", q);
    case MotionKind::kNonImpacting:
      return "non-impacting";
    case MotionKind::kChaotic:
      return "chaotic";
    case MotionKind::kUnresolved:
      return "unresolved";
  }
  return "unresolved";
}

bool ClassifyOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (period.max_q < 1) return fail(fmt::format("max_q must be >= 1, got {}", period.max_q));
  if (!(period.tolerance > 0 && std::isfinite(period.tolerance))) {
    return fail(
        fmt::format("the period tolerance must be finite and > 0, got {}", period.tolerance));
  }
  if (!(chaos_threshold >= 0 && std::isfinite(chaos_threshold))) {
    return fail(fmt::format("chaos_threshold must be finite and >= 0, got {}", chaos_threshold));
  }
  return lyapunov.IsValid(error);
}

std::string Classification::ToString() const {
  switch (kind) {
    case MotionKind::kPeriodic:
    case MotionKind::kSticking:
      return period.ToString();
    case MotionKind::kNonImpacting:
      return "non-impacting";
    case MotionKind::kChaotic:
      return fmt::format("chaotic (lambda = {:.3g})", lyapunov.largest);
    case MotionKind::kUnresolved:
      break;
  }
  if (!lyapunov_computed) return "unresolved: " + period.ToString();
  if (!lyapunov.valid)
    return fmt::format("unresolved: {}, {}", period.ToString(), lyapunov.message);
  return fmt::format("unresolved: {}, lambda = {:.3g}", period.ToString(), lyapunov.largest);
}

Classification ClassifyMotion(const System& system, const SampleLog& strobe,
                              const ImpactLog& impacts,
                              const std::vector<double>& chatter_end_times,
                              const ClassifyOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  Classification result;
  std::vector<double> times;
  times.reserve(impacts.size());
  for (const ImpactView i : impacts) times.push_back(i.t);
  result.period = DetectPeriod(strobe, times, chatter_end_times, options.period);
  if (impacts.empty()) {
    result.kind = MotionKind::kNonImpacting;
  } else if (result.period.periodic) {
    result.kind = result.period.sticking ? MotionKind::kSticking : MotionKind::kPeriodic;
  } else {
    const ImpactView last = impacts.back();
    LyapunovOptions lyapunov = options.lyapunov;
    lyapunov.map.stop = last.stop;
    const Eigen::VectorXd eta = ImpactMap(system, lyapunov.map).ToEta(last.t, last.x, last.v);
    result.lyapunov = ImpactMapLyapunov(system, eta, lyapunov);
    result.lyapunov_computed = true;
    const bool chaotic = result.lyapunov.valid && result.lyapunov.largest > options.chaos_threshold;
    result.kind = chaotic ? MotionKind::kChaotic : MotionKind::kUnresolved;
  }
  return result;
}

}  // namespace impactkit
