#pragma once
/// \file closed_form_sdof.hpp
/// An independent closed-form reference for the single-degree-of-freedom
/// impact oscillator's P(1,1) orbit (Shaw & Holmes 1983 style), for tests.
/// Depends only on Eigen and the standard library: no impactkit code.
///
/// The system:
///
///     m x'' + c x' + k x = A cos(Ω t)     while x < xs,
///     v(t+) = -r v(t-)                    when x = xs with v > 0.
///
/// With y = (x, v) the free flight is y' = S y + (0, A/m cos Ωt),
/// S = [[0, 1], [-k/m, -c/m]].
///
/// Steady (particular) response. Trying x_p = X cos(Ωt - φ):
///     (k - mΩ²) X cos(Ωt - φ) - cΩ X sin(Ωt - φ) = A cos Ωt
/// holds for all t iff X (k - mΩ²) = A cos φ and X cΩ = A sin φ, i.e.
///     X = A / sqrt((k - mΩ²)² + (cΩ)²),  φ = atan2(cΩ, k - mΩ²) ∈ [0, π].
/// So, with θ = Ωt - φ,  y_p(t) = (X cos θ, -X Ω sin θ), T-periodic, T = 2π/Ω.
///
/// Homogeneous transition Φ(s) = e^{S s}, written out for the under-damped
/// case: ω_n = sqrt(k/m), a = ζ ω_n = c/(2m), ω_d = sqrt(ω_n² - a²) > 0.
/// The free solution x(s) = e^{-a s} (x0 cos ω_d s + (v0 + a x0)/ω_d sin ω_d s)
/// and its derivative give
///     Φ(s) = e^{-a s} [[cos ω_d s + (a/ω_d) sin ω_d s,  sin(ω_d s)/ω_d            ],
///                      [-(ω_n²/ω_d) sin ω_d s,          cos ω_d s - (a/ω_d) sin ω_d s]],
/// and dΦ/ds = S Φ(s).  The general flight from y(τ+) is then
///     y(t) = y_p(t) + Φ(t - τ) (y(τ+) - y_p(τ)).
///
/// P(1,1) orbit. One impact per period at τ (mod T), speed u > 0 before it:
/// y(τ+) = (xs, -r u) and y((τ+T)-) = (xs, u). Since y_p(τ+T) = y_p(τ),
///     (xs, u) - Φ(T) (xs, -r u) = (I - Φ(T)) y_p(τ).
/// Ψ = I - Φ(T) is invertible (Φ(T) has eigenvalues of modulus e^{-aT} < 1
/// when c > 0; for c = 0 unless ω_n T ∈ 2πZ), so with w = (xs, 0), e2 = (0, 1),
///     y_p(τ) = Ψ⁻¹ [Ψ w + u (I + r Φ(T)) e2] = w + u d,
///     d = Ψ⁻¹ (I + r Φ(T)) e2.
/// Component-wise: X cos θ = xs + u d1 and -XΩ sin θ = u d2, linear in u and
/// in (cos θ, sin θ). Eliminating θ by cos² + sin² = 1:
///     (d1² + d2²/Ω²) u² + 2 xs d1 u + xs² - X² = 0,
/// a quadratic in u. Each root u > 0 gives cos θ = (xs + u d1)/X,
/// sin θ = -u d2/(XΩ), θ = atan2(sin θ, cos θ), τ = (θ + φ)/Ω mod T.
///
/// Such a root is a true orbit only if x(t) < xs on (τ, τ+T): the equations
/// ignore any earlier contact. SdofCheckFlight samples x(t) to check that.
///
/// Jacobian of the impact map P: (τ, u) -> (τ', u') (states just before
/// impacts). P is defined implicitly by
///     G(τ, u, τ', u') = (xs, u') - y_p(τ') - Φ(τ' - τ) z = 0,
///     z = (xs, -r u) - y_p(τ),   s = τ' - τ.
/// Partial derivatives (using dΦ/ds = S Φ):
///     ∂G/∂τ' = -y_p'(τ') - S Φ(s) z = -(u', x''(τ'-))   (minus the vector field),
///     ∂G/∂u' = e2,
///     ∂G/∂τ  = S Φ(s) z + Φ(s) y_p'(τ),
///     ∂G/∂u  = r Φ(s) e2,
/// and the implicit function theorem gives
///     DP = -[∂G/∂τ' ∂G/∂u']⁻¹ [∂G/∂τ ∂G/∂u],
/// whose eigenvalues are the orbit's multipliers. ([∂G/∂τ' e2] has
/// determinant -u', invertible for u' > 0.)

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace impactkit::testing {

/// The SDOF impact oscillator's parameters.
struct SdofParameters {
  double m = 1.0, k = 1.0, c = 0.1, a = 0.5, xs = 0.1, r = 0.7, omega = 1.0;

  double Period() const { return 2.0 * std::numbers::pi / omega; }
  /// X = A / sqrt((k - mΩ²)² + (cΩ)²).
  double SteadyAmplitude() const { return a / std::hypot(k - m * omega * omega, c * omega); }
  /// X'(Ω) = −A (−2mΩ (k − mΩ²) + c²Ω) / ((k − mΩ²)² + (cΩ)²)^{3/2}.
  double SteadyAmplitudeRate() const {
    const double d = k - m * omega * omega, squared = d * d + c * c * omega * omega;
    return -a * (-2.0 * m * omega * d + c * c * omega) / std::pow(squared, 1.5);
  }
  /// φ with tan φ = cΩ / (k - mΩ²), φ ∈ [0, π].
  double SteadyLag() const { return std::atan2(c * omega, k - m * omega * omega); }
  double NaturalFrequency() const { return std::sqrt(k / m); }
  /// a = ζ ω_n = c / (2m).
  double DecayRate() const { return c / (2.0 * m); }
  /// ω_d = sqrt(ω_n² - a²); throws unless under-damped.
  double DampedFrequency() const {
    const double wd2 = k / m - DecayRate() * DecayRate();
    if (!(wd2 > 0.0)) throw std::invalid_argument("closed_form_sdof: only the under-damped case");
    return std::sqrt(wd2);
  }
};

/// S = [[0, 1], [-k/m, -c/m]].
inline Eigen::Matrix2d SdofSystemMatrix(const SdofParameters& p) {
  Eigen::Matrix2d s;
  s << 0.0, 1.0, -p.k / p.m, -p.c / p.m;
  return s;
}

/// Φ(s) = e^{S s}, explicitly (under-damped).
inline Eigen::Matrix2d SdofTransition(const SdofParameters& p, double s) {
  const double a = p.DecayRate(), wd = p.DampedFrequency(), wn2 = p.k / p.m;
  const double e = std::exp(-a * s), cs = std::cos(wd * s), sn = std::sin(wd * s);
  Eigen::Matrix2d phi;
  phi << cs + a / wd * sn, sn / wd, -wn2 / wd * sn, cs - a / wd * sn;
  return e * phi;
}

/// y_p(t) = (X cos θ, -XΩ sin θ), θ = Ωt - φ.
inline Eigen::Vector2d SdofSteadyState(const SdofParameters& p, double t) {
  const double x = p.SteadyAmplitude(), th = p.omega * t - p.SteadyLag();
  return {x * std::cos(th), -x * p.omega * std::sin(th)};
}

/// y_p'(t) = (-XΩ sin θ, -XΩ² cos θ).
inline Eigen::Vector2d SdofSteadyRate(const SdofParameters& p, double t) {
  const double x = p.SteadyAmplitude(), th = p.omega * t - p.SteadyLag();
  return {-x * p.omega * std::sin(th), -x * p.omega * p.omega * std::cos(th)};
}

/// The free flight y(t) from y(t0) = y0, closed form.
inline Eigen::Vector2d SdofFlight(const SdofParameters& p, double t0, const Eigen::Vector2d& y0,
                                  double t) {
  return SdofSteadyState(p, t) + SdofTransition(p, t - t0) * (y0 - SdofSteadyState(p, t0));
}

/// The free flight by brute RK4 with `steps` equal steps: an independent
/// check of the closed form (no Φ, no y_p).
inline Eigen::Vector2d SdofFlightRk4(const SdofParameters& p, double t0, Eigen::Vector2d y,
                                     double t1, int steps) {
  const Eigen::Matrix2d s = SdofSystemMatrix(p);
  auto f = [&](double t, const Eigen::Vector2d& z) -> Eigen::Vector2d {
    return s * z + Eigen::Vector2d(0.0, p.a / p.m * std::cos(p.omega * t));
  };
  const double h = (t1 - t0) / steps;
  for (int i = 0; i < steps; ++i) {
    const double t = t0 + i * h;
    const Eigen::Vector2d k1 = f(t, y);
    const Eigen::Vector2d k2 = f(t + h / 2, y + h / 2 * k1);
    const Eigen::Vector2d k3 = f(t + h / 2, y + h / 2 * k2);
    const Eigen::Vector2d k4 = f(t + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return y;
}

/// A P(1,1) solution: impact time τ ∈ [0, T) and speed u > 0 before impact.
struct SdofP11 {
  double tau = 0.0;
  double u = 0.0;
};

/// d = Ψ⁻¹ (I + r Φ(T)) e2: y_p(τ) = w + u d at a P(1,1) orbit (above).
inline Eigen::Vector2d SdofImpactDirection(const SdofParameters& p) {
  const Eigen::Matrix2d phi = SdofTransition(p, p.Period());
  const Eigen::Matrix2d psi = Eigen::Matrix2d::Identity() - phi;
  return psi.partialPivLu().solve((Eigen::Matrix2d::Identity() + p.r * phi) *
                                  Eigen::Vector2d(0, 1));
}

/// The P(1,1) orbit of a root u of the speeds' quadratic: τ from
/// cos θ = (xs + u d1) / X, sin θ = −u d2 / (XΩ), τ = (θ + φ) / Ω mod T.
inline SdofP11 SdofP11WithSpeed(const SdofParameters& p, double u) {
  const double period = p.Period(), x = p.SteadyAmplitude();
  const Eigen::Vector2d d = SdofImpactDirection(p);
  const double cos_th = (p.xs + u * d(0)) / x;
  const double sin_th = -u * d(1) / (x * p.omega);
  const double theta = std::atan2(sin_th, cos_th);
  double tau = std::fmod((theta + p.SteadyLag()) / p.omega, period);
  if (tau < 0.0) tau += period;
  if (tau >= period) tau -= period;
  return {tau, u};
}

/// All solutions of the P(1,1) equations with u > 0 (not yet checked for
/// extra contacts: see SdofCheckFlight).
inline std::vector<SdofP11> SdofP11Solutions(const SdofParameters& p) {
  const double x = p.SteadyAmplitude();
  const Eigen::Vector2d d = SdofImpactDirection(p);
  // qa u² + qb u + qc = 0.
  const double qa = d(0) * d(0) + d(1) * d(1) / (p.omega * p.omega);
  const double qb = 2.0 * p.xs * d(0);
  // xs² − X² as a product: near grazing (X → xs, the small root u → 0) the
  // difference of squares would add the rounding of both squares; this
  // leaves X's own (a few ulps), ~3e-8 relative in u at Ω_g − Ω = 1e-8 for
  // tests/test_orbit_grazing.cpp's system (u ~ 7e-10). The roots below
  // are cancellation-free.
  const double qc = (p.xs - x) * (p.xs + x);
  const double disc = qb * qb - 4.0 * qa * qc;
  std::vector<SdofP11> out;
  if (!(qa > 0.0) || disc < 0.0) return out;
  // Cancellation-free roots.
  const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
  std::vector<double> roots;
  if (q != 0.0)
    roots = {q / qa, qc / q};
  else
    roots = {0.0};
  if (disc == 0.0) roots.resize(1);
  std::sort(roots.begin(), roots.end());
  for (double u : roots) {
    if (u > 0.0) out.push_back(SdofP11WithSpeed(p, u));
  }
  return out;
}

/// The periodicity residual (xs, u) - y((τ+T)-) of the flight from
/// (xs, -r u) at τ: zero at a solution.
inline Eigen::Vector2d SdofP11Residual(const SdofParameters& p, const SdofP11& o) {
  return Eigen::Vector2d(p.xs, o.u) -
         SdofFlight(p, o.tau, Eigen::Vector2d(p.xs, -p.r * o.u), o.tau + p.Period());
}

/// DP of the impact map (τ, u) -> (τ', u') where (τ', u') is the image of
/// (τ, u) (not checked), by implicit differentiation of G (see above).
inline Eigen::Matrix2d SdofImpactMapJacobian(const SdofParameters& p, double tau, double u,
                                             double tau_next, double u_next) {
  const Eigen::Matrix2d s = SdofSystemMatrix(p);
  const Eigen::Matrix2d phi = SdofTransition(p, tau_next - tau);
  const Eigen::Vector2d e2(0.0, 1.0);
  const Eigen::Vector2d z = Eigen::Vector2d(p.xs, -p.r * u) - SdofSteadyState(p, tau);
  Eigen::Matrix2d g_next, g_this;  // ∂G/∂(τ', u'), ∂G/∂(τ, u)
  g_next.col(0) = -SdofSteadyRate(p, tau_next) - s * phi * z;
  g_next.col(1) = e2;
  g_this.col(0) = s * phi * z + phi * SdofSteadyRate(p, tau);
  g_this.col(1) = p.r * phi * e2;
  (void)u_next;  // G is linear in u' with ∂G/∂u' = e2: u' enters only through G = 0
  return -g_next.partialPivLu().solve(g_this);
}

/// DP at a P(1,1) solution: (τ, u) -> (τ + T, u).
inline Eigen::Matrix2d SdofP11Jacobian(const SdofParameters& p, const SdofP11& o) {
  return SdofImpactMapJacobian(p, o.tau, o.u, o.tau + p.Period(), o.u);
}

/// Eigenvalues of a 2 x 2 matrix: tr/2 ± sqrt(tr²/4 - det), ordered by
/// decreasing modulus (then decreasing imaginary part). The smaller of two
/// real ones cancels when |tr| ≫ sqrt|det| (near grazing, |λ1| ~ 1/v):
/// use SdofP11Determinant / λ1 there.
inline std::array<std::complex<double>, 2> Eigenvalues2(const Eigen::Matrix2d& j) {
  const double half_tr = 0.5 * j.trace(), det = j.determinant();
  const std::complex<double> root = std::sqrt(std::complex<double>(half_tr * half_tr - det));
  std::array<std::complex<double>, 2> l{half_tr + root, half_tr - root};
  if (std::abs(l[1]) > std::abs(l[0]) ||
      (std::abs(l[1]) == std::abs(l[0]) && l[1].imag() > l[0].imag())) {
    std::swap(l[0], l[1]);
  }
  return l;
}

/// det DP at a P(1,1) orbit, exactly: det DP = det(∂G/∂(τ,u)) / det(∂G/∂(τ',u'))
/// with det ∂G/∂(τ',u') = −u' and det ∂G/∂(τ,u) = r det Φ(T) · (first entry
/// of S z + y_p'(τ)) = r e^{−cT/m} (−r u), so det DP = r² e^{−cT/m} u/u' =
/// r² e^{−cT/m}: the product of the multipliers, free of the 1/u entries'
/// cancellation.
inline double SdofP11Determinant(const SdofParameters& p) {
  return p.r * p.r * std::exp(-p.c / p.m * p.Period());
}

/// The result of sampling x(t) over the open flight (τ, τ+T).
struct SdofFlightCheck {
  double max_excess = -std::numeric_limits<double>::infinity();  ///< max of x - xs
  double max_time = 0.0;                                         ///< where the max was sampled
  /// First sample time with x > xs (NaN if none): an extra contact lies in
  /// (first_contact - T/samples, first_contact].
  double first_contact = std::numeric_limits<double>::quiet_NaN();
  bool Valid() const { return max_excess < 0.0; }
};

/// Samples x(t) - xs at t = τ + i T / samples, i = 1 .. samples - 1.
inline SdofFlightCheck SdofCheckFlight(const SdofParameters& p, const SdofP11& o,
                                       int samples = 20000) {
  SdofFlightCheck check;
  const double period = p.Period();
  const Eigen::Vector2d z = Eigen::Vector2d(p.xs, -p.r * o.u) - SdofSteadyState(p, o.tau);
  for (int i = 1; i < samples; ++i) {
    const double t = o.tau + period * i / samples;
    const double excess =
        SdofSteadyState(p, t)(0) + SdofTransition(p, t - o.tau).row(0).dot(z) - p.xs;
    if (excess > check.max_excess) {
      check.max_excess = excess;
      check.max_time = t;
    }
    if (excess > 0.0 && std::isnan(check.first_contact)) check.first_contact = t;
  }
  return check;
}

}  // namespace impactkit::testing
