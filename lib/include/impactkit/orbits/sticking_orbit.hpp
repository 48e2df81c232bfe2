#pragma once
/// \file sticking_orbit.hpp
/// Periodic sticking orbits P(∞, q): k sticking phases in q forcing periods,
/// each reached through complete chatter, as fixed points of the release
/// map (sticking_map.hpp):
///
///     U(s) = P_R^k(s) − s − q T e_t = 0,
///
/// solved by FindOrbit (orbit.hpp) with OrbitOptions::releases = k: the
/// one fixed-point solve, Newton through KINSOL with the analytic Jacobian.
///
/// Stability. The image of P_R lies on the release surface Fs(s) = 0, so
/// D P_R^k maps every direction into its tangent space: the direction off
/// the surface has multiplier exactly 0. The multipliers of the orbit are
/// those of D P_R^k restricted to the tangent space (2N − 2 of them):
/// Bᵀ D P_R^k B with B an orthonormal basis of ker ∇Fs. Sticking collapses
/// the contact mass's position and velocity (x_c = xs, v_c = 0 whatever
/// came before), which is why the section has 2N − 2 dimensions where a
/// smooth flow's would have 2N − 1 and why the stroboscopic map of the same
/// motion has two zero multipliers besides these.

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_map.hpp"

namespace impactkit {

/// The sticking orbit (a PeriodicOrbit on the release section, orbit.hpp)
/// through the fixed point s of P_R^k: its impacts and stuck phases,
/// Jacobian, section multipliers, stability, residual, extent and the
/// monitors of its family's ends; its Jacobian and multipliers by
/// `method`. Throws InvalidInput if the map cannot follow k releases from s
/// (or, for central differences, from a perturbed s).
PeriodicOrbit DescribeStickingOrbit(const StickingMap& map, const Eigen::VectorXd& s, int releases,
                                    int q, JacobianMethod method = JacobianMethod::kAnalytic);

/// The multipliers of D P_R^k at s on the release section (see above).
Eigen::VectorXcd SectionMultipliers(const StickingMap& map, const Eigen::VectorXd& s,
                                    const Eigen::MatrixXd& jacobian);

}  // namespace impactkit
