#pragma once
/// \file modal.hpp
/// Modal data of the non-impacting system (the paper's §2.1): natural
/// frequencies, mode shapes, modal damping ratios.

#include <Eigen/Dense>

#include "impactkit/model/system.hpp"

namespace impactkit {

struct ModalData {
  /// For a uniform chain the eigenvalues λ_j of E (ω_j² = λ_j k / m);
  /// otherwise ω_j². Ascending.
  Eigen::VectorXd eigenvalues;
  Eigen::VectorXd natural_frequencies;  ///< ω_j
  /// Modal damping ratios ζ_j = (φ_jᵀ C φ_j) / (2 ω_j), φ_j mass-normalised
  /// (for the chain the paper's ζ_j = (c/2) sqrt(λ_j / (k m))); with
  /// non-proportional damping only the diagonal of the projected C, an
  /// approximation flagged by `proportional` = false.
  Eigen::VectorXd damping_ratios;
  /// Columns ξ_j of unit Euclidean norm, sign chosen so that the last
  /// component is positive (the paper's convention).
  Eigen::MatrixXd mode_shapes;
  bool proportional = true;  ///< C is diagonalised by the normal modes
};

/// Throws InvalidInput for an invalid system.
ModalData ComputeModalData(const System& system);

}  // namespace impactkit
