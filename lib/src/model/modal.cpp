#include "impactkit/model/modal.hpp"

#include <cmath>

namespace impactkit {

ModalData ComputeModalData(const System& s) {
  ValidateParameters(s);  // the modes exist at a resonance too
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(s.stiffness, s.mass);
  const Eigen::MatrixXd& phi = modes.eigenvectors();  // mass-normalised
  const Eigen::MatrixXd modal_damping = phi.transpose() * s.damping * phi;
  ModalData d;
  d.natural_frequencies = modes.eigenvalues().cwiseSqrt();
  d.eigenvalues = modes.eigenvalues();
  if (s.chain) d.eigenvalues *= s.chain->mass / s.chain->stiffness;
  d.damping_ratios = modal_damping.diagonal().cwiseQuotient(2.0 * d.natural_frequencies);
  const double off_diagonal =
      (modal_damping - Eigen::MatrixXd(modal_damping.diagonal().asDiagonal())).norm();
  d.proportional = off_diagonal <= 1e-10 * std::max(1.0, modal_damping.norm());
  d.mode_shapes = phi;
  for (Eigen::Index j = 0; j < phi.cols(); ++j) {
    d.mode_shapes.col(j).normalize();
    if (d.mode_shapes(phi.rows() - 1, j) < 0) d.mode_shapes.col(j) *= -1.0;
  }
  return d;
}

}  // namespace impactkit
