#include "impactkit/dynamics/mode_clock.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace impactkit {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// sup over τ >= τ0 of τ e^{-aτ} (a > 0).
double TauDecayMax(double a, double tau0) {
  if (a <= 0) return kInfinity;
  return tau0 >= 1.0 / a ? tau0 * std::exp(-a * tau0) : 1.0 / (a * std::numbers::e);
}

/// e^{λτ} from exp and sincos.
std::complex<double> Exponential(std::complex<double> rate, double tau) {
  return std::exp(rate.real() * tau) * std::polar(1.0, rate.imag() * tau);
}

}  // namespace

std::complex<double> ForcingRotor(double omega, double t) {
  struct Memo {
    double omega = std::numeric_limits<double>::quiet_NaN();
    double t = 0.0;
    std::complex<double> rotor;
  };
  thread_local Memo memo;
  if (omega != memo.omega || t != memo.t) memo = {omega, t, std::polar(1.0, omega * t)};
  return memo.rotor;
}

ModeBasis ModeBasis::Make(double decay, double beta2) {
  ModeBasis mode{decay, beta2, std::sqrt(std::abs(beta2))};
  // For β >= e a the generic bound |α| e^{-aτ0} + |γ| sup τ e^{-aτ} is never
  // below the amplitude's: sup τ e^{-aτ} >= e^{-aτ0}/β then.
  mode.lightly_damped = beta2 > 0 && mode.root >= std::numbers::e * decay;
  if (mode.lightly_damped) mode.modulus = std::sqrt(decay * decay + beta2);
  return mode;
}

void ModeBasis::Evaluate(double tau, double* ec, double* es) const {
  if (beta2 > 0) {
    const double e = std::exp(-decay * tau);
    double sine, cosine;
    ::sincos(root * tau, &sine, &cosine);  // glibc: one call for both
    *ec = e * cosine;
    *es = e * sine / root;
  } else if (beta2 < 0) {
    // e^{-aτ}cosh(bτ) and e^{-aτ}sinh(bτ)/b from the two decaying
    // exponentials, so nothing overflows for long flights.
    const double slow = std::exp(-(decay - root) * tau);
    const double fast = std::exp(-(decay + root) * tau);
    *ec = 0.5 * (slow + fast);
    *es = -slow * std::expm1(-2.0 * root * tau) / (2.0 * root);
  } else {
    const double e = std::exp(-decay * tau);
    *ec = e;
    *es = e * tau;
  }
}

ModeBasis::Decay ModeBasis::DecayFrom(double tau_from) const {
  // |S| <= τ e^{bτ} in every regime (b = 0 unless over-damped).
  const double slow_decay = decay - (beta2 < 0 ? root : 0.0);
  if (tau_from <= 0) return Decay{1.0, TauDecayMax(slow_decay, 0.0), 1.0, 1.0};
  return Decay{std::exp(-slow_decay * tau_from), TauDecayMax(slow_decay, tau_from),
               std::exp(-decay * tau_from), std::exp(-(decay + root) * tau_from)};
}

double ModeBasis::Envelope(double alpha, double gamma, const Decay& d) const {
  if (alpha == 0 && gamma == 0) return 0.0;
  const double generic =
      std::abs(alpha) * d.slow + (gamma == 0 ? 0.0 : std::abs(gamma) * d.tau_times_slow);
  if (beta2 > 0) {
    const double ratio = gamma / root;
    return std::min(generic, d.own * std::sqrt(alpha * alpha + ratio * ratio));
  }
  if (beta2 < 0) {
    const double split =
        0.5 * (std::abs(alpha + gamma / root) * d.slow + std::abs(alpha - gamma / root) * d.fast);
    return std::min(generic, split);
  }
  return generic;
}

double ModeBasis::Envelope(double alpha, double gamma, double tau_from) const {
  return Envelope(alpha, gamma, DecayFrom(tau_from));
}

ExponentialTable::ExponentialTable(std::complex<double> rate) {
  // h = 2^-m with h|λ| in (1/32, 1/16], so |λδ| <= 1/32.
  const double magnitude = std::abs(rate);
  const int exponent = magnitude > 0 ? -std::ilogb(16.0 * magnitude) - 1 : 0;
  step_ = std::ldexp(1.0, exponent);
  inverse_step_ = std::ldexp(1.0, -exponent);
  limit_ = kFine * kCoarse - 0.5;
  std::complex<double> term = 1.0;
  for (int n = 0; n <= kDegree; ++n) {
    taylor_[n] = {term.real(), term.imag()};
    term *= rate / static_cast<double>(n + 1);
  }
  for (unsigned k = 0; k < kFine; ++k) fine_[k] = Exponential(rate, k * step_);
  for (unsigned k = 0; k < kCoarse; ++k) coarse_[k] = Exponential(rate, k * kFine * step_);
}

ModeClock::ModeClock(std::vector<ModeBasis> modes, double omega)
    : modes_(std::move(modes)), omega_(omega), rotor_({0.0, omega}) {
  for (const ModeBasis& mode : modes_) {
    const bool oscillates = mode.beta2 > 0;
    tables_.push_back(oscillates ? ExponentialTable({-mode.decay, mode.root}) : ExponentialTable());
    inverse_roots_.push_back(oscillates ? 1.0 / mode.root : 0.0);
  }
}

}  // namespace impactkit
