#pragma once
/// \file map_fit.hpp
/// Low-velocity return maps and the one-dimensional square-root map of
/// Wagg & Bishop's Eq. 18 (after Budd & Dux 1994b), fitted by least squares.
///
///     X_{n+1} = s √(d - X_n) + λ X_n     for X_n <= d
///     X_{n+1} = λ X_n                    for X_n >  d
///
/// (the paper's text lost the minus sign under the root; this is the form
/// that is continuous at X_n = d with an infinite slope there, "a linear
/// part and a parabolic part joined at X_n = d by a nonsmooth
/// discontinuity", and that gives its Fig. 11 for s = d = 1, λ = 0.2).
///
/// The fit minimises Σ (y_j - F(x_j; s, d, λ))². F is linear in s and λ for
/// fixed d, so a scan over d with the linear least-squares (s, λ) picks the
/// start; Levenberg–Marquardt (Ceres) then refines all three. Uncertainties
/// are the standard errors from the covariance σ² (JᵀJ)⁻¹ at the optimum
/// (ceres::Covariance), with σ² = Σ r² / (n - 3) the residual variance.
/// Ceres stays behind this header (map_fit_ceres.cpp).

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "impactkit/core/termination.hpp"

namespace impactkit {

struct SqrtMapParameters {
  double s = 1.0;       ///< scale of the square-root branch
  double d = 1.0;       ///< the break point (the paper's bifurcation parameter)
  double lambda = 0.2;  ///< slope of the linear part
};

/// Eq. 18 at x.
double SqrtMap(const SqrtMapParameters& parameters, double x);

/// Pairs (v(j), v(j+1)) of the low-velocity return map: the subsequence of
/// `velocities` below `bound` (in the given order), each member paired with
/// the next member of that subsequence (Budd & Dux's map of low-velocity
/// impacts; the paper's Fig. 10). Throws InvalidInput for bound <= 0.
struct ReturnMapPoints {
  std::vector<double> from;  ///< v(j)
  std::vector<double> to;    ///< v(j+1)
};
ReturnMapPoints LowVelocityReturnMap(const std::vector<double>& velocities, double bound);

struct MapFitOptions {
  /// Values of d tried for the start, evenly spread over [min x, max x] (>= 2).
  int start_candidates = 200;
  /// Levenberg–Marquardt iterations (>= 1).
  int max_iterations = 200;
  bool IsValid(std::string* error) const;
};

/// Summary::iterations counts Levenberg–Marquardt iterations.
struct MapFitSummary : Summary {
  SqrtMapParameters parameters;      ///< the fit
  SqrtMapParameters standard_error;  ///< one-sigma uncertainties of each parameter
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of (s, d, λ)
  double rms_residual = 0.0;                             ///< √(Σ r² / n)
  double sigma = 0.0;  ///< √(Σ r² / (n - 3)), the residual scale
  int points = 0;
  int points_on_root_branch = 0;  ///< x <= d at the fit
  std::string BriefReport() const;
};

/// Fits Eq. 18 to points y ≈ F(x). Throws InvalidInput for mismatched sizes,
/// fewer than 4 points, non-finite data or bad options.
MapFitSummary FitSqrtMap(const std::vector<double>& x, const std::vector<double>& y,
                         const MapFitOptions& options = {});

}  // namespace impactkit
