#pragma once
/// \file mode_clock.hpp
/// The time dependence of a linear flow: per mode e^{-aτ} C(τ) and
/// e^{-aτ} S(τ) (flow.hpp), and the forcing's rotor e^{iΩτ}.
///
/// The event search evaluates these some ten times per flight, and each
/// evaluation by exp and sincos was most of an impact's cost
/// (docs/performance.md). Every rate λ here is fixed for the flow (an
/// under-damped mode's −a + iβ, the forcing's iΩ), so e^{λτ} is tabulated:
/// with h = 2^-m, h|λ| <= 1/16, and τ = k h + δ (|δ| <= h/2, both parts
/// exact),
///
///     e^{λτ} = e^{λ k_lo h} e^{λ 64 k_hi h} Σ_{n<=7} (λδ)^n / n!,
///
/// k = k_lo + 64 k_hi; the table entries come from exp and sincos, the
/// Taylor remainder is below (1/32)^8 / 8! ≈ 2e-17, and the result is within
/// a few ulps of exp and sincos at about a fifth of their cost. Outside the
/// table's range (τ < 0, or beyond 16384 h: some 160 periods of that rate)
/// and for over- and critically damped modes the closed forms are used.
/// No library evaluates exponentials of fixed complex rates this way, hence
/// the hand-written tables.

#include <Eigen/Core>
#include <array>
#include <complex>
#include <vector>

namespace impactkit {

/// The time dependence of one mode: e^{-a τ} C(τ) and e^{-a τ} S(τ).
struct ModeBasis {
  double decay = 0.0;  ///< a >= 0
  double beta2 = 0.0;  ///< β² (negative: over-damped)
  double root = 0.0;   ///< sqrt(|β²|)
  /// Under-damped with β >= e a: then e^{-aτ}(α C + γ S) = Re((α − iγ/β) e^{λτ}),
  /// λ = −a + iβ, is bounded by e^{-aτ0} |α − iγ/β| for τ >= τ0 at least as
  /// tightly as by Envelope's other bound, and its k-th derivative by |λ|^k
  /// times that (Signal::DerivativeBounds: one square root for all orders).
  bool lightly_damped = false;
  double modulus = 0.0;  ///< |λ| = sqrt(a² + β²) where lightly damped

  static ModeBasis Make(double decay, double beta2);

  /// ec = e^{-aτ} C(τ), es = e^{-aτ} S(τ), computed without overflow.
  void Evaluate(double tau, double* ec, double* es) const;
  /// Coefficients of the derivative: d/dτ e^{-aτ}(α C + γ S) = e^{-aτ}(α' C + γ' S).
  /// Defined here so that the evaluation loops inline it (C' = -β² S, S' = C).
  void Differentiate(double* alpha, double* gamma) const {
    const double a = *alpha, g = *gamma;
    *alpha = g - decay * a;
    *gamma = -decay * g - beta2 * a;
  }
  /// An upper bound of |e^{-aτ}(α C(τ) + γ S(τ))| over all τ >= tau_from >= 0.
  double Envelope(double alpha, double gamma, double tau_from) const;

  /// The decay factors Envelope needs at one τ (they do not depend on α, γ).
  struct Decay {
    double slow;            ///< e^{-(a - b) τ0}, b = sqrt(-β²) if over-damped, else 0
    double tau_times_slow;  ///< sup over τ >= τ0 of τ e^{-(a - b) τ}
    double own;             ///< e^{-a τ0}
    double fast;            ///< e^{-(a + b) τ0}
  };
  Decay DecayFrom(double tau_from) const;
  double Envelope(double alpha, double gamma, const Decay& decay) const;
};

/// e^{λτ} for one fixed complex rate λ by the tables above.
class ExponentialTable {
 public:
  /// An empty table: Evaluate always declines.
  ExponentialTable() { taylor_.fill(Eigen::Array2d::Zero()); }
  explicit ExponentialTable(std::complex<double> rate);

  /// e^{λτ} into *value; false (nothing written) where τ is outside [0, range).
  /// Inline: it is the inner loop of every event search.
  bool Evaluate(double tau, std::complex<double>* value) const {
    const double scaled = tau * inverse_step_;  // exact: h is a power of 2
    if (!(scaled >= 0.0 && scaled < limit_)) return false;
    // Unsigned (scaled >= 0): the table indices below are then a mask and a
    // shift, where a signed k costs sign corrections in every evaluation.
    const auto k = static_cast<unsigned>(scaled + 0.5);
    const double delta = tau - k * step_;  // exact (Sterbenz)
    // Real and imaginary parts side by side in one SIMD register (the same
    // operations per part as two scalar loops, half the instructions).
    Eigen::Array2d polynomial = taylor_[kDegree];
    for (int n = kDegree - 1; n >= 0; --n) polynomial = polynomial * delta + taylor_[n];
    const double re = polynomial[0], im = polynomial[1];
    // Products written out: std::complex's operator* checks for NaN and
    // infinities through a library call.
    const std::complex<double> a = fine_[k % kFine], b = coarse_[k / kFine];
    const double ab_re = a.real() * b.real() - a.imag() * b.imag();
    const double ab_im = a.real() * b.imag() + a.imag() * b.real();
    *value = {ab_re * re - ab_im * im, ab_re * im + ab_im * re};
    return true;
  }

 private:
  static constexpr unsigned kFine = 64;     ///< entries e^{λ k h}, k < kFine
  static constexpr unsigned kCoarse = 256;  ///< entries e^{λ kFine k h}, k < kCoarse
  static constexpr int kDegree = 7;
  double step_ = 0.0;                               ///< h, a power of 2
  double inverse_step_ = 0.0;                       ///< 1/h
  double limit_ = 0.0;                              ///< τ/h must be below this (0: empty)
  std::array<Eigen::Array2d, kDegree + 1> taylor_;  ///< λ^n / n! as (re, im)
  // In the object, not behind a pointer: one load fewer per entry.
  std::array<std::complex<double>, kFine> fine_{};
  std::array<std::complex<double>, kCoarse> coarse_{};
};

/// e^{iΩt} at an absolute time t, as std::polar(1, Ω t). Per thread the
/// last instant's value is kept: at every event the simulator asks for one
/// instant's rotor four times (the state there, the next flight's modal
/// coordinates, its witness and the chatter rule's acceleration), and each
/// sincos was ~3 % of an impact.
std::complex<double> ForcingRotor(double omega, double t);

/// Every mode's time dependence and the forcing's rotor, tabulated where
/// the rate allows.
class ModeClock {
 public:
  ModeClock() = default;
  ModeClock(std::vector<ModeBasis> modes, double omega);

  const std::vector<ModeBasis>& Modes() const { return modes_; }
  /// Mode j's e^{-aτ} C(τ) and e^{-aτ} S(τ) (ModeBasis::Evaluate, to a few ulps).
  void Evaluate(int j, double tau, double* ec, double* es) const {
    if (tau == 0.0) {  // a flight's own start: exactly what every path gives
      *ec = 1.0;
      *es = 0.0;
      return;
    }
    std::complex<double> e;
    if (tables_[j].Evaluate(tau, &e)) {
      *ec = e.real();
      *es = e.imag() * inverse_roots_[j];
      return;
    }
    modes_[j].Evaluate(tau, ec, es);
  }
  /// e^{iΩτ}.
  std::complex<double> Rotor(double tau) const {
    std::complex<double> rotor{1.0, 0.0};
    if (tau == 0.0 || rotor_.Evaluate(tau, &rotor)) return rotor;
    return std::polar(1.0, omega_ * tau);
  }

 private:
  std::vector<ModeBasis> modes_;
  std::vector<ExponentialTable> tables_;  ///< empty for modes that are not under-damped
  std::vector<double> inverse_roots_;     ///< 1/β of the under-damped modes
  double omega_ = 0.0;
  ExponentialTable rotor_;
};

}  // namespace impactkit
