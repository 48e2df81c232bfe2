#include "core/symmetric_eigen.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace impactkit::detail {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
/// Eigenvalues closer than this times ‖T‖ form a cluster whose vectors are
/// orthogonalised against one another. Inverse iteration alone leaves a
/// vector off by ~ε‖T‖ / gap towards each neighbour: below 2.2e-11 outside
/// a cluster. (LAPACK's dstein takes 1e-3, which makes the whole spectrum
/// of a long chain one cluster and the orthogonalisation O(N³).)
constexpr double kClusterGap = 1e-5;
/// Inverse iterations per vector: with λ good to ε‖T‖ each one shrinks the
/// other modes' share by ε‖T‖ / gap (<= 2.2e-11 outside a cluster), so two
/// leave it at rounding; the second also repairs a start vector that
/// happened to be poor in the wanted mode.
constexpr int kIterations = 2;

/// A symmetric tridiagonal matrix: diagonal d, off-diagonal e.
struct Tridiagonal {
  Eigen::VectorXd d, e;

  double Norm() const {  // ‖T‖∞, a bound on the spectral radius
    double norm = 0.0;
    for (Eigen::Index i = 0; i < d.size(); ++i) {
      const double left = i > 0 ? std::abs(e(i - 1)) : 0.0;
      const double right = i + 1 < d.size() ? std::abs(e(i)) : 0.0;
      norm = std::max(norm, std::abs(d(i)) + left + right);
    }
    return norm;
  }
};

/// M^-1/2 K M^-1/2 for a diagonal M and a tridiagonal K.
Tridiagonal Scaled(const Eigen::MatrixXd& k, const Eigen::VectorXd& inverse_root_mass) {
  const Eigen::Index n = k.rows();
  Tridiagonal t{k.diagonal().cwiseProduct(inverse_root_mass.cwiseAbs2()),
                Eigen::VectorXd(std::max<Eigen::Index>(n - 1, 0))};
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    t.e(i) = k(i + 1, i) * inverse_root_mass(i) * inverse_root_mass(i + 1);
  }
  return t;
}

/// T − λI = P L U by Gaussian elimination with row swaps (U has two
/// superdiagonals), pivots of magnitude below `floor` raised to it: T − λI
/// is singular to rounding at an eigenvalue, and the raised pivot is what
/// makes a solve amplify the eigenvector (LAPACK's dlagtf/dlagts).
class ShiftedLu {
 public:
  ShiftedLu(const Tridiagonal& t, double lambda, double floor) {
    const Eigen::Index n = t.d.size();
    u0_.resize(n);
    u1_.assign(n, 0.0);
    u2_.assign(n, 0.0);
    multiplier_.assign(n, 0.0);
    swapped_.assign(n, false);
    double diag = t.d(0) - lambda, super = n > 1 ? t.e(0) : 0.0;  // the pivot row
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      const double below = t.e(i), next_diag = t.d(i + 1) - lambda;
      const double next_super = i + 2 < n ? t.e(i + 1) : 0.0;
      swapped_[i] = std::abs(below) > std::abs(diag);
      if (swapped_[i]) {
        u0_[i] = below;
        u1_[i] = next_diag;
        u2_[i] = next_super;
        multiplier_[i] = diag / below;
        diag = super - multiplier_[i] * next_diag;
        super = -multiplier_[i] * next_super;
      } else {
        u0_[i] = Floored(diag, floor);
        u1_[i] = super;
        multiplier_[i] = below / u0_[i];
        diag = next_diag - multiplier_[i] * super;
        super = next_super;
      }
    }
    u0_[n - 1] = Floored(diag, floor);
    // Back substitution is a chain of dependent steps: multiplying by the
    // pivots' inverses keeps a division's latency out of each.
    for (double& pivot : u0_) pivot = 1.0 / pivot;
  }

  /// b := (T − λI)⁻¹ b.
  void Solve(Eigen::VectorXd* b) const {
    Eigen::VectorXd& x = *b;
    const Eigen::Index n = x.size();
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      if (swapped_[i]) std::swap(x(i), x(i + 1));
      x(i + 1) -= multiplier_[i] * x(i);
    }
    for (Eigen::Index i = n - 1; i >= 0; --i) {
      double r = x(i);
      if (i + 1 < n) r -= u1_[i] * x(i + 1);
      if (i + 2 < n) r -= u2_[i] * x(i + 2);
      x(i) = r * u0_[i];
    }
  }

 private:
  static double Floored(double pivot, double floor) {
    return std::abs(pivot) >= floor ? pivot : (pivot < 0 ? -floor : floor);
  }

  std::vector<double> u0_, u1_, u2_, multiplier_;  ///< u0_ holds 1 / pivot
  std::vector<bool> swapped_;
};

/// A fixed start vector with no structure a chain's modes could be
/// orthogonal to (a linear congruential sequence: the same on every
/// platform, so results are reproducible).
Eigen::VectorXd StartVector(Eigen::Index n, std::uint64_t seed) {
  Eigen::VectorXd x(n);
  std::uint64_t state = seed * 6364136223846793005ULL + 1442695040888963407ULL;
  for (Eigen::Index i = 0; i < n; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    x(i) = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
  }
  return x;
}

/// Eigenvectors (columns) of T for its ascending eigenvalues.
Eigen::MatrixXd InverseIteration(const Tridiagonal& t, const Eigen::VectorXd& values) {
  const Eigen::Index n = t.d.size();
  const double norm = std::max(t.Norm(), std::numeric_limits<double>::min());
  Eigen::MatrixXd q(n, n);
  Eigen::Index cluster = 0;  // first column of the current cluster
  for (Eigen::Index j = 0; j < n; ++j) {
    if (j > 0 && values(j) - values(j - 1) >= kClusterGap * norm) cluster = j;
    const ShiftedLu lu(t, values(j), kEpsilon * norm);
    Eigen::VectorXd x = StartVector(n, static_cast<std::uint64_t>(j));
    for (int iteration = 0; iteration < kIterations; ++iteration) {
      lu.Solve(&x);
      for (Eigen::Index i = cluster; i < j; ++i) x -= q.col(i).dot(x) * q.col(i);
      x.normalize();
    }
    q.col(j) = x;
  }
  return q;
}

}  // namespace

bool IsDiagonal(const Eigen::MatrixXd& a) {
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      if (i != j && a(i, j) != 0.0) return false;
    }
  }
  return true;
}

bool IsTridiagonal(const Eigen::MatrixXd& a) {
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      if ((i > j + 1 || j > i + 1) && a(i, j) != 0.0) return false;
    }
  }
  return true;
}

bool EigenvaluesExceed(const Eigen::MatrixXd& a, double bound) {
  if (!IsTridiagonal(a)) {
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly)
               .eigenvalues()
               .minCoeff() > bound;
  }
  // Sylvester: a − bound I is positive definite iff every pivot of its
  // LDLᵀ is positive.
  double pivot = 1.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double coupling = i > 0 ? a(i, i - 1) * a(i, i - 1) / pivot : 0.0;
    pivot = a(i, i) - bound - coupling;
    if (!(pivot > 0)) return false;
  }
  return true;
}

Eigen::MatrixXd SymmetricInverse(const Eigen::MatrixXd& a) {
  if (!IsDiagonal(a)) return a.inverse();
  return a.diagonal().cwiseInverse().asDiagonal();
}

GeneralizedModes SolveGeneralized(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                                  bool with_vectors) {
  const int options = with_vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly;
  if (!IsDiagonal(m) || !IsTridiagonal(k) || k.rows() == 0) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(k, m, options);
    return {modes.eigenvalues(), with_vectors ? modes.eigenvectors() : Eigen::MatrixXd()};
  }
  const Eigen::VectorXd inverse_root_mass = m.diagonal().cwiseSqrt().cwiseInverse();
  const Tridiagonal t = Scaled(k, inverse_root_mass);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> values;
  values.computeFromTridiagonal(t.d, t.e, Eigen::EigenvaluesOnly);
  if (!with_vectors) return {values.eigenvalues(), Eigen::MatrixXd()};
  // Φ = M^-1/2 Q, Q the orthonormal eigenvectors of T.
  return {values.eigenvalues(),
          inverse_root_mass.asDiagonal() * InverseIteration(t, values.eigenvalues())};
}

}  // namespace impactkit::detail
