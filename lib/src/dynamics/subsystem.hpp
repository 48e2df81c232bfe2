#pragma once
/// \file subsystem.hpp
/// The stuck subsystem: the contact DOF removed and held at the stop.

#include <Eigen/Dense>

namespace impactkit {

/// The entries of `full` other than `removed`.
Eigen::VectorXd WithoutIndex(const Eigen::VectorXd& full, int removed);

/// Rows and columns of `full` other than `removed`.
Eigen::MatrixXd WithoutIndex(const Eigen::MatrixXd& full, int removed);

/// Rows of `full` other than `removed` (all columns).
Eigen::MatrixXd WithoutRow(const Eigen::MatrixXd& full, int removed);

/// The full vector: `reduced` with `value` inserted at index `inserted`.
Eigen::VectorXd EmbedAtStop(const Eigen::VectorXd& reduced, int inserted, double value);

/// The full matrix: `reduced` with a zero row inserted at `inserted` (the
/// derivative of a coordinate the stop holds fixed).
Eigen::MatrixXd WithZeroRow(const Eigen::MatrixXd& reduced, int inserted);

}  // namespace impactkit
