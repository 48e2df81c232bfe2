#pragma once
/// \file sorted_eigenvalues.hpp
/// A matrix's eigenvalues by Eigen's general solver, largest modulus first
/// (ties: larger imaginary part first), as tests compare multipliers.

#include <Eigen/Dense>
#include <algorithm>
#include <complex>

namespace impactkit::testing {

inline Eigen::VectorXcd SortedEigenvalues(const Eigen::MatrixXd& matrix) {
  Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(matrix).eigenvalues();
  std::sort(lambda.begin(), lambda.end(), [](const auto& a, const auto& b) {
    return std::abs(a) != std::abs(b) ? std::abs(a) > std::abs(b) : a.imag() > b.imag();
  });
  return lambda;
}

}  // namespace impactkit::testing
