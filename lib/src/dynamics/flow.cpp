#include "impactkit/dynamics/flow.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/symmetric_eigen.hpp"
#include "impactkit/core/errors.hpp"

namespace impactkit {
namespace {

/// The largest condition number of a modal basis the flow accepts (see the
/// constructor).
constexpr double kMaxBasisCondition = 1e6;
/// The largest amplification of a forced mode (forced response over static
/// response, 1 / (2ζ) at a damped resonance) the flow accepts: rounding
/// grows with it, and above 1e6 the ~1e-10 accuracy is lost.
constexpr double kMaxAmplification = 1e6;

/// The 2n x 2n first-order matrix S = [[0, I], [-M⁻¹K, -M⁻¹C]].
Eigen::MatrixXd FirstOrderMatrix(const Eigen::MatrixXd& m_inv_k, const Eigen::MatrixXd& m_inv_c) {
  const Eigen::Index n = m_inv_k.rows();
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.topRightCorner(n, n).setIdentity();
  s.bottomLeftCorner(n, n) = -m_inv_k;
  s.bottomRightCorner(n, n) = -m_inv_c;
  return s;
}

/// Normal modes from this many degrees of freedom on are kept in the
/// modal form (LinearFlow::modal_); below, the dense form costs
/// microseconds to set up, its 4 x 4 product is the fastest per event, and
/// the usual small models keep their results bit for bit
/// (tests/test_fingerprints.cpp).
constexpr Eigen::Index kModalFormFrom = 16;

/// M⁻¹ B: a row scaling for a diagonal M (a chain's) of kModalFormFrom
/// or more degrees of freedom, where a dense Cholesky factorisation is
/// O(N³); otherwise the Cholesky solve, which below that size costs
/// nothing and keeps small models' results bit for bit (a vector B is
/// solved as a vector: the matrix kernel rounds otherwise).
template <typename Rhs>
Rhs SolveMass(const Eigen::MatrixXd& m, const Rhs& b) {
  if (m.rows() >= kModalFormFrom && detail::IsDiagonal(m)) {
    return (b.array().colwise() / m.diagonal().array()).matrix();
  }
  return m.llt().solve(b);
}

/// A B through A's sparse view: O(N²) for a chain's tridiagonal A, where
/// the dense product is O(N³).
Eigen::MatrixXd SparseProduct(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::SparseMatrix<double> sparse = a.sparseView();
  return sparse * b;
}

/// C M⁻¹ K = K M⁻¹ C (Caughey & O'Kelly): the normal modes decouple C too.
bool IsClassicallyDamped(const Eigen::MatrixXd& c, const Eigen::MatrixXd& m_inv_k) {
  const Eigen::MatrixXd m_inv_c_term = SparseProduct(c, m_inv_k);  // C M⁻¹ K
  const double scale = c.norm() * m_inv_k.norm();
  if (scale == 0) return true;
  return (m_inv_c_term - m_inv_c_term.transpose()).norm() <= 1e-10 * scale;
}

/// A real basis of invariant 2-planes of S and the 2 x 2 blocks on them.
struct BlockDecomposition {
  /// V (2n x 2n); in the modal form Φ (n x n), V = Φ ⊗ I₂ in coordinates
  /// that interleave each mode's q_j and q_j'.
  Eigen::MatrixXd basis;
  Eigen::MatrixXd blocks;  ///< 2 x 2n, B_j in columns 2j, 2j+1
  /// V⁻¹ = Φᵀ M ⊗ I₂ in the modal form (Φᵀ M Φ = I): no inverse to form.
  Eigen::MatrixXd modal_inverse;
};

/// Normal modes: z_j = (q_j, q_j'), B_j = [[0, 1], [-ω_j², -2 a_j]], with
/// modal damping 2 a_j = φ_jᵀ C φ_j.
Eigen::MatrixXd NormalModeBlocks(const Eigen::VectorXd& squares, const Eigen::MatrixXd& phi,
                                 const Eigen::MatrixXd& c) {
  const Eigen::VectorXd modal_damping =
      phi.cwiseProduct(SparseProduct(c, phi)).colwise().sum().transpose();
  Eigen::MatrixXd blocks(2, 2 * phi.cols());
  for (Eigen::Index j = 0; j < phi.cols(); ++j) {
    blocks.block<2, 2>(0, 2 * j) << 0.0, 1.0, -squares(j), -modal_damping(j);
  }
  return blocks;
}

/// Classical damping in the dense form: V holds each φ_j twice.
BlockDecomposition ClassicalBlocks(const Eigen::MatrixXd& m, const Eigen::MatrixXd& c,
                                   const Eigen::MatrixXd& k) {
  const Eigen::Index n = m.rows();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(k, m);  // Φᵀ M Φ = I
  const Eigen::MatrixXd& phi = modes.eigenvectors();
  BlockDecomposition d{Eigen::MatrixXd::Zero(2 * n, 2 * n),
                       NormalModeBlocks(modes.eigenvalues(), phi, c), Eigen::MatrixXd()};
  for (Eigen::Index j = 0; j < n; ++j) {
    d.basis.col(2 * j).head(n) = phi.col(j);
    d.basis.col(2 * j + 1).tail(n) = phi.col(j);
  }
  return d;
}

/// Classical damping in the modal form, the modes by the structured
/// eigensolver where M is diagonal and K tridiagonal (a chain): O(N²) in
/// all for a chain, where the dense form's inverse alone is O(N³).
BlockDecomposition ModalBlocks(const Eigen::MatrixXd& m, const Eigen::MatrixXd& c,
                               const Eigen::MatrixXd& k) {
  detail::GeneralizedModes modes = detail::SolveGeneralized(k, m, true);
  Eigen::MatrixXd blocks = NormalModeBlocks(modes.values, modes.vectors, c);
  Eigen::MatrixXd inverse = SparseProduct(m, modes.vectors).transpose();  // Φᵀ M
  return {std::move(modes.vectors), std::move(blocks), std::move(inverse)};
}

/// Non-classical damping: complex modes of S. A conjugate pair σ ± iω with
/// eigenvector u + iw spans [u, w] with block [[σ, ω], [-ω, σ]]; real
/// eigenvalues (an even number of them) are paired as diag(λ1, λ2).
BlockDecomposition ComplexBlocks(const Eigen::MatrixXd& s) {
  const Eigen::Index dim = s.rows();
  Eigen::EigenSolver<Eigen::MatrixXd> solver(s);
  const Eigen::VectorXcd& lambda = solver.eigenvalues();
  const Eigen::MatrixXcd& vectors = solver.eigenvectors();
  const double tol = 1e-12 * std::max(1.0, lambda.cwiseAbs().maxCoeff());
  BlockDecomposition d{Eigen::MatrixXd::Zero(dim, dim), Eigen::MatrixXd::Zero(2, dim),
                       Eigen::MatrixXd()};
  Eigen::Index col = 0;
  std::vector<Eigen::Index> reals;
  for (Eigen::Index i = 0; i < dim; ++i) {
    if (std::abs(lambda(i).imag()) <= tol) {
      reals.push_back(i);
    } else if (lambda(i).imag() > 0) {
      d.basis.col(col) = vectors.col(i).real();
      d.basis.col(col + 1) = vectors.col(i).imag();
      const double sigma = lambda(i).real(), w = lambda(i).imag();
      d.blocks.block<2, 2>(0, col) << sigma, w, -w, sigma;
      col += 2;
    }
  }
  std::sort(reals.begin(), reals.end(),
            [&](auto a, auto b) { return lambda(a).real() < lambda(b).real(); });
  for (std::size_t i = 0; i + 1 < reals.size(); i += 2) {
    d.basis.col(col) = vectors.col(reals[i]).real();
    d.basis.col(col + 1) = vectors.col(reals[i + 1]).real();
    d.blocks.block<2, 2>(0, col) << lambda(reals[i]).real(), 0.0, 0.0, lambda(reals[i + 1]).real();
    col += 2;
  }
  return d;
}

/// W = V⁻¹ of the dense form, refused where V is too ill-conditioned.
Eigen::MatrixXd DenseInverse(const Eigen::MatrixXd& basis) {
  const Eigen::FullPivLU<Eigen::MatrixXd> basis_lu(basis);
  // Rounding in the modal coordinates grows with the basis's condition
  // number: up to 1e6 the flow keeps ~1e-10. A defective state matrix (a
  // repeated eigenvalue with one eigenvector, e.g. M = I, K the paper's
  // chain, C = diag(2, 0)) has computed eigenvectors that nearly coincide,
  // a condition number ~1/√ε, and a flow wrong in the second digit.
  if (const double condition = 1.0 / basis_lu.rcond(); !(condition <= kMaxBasisCondition)) {
    throw InvalidInput(fmt::format(
        "the free modes are (nearly) defective: non-proportional damping with a repeated "
        "eigenvalue (condition number of the modal basis {:.2g}, at most {:.0e}); the exact "
        "flow needs distinct modes: change C slightly (e.g. no zero damping on one mass) or "
        "use proportional damping",
        condition, kMaxBasisCondition));
  }
  return basis_lu.inverse();
}

/// y = A x for the change of basis at every event. A 2 x 2 or 4 x 4 A (one
/// or two degrees of freedom, the usual vibro-impact models) goes through
/// Eigen's fixed-size product, unrolled in registers; the general kernel's
/// set-up cost more than its arithmetic there (~170 instructions a call
/// against ~60, docs/performance.md).
void Multiply(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd* y) {
  if (a.rows() == 4) {
    Eigen::Map<Eigen::Vector4d>(y->data()).noalias() =
        Eigen::Map<const Eigen::Matrix4d>(a.data()) * Eigen::Map<const Eigen::Vector4d>(x.data());
  } else if (a.rows() == 2) {
    Eigen::Map<Eigen::Vector2d>(y->data()).noalias() =
        Eigen::Map<const Eigen::Matrix2d>(a.data()) * Eigen::Map<const Eigen::Vector2d>(x.data());
  } else {
    y->noalias() = a * x;
  }
}

}  // namespace

double Signal::Value(double t) const {
  double value = 0.0, slope = 0.0;
  ValueAndSlope(t, &value, &slope);
  return value;
}

void Signal::ValueAndSlope(double t, double* value, double* slope) const {
  double curvature;
  ValueSlopeCurvature(t, value, slope, &curvature);
}

void Signal::ModeTerms::Set(const ModeBasis& mode, double alpha0, double gamma0) {
  for (int k = 0; k < 3; ++k) {
    alpha[k] = alpha0;
    gamma[k] = gamma0;
    mode.Differentiate(&alpha0, &gamma0);
  }
}

void Signal::ValueSlopeCurvature(double t, double* value, double* slope, double* curvature) const {
  const double tau = t - t0_;
  double w = constant_, dw = 0.0, d2w = 0.0;
  for (std::size_t j = 0; j < terms_.size(); ++j) {
    double ec, es;
    clock_->Evaluate(static_cast<int>(j), tau, &ec, &es);
    const ModeTerms& m = terms_[j];
    w += m.alpha[0] * ec + m.gamma[0] * es;
    dw += m.alpha[1] * ec + m.gamma[1] * es;
    d2w += m.alpha[2] * ec + m.gamma[2] * es;
  }
  const std::complex<double> forced = forced_ * clock_->Rotor(tau);
  *value = w + forced.real();
  *slope = dw - omega_ * forced.imag();
  *curvature = d2w - omega_ * omega_ * forced.real();
}

void Signal::PreciseValueSlopeCurvature(double t, double* value, double* slope,
                                        double* curvature) const {
  const double tau = t - t0_;
  // Beyond the span the anchor's linear part rounds above the plain sum.
  if (!anchored_ || !(tau >= 0.0 && tau <= clock_->AnchoredSpan())) {
    ValueSlopeCurvature(t, value, slope, curvature);
    return;
  }
  double w = anchor_ + anchor_slope_ * tau, dw = 0.0, d2w = 0.0;
  for (std::size_t j = 0; j < terms_.size(); ++j) {
    double ec, es, ec_second, es_second;
    clock_->EvaluateSecond(static_cast<int>(j), tau, &ec, &es, &ec_second, &es_second);
    const ModeTerms& m = terms_[j];
    w += m.alpha[0] * ec_second + m.gamma[0] * es_second;
    dw += m.alpha[1] * ec + m.gamma[1] * es;
    d2w += m.alpha[2] * ec + m.gamma[2] * es;
  }
  // P e^{iΩτ} = P (1 + iΩτ + E), its first two terms in the anchor.
  const std::complex<double> second = forced_ * clock_->RotorSecondIncrement(tau);
  const std::complex<double> forced = forced_ * std::complex<double>(1.0, omega_ * tau) + second;
  *value = w + second.real();
  *slope = dw - omega_ * forced.imag();
  *curvature = d2w - omega_ * omega_ * forced.real();
}

Signal Signal::Derivative(int order) const {
  Signal d = *this;
  for (std::size_t j = 0; j < d.terms_.size(); ++j) {
    const ModeBasis& mode = clock_->Modes()[j];
    double alpha = terms_[j].alpha[0], gamma = terms_[j].gamma[0];
    for (int k = 0; k < order; ++k) mode.Differentiate(&alpha, &gamma);
    d.terms_[j].Set(mode, alpha, gamma);
  }
  for (int k = 0; k < order; ++k) d.forced_ *= std::complex<double>(0.0, omega_);
  d.forced_magnitude_ = std::abs(d.forced_);
  if (order > 0) {
    d.constant_ = 0.0;
    d.anchored_ = false;
  }
  return d;
}

double Signal::DerivativeBound(int order, double t_from) const {
  double bounds[kMaxBoundOrder + 1];
  DerivativeBounds(t_from, order, bounds);
  return bounds[order];
}

void Signal::DerivativeBounds(double t_from, int max_order, double* bounds) const {
  if (max_order < 0 || max_order > kMaxBoundOrder) {
    throw std::out_of_range("Signal::DerivativeBounds: order must be in [0, 6]");
  }
  const double tau = t_from - t0_;
  double forced = forced_magnitude_;
  for (int k = 0; k <= max_order; ++k, forced *= omega_) bounds[k] = forced;
  bounds[0] += std::abs(constant_);
  for (std::size_t j = 0; j < terms_.size(); ++j) {
    const ModeBasis& mode = clock_->Modes()[j];
    double a = terms_[j].alpha[0], g = terms_[j].gamma[0];
    if (mode.lightly_damped) {
      const double ratio = g / mode.root;
      double envelope = std::sqrt(a * a + ratio * ratio);
      if (tau > 0) envelope *= std::exp(-mode.decay * tau);
      for (int k = 0; k <= max_order; ++k, envelope *= mode.modulus) bounds[k] += envelope;
      continue;
    }
    const ModeBasis::Decay decay = mode.DecayFrom(tau);  // shared by every order
    for (int k = 0; k <= max_order; ++k) {
      bounds[k] += mode.Envelope(a, g, decay);
      mode.Differentiate(&a, &g);
    }
  }
}

double Signal::Scale() const {
  double alpha = 0.0, gamma = 0.0;
  for (const ModeTerms& m : terms_) {
    alpha += std::abs(m.alpha[0]);
    gamma += std::abs(m.gamma[0]);
  }
  return alpha + gamma + forced_magnitude_ + std::abs(constant_);
}

Signal Signal::Negated() const {
  Signal n = *this;
  for (ModeTerms& m : n.terms_) {
    for (int k = 0; k < 3; ++k) {
      m.alpha[k] = -m.alpha[k];
      m.gamma[k] = -m.gamma[k];
    }
  }
  n.forced_ = -forced_;
  n.constant_ = -constant_;
  n.anchor_ = -anchor_;
  n.anchor_slope_ = -anchor_slope_;
  return n;
}

LinearFlow::LinearFlow(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                       const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing,
                       const Eigen::VectorXd& constant_force, double omega)
    : dof_(static_cast<int>(mass.rows())), omega_(omega) {
  const Eigen::Index n = dof_;
  if (n == 0) {
    // The stuck subsystem of a single mass: nothing moves.
    system_matrix_.resize(0, 0);
    basis_.resize(0, 0);
    inverse_basis_.resize(0, 0);
    shifted_blocks_.resize(2, 0);
    steady_forced_.resize(0);
    steady_constant_.resize(0);
    clock_ = ModeClock({}, omega);
    return;
  }
  const Eigen::MatrixXd m_inv_k = SolveMass(mass, stiffness);
  system_matrix_ = FirstOrderMatrix(m_inv_k, SolveMass(mass, damping));
  BlockDecomposition d;
  if (!IsClassicallyDamped(damping, m_inv_k)) {
    d = ComplexBlocks(system_matrix_);
  } else if (n < kModalFormFrom) {
    d = ClassicalBlocks(mass, damping, stiffness);
  } else {
    d = ModalBlocks(mass, damping, stiffness);
  }
  modal_ = d.modal_inverse.size() > 0;
  basis_ = std::move(d.basis);
  inverse_basis_ = modal_ ? std::move(d.modal_inverse) : DenseInverse(basis_);

  // b = (0, M⁻¹A), f = (0, M⁻¹f0) in modal coordinates.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n), b = SolveMass(mass, forcing);
  Eigen::VectorXd modal_b, modal_f;
  ToModal(zero, b, &modal_b);
  ToModal(zero, SolveMass(mass, constant_force), &modal_f);

  std::vector<ModeBasis> modes;
  shifted_blocks_.resize(2, 2 * n);
  steady_forced_.resize(2 * n);
  steady_constant_.resize(2 * n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Matrix2d block = d.blocks.block<2, 2>(0, 2 * j);
    const double a = -0.5 * block.trace();
    const double det = block.determinant();
    const double beta2 = det - a * a;
    modes.push_back(ModeBasis::Make(a, beta2));
    fastest_rate_ = std::max(fastest_rate_, std::abs(a) + std::sqrt(std::abs(beta2)));
    shifted_blocks_.block<2, 2>(0, 2 * j) = block + a * Eigen::Matrix2d::Identity();

    // Steady response of this block: (iΩ - B_j) Z_j = b_j, B_j z_c = -f_j.
    const Eigen::Matrix2cd resolvent =
        std::complex<double>(0.0, omega) * Eigen::Matrix2cd::Identity() -
        block.cast<std::complex<double>>();
    const std::complex<double> resolvent_det = resolvent.determinant();
    const Eigen::Vector2d bj = modal_b.segment<2>(2 * j);
    // |det B_j| / |det(iΩ − B_j)| is the mode's amplification of a forcing
    // over its static response; ε times it is the rounding left when a
    // start from rest cancels the steady part.
    const double amplification = std::max(omega * omega, std::abs(det)) / std::abs(resolvent_det);
    const bool forced = bj.norm() > 1e-14 * std::max(1.0, b.norm());
    if (forced && amplification > 1e12) {
      throw InvalidInput(fmt::format(
          "undamped mode with natural frequency {:.6g} is forced at omega = {:.6g}: no bounded "
          "steady response exists; add damping or change omega",
          std::sqrt(std::abs(det)), omega));
    }
    if (forced && amplification > kMaxAmplification) {
      throw InvalidInput(fmt::format(
          "the mode with natural frequency {:.9g} and damping rate {:.3g} is forced at omega = "
          "{:.9g}, so near resonance that it amplifies the forcing {:.3g} times (at most {:.0e}): "
          "a start from rest would cancel its steady response and lose {:.0f} of 16 digits; add "
          "damping or move omega",
          std::sqrt(std::abs(det)), std::abs(a), omega, amplification, kMaxAmplification,
          std::log10(amplification)));
    }
    if (amplification > 1e12) {
      steady_forced_.segment<2>(2 * j).setZero();
    } else {
      steady_forced_.segment<2>(2 * j) = resolvent.inverse() * bj.cast<std::complex<double>>();
    }
    steady_constant_.segment<2>(2 * j) = -block.inverse() * modal_f.segment<2>(2 * j);
  }
  clock_ = ModeClock(std::move(modes), omega);
}

double LinearFlow::ShortestPeriod() const {
  const double two_pi = 2.0 * std::numbers::pi;
  return fastest_rate_ > 0 ? std::min(two_pi / omega_, two_pi / fastest_rate_) : two_pi / omega_;
}

Eigen::VectorXd LinearFlow::Transient(double t, const Eigen::VectorXd& x,
                                      const Eigen::VectorXd& v) const {
  Eigen::VectorXd z;
  Transient(t, x, v, &z);
  return z;
}

// The scratch vectors below are per thread (flows are shared by the
// threads of a sweep) and keep their storage between calls: the simulator
// calls these once or twice per impact, where a malloc/free pair per
// temporary was ~14 % of its instructions (docs/performance.md).
void LinearFlow::Transient(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                           Eigen::VectorXd* z) const {
  const std::complex<double> rotor = ForcingRotor(omega_, t);
  ToModal(x, v, z);
  *z -= (steady_forced_ * rotor).real();
  *z -= steady_constant_;
}

void LinearFlow::State(double t0, const Eigen::VectorXd& z0, double t, Eigen::VectorXd* x,
                       Eigen::VectorXd* v) const {
  thread_local Eigen::VectorXd z;
  const Eigen::Index n = dof_;
  const double tau = t - t0;
  const std::complex<double> rotor = ForcingRotor(omega_, t);
  z = (steady_forced_ * rotor).real() + steady_constant_;
  for (Eigen::Index j = 0; j < n; ++j) {
    double ec, es;
    clock_.Evaluate(static_cast<int>(j), tau, &ec, &es);
    const Eigen::Vector2d zj = z0.segment<2>(2 * j);
    z.segment<2>(2 * j) += ec * zj + es * (shifted_blocks_.block<2, 2>(0, 2 * j) * zj);
  }
  FromModal(z, x, v);
}

void LinearFlow::StateFrom(double t0, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0,
                           const Eigen::VectorXd& z0, double t, Eigen::VectorXd* x,
                           Eigen::VectorXd* v) const {
  thread_local Eigen::VectorXd dz, dx, dv;
  const Eigen::Index n = dof_;
  const double tau = t - t0;
  // y(t) − y(t0) = V [(e^{Bτ} − I) z0 + Re(Z e^{iΩt0} (e^{iΩτ} − 1))], and
  // e^{iΩt0} (e^{iΩτ} − 1) = −e^{iΩt} conj(e^{iΩτ} − 1): the rotor at t,
  // which the next flight's Transient asks for too (ForcingRotor keeps one).
  const std::complex<double> forced_increment =
      -ForcingRotor(omega_, t) * std::conj(clock_.RotorIncrement(tau));
  dz = (steady_forced_ * forced_increment).real();
  for (Eigen::Index j = 0; j < n; ++j) {
    double ec, es, ec_increment;
    clock_.Evaluate(static_cast<int>(j), tau, &ec, &es, &ec_increment);
    const Eigen::Vector2d zj = z0.segment<2>(2 * j);
    dz.segment<2>(2 * j) += ec_increment * zj + es * (shifted_blocks_.block<2, 2>(0, 2 * j) * zj);
  }
  FromModal(dz, &dx, &dv);
  *x = x0 + dx;
  *v = v0 + dv;
}

void LinearFlow::SteadyState(double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const {
  State(t, Eigen::VectorXd::Zero(2 * dof_), t, x, v);
}

PreparedOutput LinearFlow::Prepare(const LinearOutput& output) const {
  const Eigen::Index n = dof_;
  PreparedOutput p;
  if (modal_) {  // l V = (l_x φ_j, l_v φ_j) per mode
    p.modal_weights.resize(2 * n);
    p.modal_weights(Eigen::seq(0, 2 * n - 2, 2)) = output.wx * basis_;
    p.modal_weights(Eigen::seq(1, 2 * n - 1, 2)) = output.wv * basis_;
  } else {
    Eigen::RowVectorXd l(2 * n);
    l << output.wx, output.wv;
    p.modal_weights = l * basis_;
  }
  p.forced = (p.modal_weights.cast<std::complex<double>>() * steady_forced_).value() +
             output.cos_amplitude;
  p.constant = p.modal_weights.dot(steady_constant_) + output.offset;
  return p;
}

Signal LinearFlow::Output(const PreparedOutput& output, double t0,
                          const Eigen::VectorXd& z0) const {
  Signal s;
  Output(output, t0, z0, &s);
  return s;
}

void LinearFlow::Output(const PreparedOutput& output, double t0, const Eigen::VectorXd& z0,
                        Signal* signal) const {
  const Eigen::Index n = dof_;
  signal->clock_ = &clock_;
  signal->omega_ = omega_;
  signal->t0_ = t0;
  signal->terms_.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Vector2d c = output.modal_weights.segment<2>(2 * j).transpose();
    const Eigen::Vector2d zj = z0.segment<2>(2 * j);
    signal->terms_[j].Set(clock_.Modes()[j], c.dot(zj),
                          c.dot(shifted_blocks_.block<2, 2>(0, 2 * j) * zj));
  }
  signal->forced_ = output.forced * ForcingRotor(omega_, t0);
  signal->forced_magnitude_ = std::abs(signal->forced_);
  signal->constant_ = output.constant;
  signal->anchored_ = false;
}

Eigen::MatrixXd LinearFlow::Transition(double tau) const {
  const Eigen::Index n = dof_;
  Eigen::MatrixXd modal = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (Eigen::Index j = 0; j < n; ++j) {
    double ec, es;
    clock_.Evaluate(static_cast<int>(j), tau, &ec, &es);
    modal.block<2, 2>(2 * j, 2 * j) =
        ec * Eigen::Matrix2d::Identity() + es * shifted_blocks_.block<2, 2>(0, 2 * j);
  }
  // W = V⁻¹ has V's pattern transposed: rows 2j and 2j + 1 hold φ_jᵀ M.
  return DenseBasis(basis_) * modal * DenseBasis(inverse_basis_.transpose()).transpose();
}

Eigen::MatrixXd LinearFlow::DenseBasis(const Eigen::MatrixXd& half) const {
  if (!modal_) return half;
  const Eigen::Index n = dof_;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  dense(Eigen::seq(0, n - 1), Eigen::seq(0, 2 * n - 2, 2)) = half;
  dense(Eigen::seq(n, 2 * n - 1), Eigen::seq(1, 2 * n - 1, 2)) = half;
  return dense;
}

void LinearFlow::ToModal(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                         Eigen::VectorXd* z) const {
  const Eigen::Index n = dof_;
  z->resize(2 * n);
  if (modal_) {  // z = (Φᵀ M x, Φᵀ M v), interleaved
    thread_local Eigen::VectorXd q, p;
    q.resize(n);
    p.resize(n);
    Multiply(inverse_basis_, x, &q);
    Multiply(inverse_basis_, v, &p);
    (*z)(Eigen::seq(0, 2 * n - 2, 2)) = q;
    (*z)(Eigen::seq(1, 2 * n - 1, 2)) = p;
    return;
  }
  thread_local Eigen::VectorXd y;
  y.resize(2 * n);
  y << x, v;
  Multiply(inverse_basis_, y, z);
}

void LinearFlow::FromModal(const Eigen::VectorXd& z, Eigen::VectorXd* x, Eigen::VectorXd* v) const {
  const Eigen::Index n = dof_;
  if (modal_) {  // x = Φ q, v = Φ q'
    thread_local Eigen::VectorXd q, p;
    q = z(Eigen::seq(0, 2 * n - 2, 2));
    p = z(Eigen::seq(1, 2 * n - 1, 2));
    x->resize(n);
    v->resize(n);
    Multiply(basis_, q, x);
    Multiply(basis_, p, v);
    return;
  }
  thread_local Eigen::VectorXd y;
  y.resize(2 * n);
  Multiply(basis_, z, &y);
  *x = y.head(n);
  *v = y.tail(n);
}

}  // namespace impactkit
