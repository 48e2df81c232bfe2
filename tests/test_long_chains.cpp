// Long chains (issue 38): the structured eigensolver for a diagonal M and a
// tridiagonal K (core/symmetric_eigen.hpp, private), and the flow's modal
// form built on it, against references computed independently: the
// chain's closed-form eigenvalues, orthogonality and residuals, and the
// matrix exponential of S assembled here from M, C and K.
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/symmetric_eigen.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/model/system.hpp"

using namespace impactkit;

namespace {

/// ‖Φᵀ M Φ − I‖max and ‖K Φ − M Φ Λ‖max / ‖K‖max of a decomposition.
void CheckModes(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                const detail::GeneralizedModes& modes, double tolerance) {
  const Eigen::Index n = k.rows();
  const Eigen::MatrixXd& phi = modes.vectors;
  const Eigen::MatrixXd gram = phi.transpose() * m * phi;
  CHECK((gram - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() < tolerance);
  const Eigen::MatrixXd residual = k * phi - m * phi * modes.values.asDiagonal();
  CHECK(residual.cwiseAbs().maxCoeff() < tolerance * k.cwiseAbs().maxCoeff());
}

/// A chain of unequal masses and springs, wall at mass 1, with Rayleigh
/// damping C = α M + β K (classical) plus `extra` on the last mass.
struct Chain {
  Eigen::MatrixXd m, c, k;
};

Chain UnevenChain(int n, double extra) {
  Chain chain{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
              Eigen::MatrixXd::Zero(n, n)};
  for (int i = 0; i < n; ++i) {
    chain.m(i, i) = 1.0 + 0.5 * std::sin(0.7 * i);
    const double spring = 1.0 + 0.3 * std::cos(1.3 * i);  // between i − 1 (or the wall) and i
    chain.k(i, i) += spring;
    if (i > 0) {
      chain.k(i - 1, i - 1) += spring;
      chain.k(i - 1, i) = chain.k(i, i - 1) = -spring;
    }
  }
  chain.c = 0.02 * chain.m + 0.05 * chain.k;
  chain.c(n - 1, n - 1) += extra;
  return chain;
}

/// The state at t of the flight from (x0, v0) at t0, from e^{Sτ} and the
/// steady response solved here: y_p(t) = Re(Y e^{iΩt}), (iΩ − S) Y = b.
Eigen::VectorXd ReferenceState(const Chain& chain, const Eigen::VectorXd& a, double omega,
                               const Eigen::VectorXd& y0, double t0, double t) {
  const Eigen::Index n = chain.m.rows();
  const Eigen::MatrixXd m_inv = chain.m.inverse();
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.topRightCorner(n, n).setIdentity();
  s.bottomLeftCorner(n, n) = -m_inv * chain.k;
  s.bottomRightCorner(n, n) = -m_inv * chain.c;
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(2 * n);
  b.tail(n) = (m_inv * a).cast<std::complex<double>>();
  const Eigen::MatrixXcd resolvent =
      std::complex<double>(0.0, omega) * Eigen::MatrixXcd::Identity(2 * n, 2 * n) -
      s.cast<std::complex<double>>();
  const Eigen::VectorXcd steady = resolvent.partialPivLu().solve(b);
  auto particular = [&](double time) {
    return Eigen::VectorXd((steady * std::polar(1.0, omega * time)).real());
  };
  return particular(t) + (s * (t - t0)).exp() * (y0 - particular(t0));
}

/// Largest difference between the flow's state and the reference after
/// flights of several lengths from one state.
double FlowError(const Chain& chain, const Eigen::VectorXd& a, double omega) {
  const Eigen::Index n = chain.m.rows();
  const LinearFlow flow(chain.m, chain.c, chain.k, a, Eigen::VectorXd::Zero(n), omega);
  const Eigen::VectorXd x0 = Eigen::VectorXd::LinSpaced(n, 0.3, -0.2);
  const Eigen::VectorXd v0 = Eigen::VectorXd::LinSpaced(n, -0.4, 0.6);
  Eigen::VectorXd y0(2 * n);
  y0 << x0, v0;
  const double t0 = 0.7;
  const Eigen::VectorXd z0 = flow.Transient(t0, x0, v0);
  double worst = 0.0;
  for (double tau : {0.0, 0.37, 4.1, 30.0}) {
    Eigen::VectorXd x, v, y(2 * n);
    flow.State(t0, z0, t0 + tau, &x, &v);
    y << x, v;
    worst = std::max(worst,
                     (y - ReferenceState(chain, a, omega, y0, t0, t0 + tau)).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

TEST_CASE("tridiagonal modes of the paper's chain match the closed form at N = 400",
          "[flow][long_chains]") {
  // E = Q Λ Qᵀ with λ_j = 4 sin²((2j − 1)π / (2(2N + 1))), j = 1..N.
  const int n = 400;
  const Eigen::MatrixXd e = ChainCouplingMatrix(n);
  const Eigen::MatrixXd m = 2.0 * Eigen::MatrixXd::Identity(n, n);
  const detail::GeneralizedModes modes = detail::SolveGeneralized(e, m, true);
  for (int j = 1; j <= n; ++j) {
    const double half_angle = (2 * j - 1) * std::numbers::pi / (2.0 * (2 * n + 1));
    const double lambda = 4.0 * std::pow(std::sin(half_angle), 2) / 2.0;  // K φ = λ M φ, M = 2I
    CHECK(std::abs(modes.values(j - 1) - lambda) < 1e-14);
  }
  CheckModes(e, m, modes, 1e-11);
}

TEST_CASE("tridiagonal modes stay orthogonal where eigenvalues cluster or repeat",
          "[flow][long_chains]") {
  // Two equal uneven chains, joined by a spring of 1e-9 (eigenvalues in
  // pairs 1e-9 apart) and by none (exactly repeated eigenvalues).
  for (double joint : {1e-9, 0.0}) {
    INFO("joint " << joint);
    const Chain half = UnevenChain(60, 0.0);
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(120, 120), m = k;
    k.topLeftCorner(60, 60) = k.bottomRightCorner(60, 60) = half.k;
    m.topLeftCorner(60, 60) = m.bottomRightCorner(60, 60) = half.m;
    k(59, 59) += joint;
    k(60, 60) += joint;
    k(59, 60) = k(60, 59) = -joint;
    CheckModes(k, m, detail::SolveGeneralized(k, m, true), 1e-11);
  }
}

TEST_CASE("the modal form of a 50-mass chain agrees with the matrix exponential",
          "[flow][long_chains]") {
  // The paper's uniform chain (c = 0.1) and an uneven chain with Rayleigh
  // damping, both classical: the modal form (N >= 16) on the structured
  // eigensolver. Reference: y_p + e^{Sτ}(y0 − y_p), S from M, C, K here.
  const int n = 50;
  const Eigen::MatrixXd e = ChainCouplingMatrix(n);
  const Chain uniform{Eigen::MatrixXd::Identity(n, n), 0.1 * e, e};
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  a(0) = 0.5;
  CHECK(FlowError(uniform, a, 1.0) < 1e-10);
  CHECK(FlowError(UnevenChain(n, 0.0), Eigen::VectorXd::LinSpaced(n, 0.5, -0.1), 1.4) < 1e-10);
}

TEST_CASE("a 30-mass chain with a dashpot on its last mass takes the general route",
          "[flow][long_chains]") {
  // C = Rayleigh + 0.3 on the last mass does not commute through M⁻¹K: the
  // normal modes would couple (Φᵀ C Φ has off-diagonal terms 0.3 φ_iN φ_jN,
  // ~1e-2 here), and only the complex modes of S give this flow.
  const Chain chain = UnevenChain(30, 0.3);
  CHECK(FlowError(chain, Eigen::VectorXd::LinSpaced(30, 0.5, -0.1), 1.4) < 1e-9);
}
