#pragma once
/// \file modal.hpp
/// Modal data of the non-impacting system (the paper's §2.1): natural
/// frequencies, mode shapes, modal damping ratios.

#include <Eigen/Dense>

#include "impactkit/model.hpp"

namespace impactkit {

struct ModalData {
  /// For a uniform chain the eigenvalues λ_j of E (ω_j² = λ_j k / m);
  /// otherwise ω_j². Ascending.
  Eigen::VectorXd eigenvalues;
  Eigen::VectorXd natural_frequencies;  ///< ω_j
  /// ζ_j = ξ_jᵀ... modal damping ratio, (φ_jᵀ C φ_j) / (2 ω_j) with φ_j
  /// mass-normalised; for non-proportional damping the ratio of the
  /// projected damping (an approximation, flagged by `proportional`).
  Eigen::VectorXd damping_ratios;
  /// Columns ξ_j of unit Euclidean norm, sign chosen so that the last
  /// component is positive (the paper's convention).
  Eigen::MatrixXd mode_shapes;
  bool proportional = true;  ///< C is diagonalised by the normal modes
};

/// Throws InvalidInput for an invalid system.
ModalData ComputeModalData(const System& system);

}  // namespace impactkit
