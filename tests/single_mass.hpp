#pragma once
/// \file single_mass.hpp
/// The library's System for one forced mass on a spring and dashpot with
/// one stop, as the single-degree-of-freedom tests build it.

#include <Eigen/Dense>

#include "closed_form_sdof.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::testing {

/// Unit mass, stiffness k, damping c, forcing amplitude a at Ω = omega,
/// the stop at xs with restitution r.
inline System SingleMass(double k, double c, double a, double omega, double xs, double r) {
  return GeneralSystem(Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, c),
                       Eigen::MatrixXd::Constant(1, 1, k), Eigen::VectorXd::Constant(1, a), omega,
                       xs, r);
}

/// The system the closed-form reference (closed_form_sdof.hpp) describes.
inline System SdofSystem(const SdofParameters& p) {
  return UniformChain({1, p.m, p.k, p.c}, Eigen::VectorXd::Constant(1, p.a), p.omega, p.xs, p.r);
}

}  // namespace impactkit::testing
