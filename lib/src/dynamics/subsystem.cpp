#include "dynamics/subsystem.hpp"

namespace impactkit {

Eigen::VectorXd WithoutIndex(const Eigen::VectorXd& full, int removed) {
  const Eigen::Index n = full.size();
  Eigen::VectorXd reduced(n - 1);
  reduced << full.head(removed), full.tail(n - 1 - removed);
  return reduced;
}

Eigen::MatrixXd WithoutIndex(const Eigen::MatrixXd& full, int removed) {
  const Eigen::Index n = full.rows(), after = n - 1 - removed;
  Eigen::MatrixXd reduced(n - 1, n - 1);
  reduced << full.topLeftCorner(removed, removed), full.topRightCorner(removed, after),
      full.bottomLeftCorner(after, removed), full.bottomRightCorner(after, after);
  return reduced;
}

Eigen::VectorXd EmbedAtStop(const Eigen::VectorXd& reduced, int inserted, double value) {
  const Eigen::Index n = reduced.size() + 1;
  Eigen::VectorXd full(n);
  full << reduced.head(inserted), value, reduced.tail(n - 1 - inserted);
  return full;
}

Eigen::MatrixXd WithZeroRow(const Eigen::MatrixXd& reduced, int inserted) {
  const Eigen::Index n = reduced.rows() + 1;
  Eigen::MatrixXd full(n, reduced.cols());
  full << reduced.topRows(inserted), Eigen::RowVectorXd::Zero(reduced.cols()),
      reduced.bottomRows(n - 1 - inserted);
  return full;
}

Eigen::MatrixXd WithoutRow(const Eigen::MatrixXd& full, int removed) {
  const Eigen::Index n = full.rows();
  Eigen::MatrixXd reduced(n - 1, full.cols());
  reduced << full.topRows(removed), full.bottomRows(n - 1 - removed);
  return reduced;
}

}  // namespace impactkit
