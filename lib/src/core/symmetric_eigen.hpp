#pragma once
/// \file symmetric_eigen.hpp
/// Symmetric matrices of a system (M, C, K) by their structure: a chain's M
/// is diagonal and its K and C tridiagonal, and for long chains (N up to
/// 1000) every dense O(N³) step — a factorisation, an inverse, a product,
/// an eigen-decomposition — costs seconds where the structure gives the
/// same result in O(N²) (docs/performance.md, "Long chains"). Dense
/// matrices take Eigen's dense routes.

#include <Eigen/Dense>

namespace impactkit::detail {

bool IsDiagonal(const Eigen::MatrixXd& a);
/// Zero beyond the first sub- and superdiagonal.
bool IsTridiagonal(const Eigen::MatrixXd& a);

/// Whether every eigenvalue of the symmetric `a` exceeds `bound`: a Sturm
/// count (the signs of the pivots of a − bound I, O(N)) for a tridiagonal
/// `a`, its eigenvalues otherwise.
bool EigenvaluesExceed(const Eigen::MatrixXd& a, double bound);

/// The inverse of a symmetric positive definite `a`: 1 / a_ii for a
/// diagonal one (exactly what an LU gives, without its O(N³)).
Eigen::MatrixXd SymmetricInverse(const Eigen::MatrixXd& a);

/// K φ = λ M φ for symmetric K and positive definite M: λ ascending, and
/// (where asked) Φ with Φᵀ M Φ = I.
struct GeneralizedModes {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;  ///< Φ (empty unless asked for)
};

/// For a diagonal M and a tridiagonal K the problem is the tridiagonal
/// T = M^-1/2 K M^-1/2: eigenvalues by implicit QR without vectors, each
/// vector by inverse iteration (O(N) apiece, O(N²) in all); otherwise
/// Eigen's GeneralizedSelfAdjointEigenSolver (O(N³)). Written here because
/// Eigen has no tridiagonal eigenvector routine (its solver accumulates the
/// QR rotations, O(N³)) and LAPACK's (dstein, dstemr) is not in the
/// project's stack.
GeneralizedModes SolveGeneralized(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m,
                                  bool with_vectors);

}  // namespace impactkit::detail
