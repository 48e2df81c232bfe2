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
/// k = k_lo + 64 k_hi; the table entries come from long double recurrences
/// (within an ulp of exp and sincos), the Taylor remainder is below
/// (1/32)^8 / 8! ≈ 2e-17, and the result is within a few ulps of exp and
/// sincos at about a fifth of their cost. Outside the
/// table's range (τ < 0, or beyond 16384 h: 80–160 periods of that rate;
/// the forcing's rotor 2048 h, ModeClock::kRotorCoarse) and for over- and
/// critically damped modes the closed forms are used.
///
/// Beside e^{λτ} the clock gives e^{λτ} − 1 without cancellation (from the
/// polynomial's terms past the first and tables of e^{λkh} − 1; expm1 in
/// the closed forms), and near a flight's start, |λ|τ <= 1, each mode's
/// remainder past the first order by its series (SecondOrderSeries): a
/// state or a signal known exactly at a flight's start (the gap at an
/// impact and its slope) is then evaluated as that plus increments whose
/// rounding is relative to their own size (LinearFlow::StateFrom,
/// Signal::AnchorAt).
/// No library evaluates exponentials of fixed complex rates this way, hence
/// the hand-written tables.

#include <Eigen/Core>
#include <array>
#include <complex>
#include <memory>
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
  /// e^{-aτ} C(τ) − 1, by expm1: no cancellation for small τ.
  double CosineIncrement(double tau) const;
  /// |λ|, the mode's largest rate: sqrt(a² + β²), or a + b when over-damped.
  double LargestRate() const;
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
  static constexpr unsigned kCoarse = 256;  ///< coarse entries at most
  /// The table of e^{λτ} for τ up to 64 `coarse_entries` steps h; the
  /// entries are the same bits whatever the range. Throws InvalidInput
  /// unless 1 <= coarse_entries <= kCoarse.
  explicit ExponentialTable(std::complex<double> rate, unsigned coarse_entries = kCoarse);
  /// One empty table, shared by the clocks of modes that have none.
  static const std::shared_ptr<const ExponentialTable>& Empty();

  /// e^{λτ} into *value; false (nothing written) where τ is outside [0, range).
  /// Inline: it is the inner loop of every event search.
  bool Evaluate(double tau, std::complex<double>* value) const {
    unsigned k;
    double delta;
    if (!Locate(tau, &k, &delta)) return false;
    const std::complex<double> steps = StepProduct(k);
    *value = Multiply(steps, Increment(delta) + 1.0);
    return true;
  }
  /// e^{λτ} − 1 to a few ulps of itself: (e^{λkh} − 1) e^{λδ} + (e^{λδ} − 1),
  /// each factor's increment kept (e^{λτ} itself is 1 plus it, to an ulp).
  bool EvaluateIncrement(double tau, std::complex<double>* increment) const {
    unsigned k;
    double delta;
    if (!Locate(tau, &k, &delta)) return false;
    const std::complex<double> small = Increment(delta);
    *increment = Multiply(StepIncrement(k), small + 1.0) + small;
    return true;
  }

 private:
  /// τ = k h + δ with |δ| <= h/2, both exact; false outside the range.
  bool Locate(double tau, unsigned* k, double* delta) const {
    const double scaled = tau * inverse_step_;  // exact: h is a power of 2
    if (!(scaled >= 0.0 && scaled < limit_)) return false;
    // Unsigned (scaled >= 0): the table indices below are then a mask and a
    // shift, where a signed k costs sign corrections in every evaluation.
    *k = static_cast<unsigned>(scaled + 0.5);
    *delta = tau - *k * step_;  // exact (Sterbenz)
    return true;
  }
  /// e^{λδ} − 1 by its Taylor polynomial's terms past the first.
  std::complex<double> Increment(double delta) const {
    // Real and imaginary parts side by side in one SIMD register (the same
    // operations per part as two scalar loops, half the instructions).
    Eigen::Array2d polynomial = taylor_[kDegree];
    for (int n = kDegree - 1; n >= 1; --n) polynomial = polynomial * delta + taylor_[n];
    polynomial *= delta;
    return {polynomial[0], polynomial[1]};
  }
  /// e^{λkh} from the two tables.
  std::complex<double> StepProduct(unsigned k) const {
    return Multiply(fine_[k % kFine], coarse_[k / kFine]);
  }
  /// e^{λkh} − 1 = (a − 1)(b − 1) + (a − 1) + (b − 1), a and b the two tables' entries.
  std::complex<double> StepIncrement(unsigned k) const {
    const std::complex<double> a = fine_increment_[k % kFine], b = coarse_increment_[k / kFine];
    return Multiply(a, b) + a + b;
  }
  /// Products written out: std::complex's operator* checks for NaN and
  /// infinities through a library call.
  static std::complex<double> Multiply(std::complex<double> a, std::complex<double> b) {
    return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
  }

  static constexpr unsigned kFine = 64;  ///< entries e^{λ k h}, k < kFine; then e^{λ kFine k h}
  static constexpr int kDegree = 7;
  double step_ = 0.0;                               ///< h, a power of 2
  double inverse_step_ = 0.0;                       ///< 1/h
  double limit_ = 0.0;                              ///< τ/h must be below this (0: empty)
  std::array<Eigen::Array2d, kDegree + 1> taylor_;  ///< λ^n / n! as (re, im)
  // In the object, not behind a pointer: one load fewer per entry.
  std::array<std::complex<double>, kFine> fine_{};
  std::array<std::complex<double>, kCoarse> coarse_{};
  std::array<std::complex<double>, kFine> fine_increment_{};      ///< e^{λ k h} − 1
  std::array<std::complex<double>, kCoarse> coarse_increment_{};  ///< e^{λ kFine k h} − 1
};

/// e^{λτ} − 1 from exp, expm1 and sincos, without cancellation.
std::complex<double> ExponentialIncrement(std::complex<double> rate, double tau);

/// A mode's parts past the first order, e^{-aτ} C(τ) − 1 + aτ and
/// e^{-aτ} S(τ) − τ, by their Taylor series where |λ|τ <= 1. Both functions
/// solve y'' + 2a y' + (a² + β²) y = 0 (y(0), y'(0) = (1, −a) and (0, 1)),
/// so their derivatives at 0 follow one recurrence in every regime, under-,
/// over- and critically damped, without the division by β that makes the
/// closed forms cancel near critical damping. Their n-th derivatives are at
/// most |λ|^n and n |λ|^(n−1), so at |λ|τ = 1 the terms past τ¹⁹ are below
/// 1e-17 of the functions' scales, 1 and τ.
class SecondOrderSeries {
 public:
  SecondOrderSeries() = default;
  SecondOrderSeries(double decay, double beta2);
  /// Precondition: |λ|τ <= 1.
  void Evaluate(double tau, double* cosine_second, double* sine_second) const {
    double cosine = cosine_[kTerms - 1], sine = sine_[kTerms - 1];
    for (int n = kTerms - 2; n >= 0; --n) {
      cosine = cosine * tau + cosine_[n];
      sine = sine * tau + sine_[n];
    }
    const double tau2 = tau * tau;
    *cosine_second = cosine * tau2;
    *sine_second = sine * tau2;
  }

 private:
  static constexpr int kTerms = 18;      ///< the powers τ² … τ¹⁹
  std::array<double, kTerms> cosine_{};  ///< y^(n+2)(0) / (n+2)! of e^{-aτ} C
  std::array<double, kTerms> sine_{};    ///< and of e^{-aτ} S
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
  /// The rotor's table reaches 2048 h, h Ω in (1/32, 1/16]: 10–20 forcing
  /// periods from a flight's start, beyond which std::polar gives e^{iΩτ}
  /// (to an ulp, as the table). The modes' tables are kept while Ω moves,
  /// but the rotor's is built again at every Ω a continuation visits, and
  /// building all 256 coarse entries was 10 % of a connected diagram's CPU
  /// time, for flights that reach a few of them (docs/performance.md).
  static constexpr unsigned kRotorCoarse = 32;

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
    if (tables_[j]->Evaluate(tau, &e)) {
      *ec = e.real();
      *es = e.imag() * inverse_roots_[j];
      return;
    }
    modes_[j].Evaluate(tau, ec, es);
  }
  /// The same, and *ec_increment = e^{-aτ} C(τ) − 1 without cancellation.
  void Evaluate(int j, double tau, double* ec, double* es, double* ec_increment) const {
    if (tau == 0.0) {
      *ec = 1.0;
      *es = 0.0;
      *ec_increment = 0.0;
      return;
    }
    std::complex<double> increment;
    if (tables_[j]->EvaluateIncrement(tau, &increment)) {
      *ec_increment = increment.real();
      *ec = 1.0 + increment.real();
      *es = increment.imag() * inverse_roots_[j];
      return;
    }
    modes_[j].Evaluate(tau, ec, es);
    *ec_increment = modes_[j].CosineIncrement(tau);
  }
  /// e^{iΩτ}.
  std::complex<double> Rotor(double tau) const {
    std::complex<double> rotor{1.0, 0.0};
    if (tau == 0.0 || rotor_->Evaluate(tau, &rotor)) return rotor;
    return std::polar(1.0, omega_ * tau);
  }
  /// How far from a flight's start the parts past the first order are
  /// worth their cost: τ with |λ|τ <= 1 for every rate (the modes' and the
  /// forcing's). There each remainder is at most ~(|λ|τ)²/2 of its term, and
  /// so is its rounding; beyond, a sum anchored at the start (Signal::AnchorAt)
  /// would round at ε |λ|τ of each term, above the plain sum's ε.
  double AnchoredSpan() const { return anchored_span_; }
  /// Mode j's ec2 = e^{-aτ} C(τ) − 1 + aτ and es2 = e^{-aτ} S(τ) − τ by
  /// their series, and *ec, *es from them (to an ulp). Precondition:
  /// 0 <= τ <= AnchoredSpan().
  void EvaluateSecond(int j, double tau, double* ec, double* es, double* ec_second,
                      double* es_second) const {
    series_[j].Evaluate(tau, ec_second, es_second);
    *ec = 1.0 - modes_[j].decay * tau + *ec_second;
    *es = tau + *es_second;
  }
  /// e^{iΩτ} − 1 − iΩτ by its series. Precondition: 0 <= τ <= AnchoredSpan().
  std::complex<double> RotorSecondIncrement(double tau) const {
    double cosine_second, sine_second;
    rotor_series_.Evaluate(tau, &cosine_second, &sine_second);
    return {cosine_second, omega_ * sine_second};
  }
  /// e^{iΩτ} − 1 without cancellation.
  std::complex<double> RotorIncrement(double tau) const {
    std::complex<double> increment{0.0, 0.0};
    if (tau == 0.0 || rotor_->EvaluateIncrement(tau, &increment)) return increment;
    return ExponentialIncrement({0.0, omega_}, tau);
  }

 private:
  std::vector<ModeBasis> modes_;
  // Shared, not copied: the flows of neighbouring parameter values have
  // the same tables (mode_clock.cpp's KeptTable), and copying them was 4 %
  // of a connected diagram's CPU time.
  std::vector<std::shared_ptr<const ExponentialTable>> tables_;  ///< Empty() unless under-damped
  std::vector<double> inverse_roots_;                            ///< 1/β of the under-damped modes
  std::vector<SecondOrderSeries> series_;
  double omega_ = 0.0;
  std::shared_ptr<const ExponentialTable> rotor_ = ExponentialTable::Empty();
  SecondOrderSeries rotor_series_;  ///< cos Ωτ and sin(Ωτ)/Ω: a = 0, β = Ω
  double anchored_span_ = 0.0;
};

}  // namespace impactkit
