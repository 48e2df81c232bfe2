#include "impactkit/dynamics/mode_clock.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "core/require.hpp"

namespace impactkit {
namespace {

/// sup over τ >= τ0 of τ e^{-aτ} (a > 0).
double TauDecayMax(double a, double tau0) {
  if (a <= 0) return std::numeric_limits<double>::infinity();
  return tau0 >= 1.0 / a ? tau0 * std::exp(-a * tau0) : 1.0 / (a * std::numbers::e);
}

/// a b written out: std::complex's operator* checks for NaN and infinities
/// through a library call (__mulxc3), which made a table's construction
/// cost three times its arithmetic. The same operations otherwise, so the
/// same bits.
std::complex<long double> Product(std::complex<long double> a, std::complex<long double> b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

/// e^{λτ} and e^{λτ} − 1 in long double.
struct ExponentialParts {
  std::complex<long double> value{1.0L, 0.0L}, increment{0.0L, 0.0L};

  /// At z = λτ with |z| <= 4, from the series: 40 terms take 4^n / n! below 1e-20.
  static ExponentialParts At(std::complex<long double> z) {
    ExponentialParts parts;
    std::complex<long double> term = z;
    for (int n = 2; n <= 42; ++n) {
      parts.increment += term;
      term = Product(term, z / static_cast<long double>(n));
    }
    parts.value = 1.0L + parts.increment;
    return parts;
  }
  /// From τ to τ + σ, with `step` the parts at σ:
  /// e^{λ(τ+σ)} − 1 = e^{λσ}(e^{λτ} − 1) + (e^{λσ} − 1).
  void Advance(const ExponentialParts& step) {
    increment = Product(step.value, increment) + step.increment;
    value = Product(step.value, value);
  }
};

/// The tables' first `count` entries, at τ = k σ, by the recurrence above:
/// each step's rounding is an ulp of long double, so 256 steps stay below
/// an ulp of double, where exp, expm1 and sincos per entry made a table's
/// construction cost as much as ten thousand evaluations of it.
template <std::size_t kSize>
void FillTables(std::complex<double> rate, double sigma, std::size_t count,
                std::array<std::complex<double>, kSize>* values,
                std::array<std::complex<double>, kSize>* increments) {
  const std::complex<long double> rate_ld(rate.real(), rate.imag());
  const ExponentialParts step = ExponentialParts::At(rate_ld * static_cast<long double>(sigma));
  ExponentialParts parts;
  auto narrow = [](std::complex<long double> z) {
    return std::complex<double>(static_cast<double>(z.real()), static_cast<double>(z.imag()));
  };
  for (std::size_t k = 0; k < count; ++k) {
    (*values)[k] = narrow(parts.value);
    (*increments)[k] = narrow(parts.increment);
    parts.Advance(step);
  }
}

}  // namespace

/// e^x (cos y + i sin y) − 1 with x + iy = λτ is
/// (expm1(x) cos y − 2 sin²(y/2)) + i e^x sin y.
std::complex<double> ExponentialIncrement(std::complex<double> rate, double tau) {
  const double x = rate.real() * tau, y = rate.imag() * tau;
  const double half_sine = std::sin(0.5 * y);
  return {std::expm1(x) * std::cos(y) - 2.0 * half_sine * half_sine, std::exp(x) * std::sin(y)};
}

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

double ModeBasis::CosineIncrement(double tau) const {
  if (beta2 > 0) return ExponentialIncrement({-decay, root}, tau).real();
  // Over-damped: e^{-aτ} cosh(bτ) − 1 = (e^{-(a−b)τ} − 1 + e^{-(a+b)τ} − 1) / 2.
  if (beta2 < 0)
    return 0.5 * (std::expm1(-(decay - root) * tau) + std::expm1(-(decay + root) * tau));
  return std::expm1(-decay * tau);
}

double ModeBasis::LargestRate() const {
  if (beta2 > 0) return std::sqrt(decay * decay + beta2);
  return decay + root;  // over-damped: the faster of a ± b; critical: a
}

SecondOrderSeries::SecondOrderSeries(double decay, double beta2) {
  // y^(n+2) = −2a y^(n+1) − (a² + β²) y^(n), kept divided by n! and in long
  // double (its rounding then stays below double's).
  const long double a = decay, m = static_cast<long double>(decay) * decay + beta2;
  auto fill = [&](long double y0, long double y1, std::array<double, kTerms>* coefficients) {
    for (int n = 0; n < kTerms; ++n) {  // y0, y1: y^(n)/n!, y^(n+1)/(n+1)!
      const long double k = n + 1;
      const long double y2 = (-2.0L * a * k * y1 - m * y0) / (k * (k + 1));
      (*coefficients)[n] = static_cast<double>(y2);
      y0 = y1;
      y1 = y2;
    }
  };
  fill(1.0L, -a, &cosine_);
  fill(0.0L, 1.0L, &sine_);
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

ExponentialTable::ExponentialTable(std::complex<double> rate, unsigned coarse_entries) {
  Require(coarse_entries >= 1 && coarse_entries <= kCoarse,
          "an exponential table holds 1 to {} coarse entries, asked for {}", kCoarse,
          coarse_entries);
  // h = 2^-m with h|λ| in (1/32, 1/16], so |λδ| <= 1/32.
  const double magnitude = std::abs(rate);
  const int exponent = magnitude > 0 ? -std::ilogb(16.0 * magnitude) - 1 : 0;
  step_ = std::ldexp(1.0, exponent);
  inverse_step_ = std::ldexp(1.0, -exponent);
  limit_ = kFine * coarse_entries - 0.5;
  std::complex<double> term = 1.0;
  for (int n = 0; n <= kDegree; ++n) {
    taylor_[n] = {term.real(), term.imag()};
    term *= rate / static_cast<double>(n + 1);
  }
  FillTables(rate, step_, kFine, &fine_, &fine_increment_);
  FillTables(rate, kFine * step_, coarse_entries, &coarse_, &coarse_increment_);
}

const std::shared_ptr<const ExponentialTable>& ExponentialTable::Empty() {
  static const auto empty = std::make_shared<const ExponentialTable>();
  return empty;
}

namespace {

/// The table of e^{λτ} for a rate λ. Continuation builds the flows at
/// every parameter value its corrector visits (μ and μ ± h for ∂U/∂μ);
/// in Ω, r or xs the modes do not move, and building their tables (640
/// long-double products each) was a quarter of a connected diagram's CPU
/// time (docs/performance.md). The forcing's rotor moves with Ω but is
/// asked for again at one μ: by each mode of a hybrid system, and by the
/// systems built again at a converged point. The last few rates' tables
/// are kept per thread and shared: the same rate, bit for bit, and range
/// give the same table.
std::shared_ptr<const ExponentialTable> KeptTable(std::complex<double> rate,
                                                  unsigned coarse_entries) {
  constexpr std::size_t kKept = 8;
  struct Kept {
    std::uint64_t real, imag;
    unsigned coarse_entries;
    std::shared_ptr<const ExponentialTable> table;
  };
  thread_local std::vector<Kept> kept;  // the newest last
  const std::uint64_t real = std::bit_cast<std::uint64_t>(rate.real());
  const std::uint64_t imag = std::bit_cast<std::uint64_t>(rate.imag());
  for (const Kept& k : kept) {
    if (k.real == real && k.imag == imag && k.coarse_entries == coarse_entries) return k.table;
  }
  if (kept.size() == kKept) kept.erase(kept.begin());
  kept.push_back(
      {real, imag, coarse_entries, std::make_shared<const ExponentialTable>(rate, coarse_entries)});
  return kept.back().table;
}

}  // namespace

ModeClock::ModeClock(std::vector<ModeBasis> modes, double omega)
    : modes_(std::move(modes)),
      omega_(omega),
      rotor_(KeptTable({0.0, omega}, kRotorCoarse)),
      rotor_series_(0.0, omega * omega) {
  double largest_rate = omega;
  for (const ModeBasis& mode : modes_) {
    series_.emplace_back(mode.decay, mode.beta2);
    largest_rate = std::max(largest_rate, mode.LargestRate());
    const bool oscillates = mode.beta2 > 0;
    tables_.push_back(oscillates ? KeptTable({-mode.decay, mode.root}, ExponentialTable::kCoarse)
                                 : ExponentialTable::Empty());
    inverse_roots_.push_back(oscillates ? 1.0 / mode.root : 0.0);
  }
  anchored_span_ = 1.0 / largest_rate;
}

}  // namespace impactkit
