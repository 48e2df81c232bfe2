#include "impactkit/analysis/lyapunov.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace impactkit {

bool LyapunovOptions::IsValid(std::string* error) const {
  if (impacts < 1) {
    *error = fmt::format("impacts must be >= 1, got {}", impacts);
    return false;
  }
  if (transient_impacts < 0) {
    *error = fmt::format("transient_impacts must be >= 0, got {}", transient_impacts);
    return false;
  }
  return map.IsValid(error);
}

LyapunovResult ImpactMapLyapunov(const System& system, const Eigen::VectorXd& eta,
                                 const LyapunovOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const ImpactMap map(system, options.map);
  map.ValidateEta(eta);

  const int n = static_cast<int>(eta.size());
  const int time_index = map.TimeIndex();
  const double period = system.ForcingPeriod();
  LyapunovResult result;

  // τ is an absolute time; the map commutes with shifts by T, so τ is kept
  // in [0, T) (event times stay precise over long runs) and the whole
  // periods removed are counted in `elapsed`.
  Eigen::VectorXd current = eta;
  double shifted = 0.0;
  auto normalise_time = [&] {
    const double whole = std::floor(current(time_index) / period) * period;
    current(time_index) -= whole;
    shifted += whole;
  };
  auto fail = [&](const MapResult& image, int impact) {
    result.valid = false;
    result.exponents.clear();
    result.message = fmt::format("the impact map failed at impact {} ({}): {}", impact,
                                 impact < options.transient_impacts ? "transient" : "counted",
                                 Describe(image.termination));
    return result;
  };

  normalise_time();
  // The transient impacts also turn the frame Q towards the growing
  // subspaces (their logarithms are not counted): without that, the initial
  // frame's misalignment adds an O(1/n) bias, ~4/n per impact here.
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd log_sums = Eigen::VectorXd::Zero(n);
  double start = 0.0;
  // With several stops each step may end at another stop, whose impacts
  // have coordinates of their own: the Jacobians chain across them.
  int stop = map.SectionStop();
  const int total = options.transient_impacts + options.impacts;
  for (int j = 0; j < total; ++j) {
    if (j == options.transient_impacts) {
      start = shifted + current(time_index);
      log_sums.setZero();
    }
    const MapResult image = map.Follow(current, stop, 1, true);
    if (image.termination != Termination::kCompleted) return fail(image, j);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(image.jacobian * q);
    const Eigen::VectorXd diagonal = qr.matrixQR().diagonal();
    if (!diagonal.allFinite() || (diagonal.array() == 0.0).any()) {
      result.message = fmt::format("singular or non-finite Jacobian at impact {}", j);
      return result;
    }
    // Householder QR leaves signs on diag R; the exponents need |R_ii|, and
    // Q must carry the signs so that the next product stays J Q.
    q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    for (int i = 0; i < n; ++i) {
      if (diagonal(i) < 0) q.col(i) = -q.col(i);
    }
    log_sums += diagonal.cwiseAbs().array().log().matrix();
    current = image.eta;
    stop = image.stops.back();
    normalise_time();
  }
  const double end = shifted + current(time_index);

  result.impacts_used = options.impacts;
  result.time_span = end - start;
  if (!(result.time_span > 0.0)) {
    result.message = "no time elapsed over the counted impacts";
    return result;
  }
  result.exponents.resize(n);
  for (int i = 0; i < n; ++i) result.exponents[i] = log_sums(i) / result.time_span;
  std::sort(result.exponents.begin(), result.exponents.end(), std::greater<>());
  result.largest = result.exponents.front();
  result.valid = true;
  result.message =
      fmt::format("{} impacts over time {:.6g}", result.impacts_used, result.time_span);
  return result;
}

}  // namespace impactkit
