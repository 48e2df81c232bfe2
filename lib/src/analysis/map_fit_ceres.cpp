/// The only translation unit of the map fit that includes Ceres.
#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "impactkit/analysis/map_fit.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {
namespace {

/// F(x; s, d, λ) for doubles and Ceres jets. Under the root the argument is
/// kept above 1e-300: a point exactly at the break would give an infinite
/// derivative (the map's own), which Ceres cannot use.
template <typename T>
T Evaluate(const T* p, double x) {
  const T& s = p[0];
  const T& d = p[1];
  const T& lambda = p[2];
  if (x <= d) {
    using std::max;
    using std::sqrt;
    return s * sqrt(max(d - x, T(1e-300))) + lambda * x;
  }
  return lambda * x;
}

struct PointResidual {
  double x, y;
  template <typename T>
  bool operator()(const T* p, T* residual) const {
    residual[0] = T(y) - Evaluate(p, x);
    return true;
  }
};

double SumOfSquares(const double* p, const std::vector<double>& x, const std::vector<double>& y) {
  double sum = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double r = y[j] - Evaluate(p, x[j]);
    sum += r * r;
  }
  return sum;
}

/// For fixed d the model is linear in (s, λ): the least-squares pair.
Eigen::Vector2d LinearPart(double d, const std::vector<double>& x, const std::vector<double>& y) {
  Eigen::MatrixXd a(x.size(), 2);
  Eigen::VectorXd b(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) {
    a(j, 0) = x[j] <= d ? std::sqrt(d - x[j]) : 0.0;
    a(j, 1) = x[j];
    b(j) = y[j];
  }
  return a.colPivHouseholderQr().solve(b);
}

}  // namespace

double SqrtMap(const SqrtMapParameters& parameters, double x) {
  const double p[3] = {parameters.s, parameters.d, parameters.lambda};
  return Evaluate(p, x);
}

ReturnMapPoints LowVelocityReturnMap(const std::vector<double>& velocities, double bound) {
  if (!(bound > 0.0))
    throw InvalidInput(fmt::format("the velocity bound must be > 0, got {}", bound));
  ReturnMapPoints points;
  double previous = -1.0;
  for (double v : velocities) {
    if (!(v < bound)) continue;
    if (previous >= 0.0) {
      points.from.push_back(previous);
      points.to.push_back(v);
    }
    previous = v;
  }
  return points;
}

bool MapFitOptions::IsValid(std::string* error) const {
  if (start_candidates < 2) {
    *error = fmt::format("start_candidates must be >= 2, got {}", start_candidates);
    return false;
  }
  if (max_iterations < 1) {
    *error = fmt::format("max_iterations must be >= 1, got {}", max_iterations);
    return false;
  }
  return true;
}

std::string MapFitSummary::BriefReport() const {
  return fmt::format(
      "{}: s = {:.6g} ± {:.2g}, d = {:.6g} ± {:.2g}, lambda = {:.6g} ± {:.2g}; "
      "rms residual {:.3g} over {} points ({} on the root branch)",
      Describe(termination), parameters.s, standard_error.s, parameters.d, standard_error.d,
      parameters.lambda, standard_error.lambda, rms_residual, points, points_on_root_branch);
}

MapFitSummary FitSqrtMap(const std::vector<double>& x, const std::vector<double>& y,
                         const MapFitOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  if (x.size() != y.size()) {
    throw InvalidInput(fmt::format("x and y differ in length ({} and {})", x.size(), y.size()));
  }
  if (x.size() < 4) {
    throw InvalidInput(fmt::format("the fit needs at least 4 points, got {}", x.size()));
  }
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (!std::isfinite(x[j]) || !std::isfinite(y[j])) {
      throw InvalidInput(fmt::format("point {} is not finite", j));
    }
  }
  const auto [x_min, x_max] = std::minmax_element(x.begin(), x.end());

  // The start: the best d on an even grid with its linear (s, λ).
  double p[3] = {0.0, 0.0, 0.0};
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < options.start_candidates; ++k) {
    const double d = *x_min + (*x_max - *x_min) * k / (options.start_candidates - 1);
    const Eigen::Vector2d linear = LinearPart(d, x, y);
    const double trial[3] = {linear(0), d, linear(1)};
    const double cost = SumOfSquares(trial, x, y);
    if (cost < best) best = cost, std::copy(trial, trial + 3, p);
  }

  ceres::Problem problem;
  for (std::size_t j = 0; j < x.size(); ++j) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PointResidual, 1, 3>(new PointResidual{x[j], y[j]}),
        nullptr, p);
  }
  ceres::Solver::Options solver_options;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  MapFitSummary summary;
  summary.parameters = {p[0], p[1], p[2]};
  summary.points = static_cast<int>(x.size());
  summary.points_on_root_branch =
      static_cast<int>(std::count_if(x.begin(), x.end(), [&](double v) { return v <= p[1]; }));
  summary.iterations = static_cast<int>(ceres_summary.iterations.size());
  const double sum_of_squares = SumOfSquares(p, x, y);
  summary.rms_residual = std::sqrt(sum_of_squares / summary.points);
  summary.sigma = std::sqrt(sum_of_squares / (summary.points - 3));
  summary.termination =
      ceres_summary.termination_type == ceres::CONVERGENCE      ? Termination::kConverged
      : ceres_summary.termination_type == ceres::NO_CONVERGENCE ? Termination::kNoConvergence
                                                                : Termination::kFailure;
  summary.message = ceres_summary.message;

  if (summary.points_on_root_branch < 2) {
    // With (almost) no point below d, s and d are not determined.
    summary.termination = Termination::kFailure;
    summary.message = fmt::format("{} of {} points lie on the root branch: d is not determined",
                                  summary.points_on_root_branch, summary.points);
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return summary;
  }

  // Covariance of the parameters: Ceres gives (JᵀJ)⁻¹ for the unit-weight
  // residuals; the data's own scatter σ² scales it.
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{p, p}};
  double c[9];
  if (covariance.Compute(blocks, &problem) && covariance.GetCovarianceBlock(p, p, c)) {
    summary.covariance = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(c) *
                         (summary.sigma * summary.sigma);
    const Eigen::Vector3d se = summary.covariance.diagonal().cwiseSqrt();
    summary.standard_error = {se(0), se(1), se(2)};
  } else if (summary.termination == Termination::kConverged) {
    summary.termination = Termination::kFailure;
    summary.message = "the covariance is rank deficient: a parameter is not determined by the data";
  }
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return summary;
}

}  // namespace impactkit
