#include "continuation/defining_function.hpp"

#include <algorithm>
#include <cmath>

namespace impactkit::detail {

namespace {

Eigen::MatrixXd Shifted(const Eigen::MatrixXd& dp, double lambda) {
  return dp - lambda * Eigen::MatrixXd::Identity(dp.rows(), dp.cols());
}

}  // namespace

SigmaBorders MultiplierBorders(const Eigen::MatrixXd& dp, double lambda) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Shifted(dp, lambda),
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Index last = dp.rows() - 1;
  return {svd.matrixU().col(last), svd.matrixV().col(last)};
}

double MultiplierFunction(const Eigen::MatrixXd& dp, double lambda, const SigmaBorders& borders) {
  const Eigen::Index n = dp.rows();
  Eigen::MatrixXd bordered = Eigen::MatrixXd::Zero(n + 1, n + 1);
  bordered.topLeftCorner(n, n) = Shifted(dp, lambda);
  bordered.topRightCorner(n, 1) = borders.b;
  bordered.bottomLeftCorner(1, n) = borders.c.transpose();
  const double sigma = bordered.fullPivLu().solve(Eigen::VectorXd::Unit(n + 1, n))(n);
  return sigma / (1.0 + dp.norm());
}

bool SameImpacts(const Eigen::VectorXd& change, const Eigen::VectorXd& predicted) {
  // U carries the event times' rounding, ~1e-12 (impact_map.hpp).
  constexpr double kRelative = 10.0, kRounding = 1e-10;
  return (change - predicted).lpNorm<Eigen::Infinity>() <=
         kRelative * predicted.lpNorm<Eigen::Infinity>() + kRounding;
}

bool CentralDifferenceGradient(const Rows& rows, const Eigen::VectorXd& x, double relative_step,
                               Eigen::MatrixXd* gradient) {
  Eigen::VectorXd g0;
  if (!rows(x, &g0)) return false;
  gradient->resize(g0.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double h = relative_step * std::max(1.0, std::abs(x(i)));
    Eigen::VectorXd plus = x, minus = x, g_plus, g_minus;
    plus(i) += h;
    minus(i) -= h;
    const bool up = rows(plus, &g_plus), down = rows(minus, &g_minus);
    if (!up && !down) return false;
    const Eigen::VectorXd& high = up ? g_plus : g0;
    const Eigen::VectorXd& low = down ? g_minus : g0;
    gradient->col(i) = (high - low) / ((up ? h : 0.0) + (down ? h : 0.0));
  }
  return gradient->allFinite();
}

}  // namespace impactkit::detail
