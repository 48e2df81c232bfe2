#pragma once
/// \file grazing_limit.hpp
/// The linearisation of a P(1, q) orbit as its impact speed goes to zero,
/// and where a fold or period-doubling curve ends on the curve along which
/// that impact vanishes.
///
/// From just before the impact (speed ε towards the stop) to just before the
/// next, q forcing periods later, the orbit's monodromy is
///
///     M(ε) = Φ(qT) S(ε),   S(ε) = R + (f⁺ − R f⁻) nᵀ / ε,
///
/// Φ the free flow's transition matrix, R the reset's Jacobian, f∓ the
/// vector field before and after the reset, n the gap's gradient (n · f⁻ =
/// ε): the saltation matrix. f⁺ − R f⁻ is affine in ε (the vector field is
/// affine in the velocities, the reset linear), d0 + ε d1, so
///
///     M(ε) = Φ (R + d1 nᵀ) + Φ d0 nᵀ / ε:
///
/// a part that stays finite and a rank-one part that grows like 1/ε — why
/// the multipliers grow like 1/v near a vanishing impact (docs/theory.md).
/// With B = Φ (R + d1 nᵀ) − λ I and u = Φ d0, the matrix determinant lemma
/// gives
///
///     ε det(M(ε) − λ I) = ε det B − det [B u; nᵀ 0],
///
/// smooth in ε. On a fold (λ = 1) or period-doubling (λ = −1) curve it is
/// zero, so as the curve reaches the vanishing impact (ε → 0) the bordered
/// matrix K_λ = [B u; nᵀ 0] becomes singular: det K_λ = 0 at the grazing
/// orbit is the corner's second condition, regular where the multiplier
/// test itself is undefined.

#include <Eigen/Dense>

#include "impactkit/model/system.hpp"

namespace impactkit {

/// M(ε) = regular + singular · normal / ε.
struct SpeedSplitMonodromy {
  Eigen::MatrixXd regular;    ///< Φ (R + d1 nᵀ)
  Eigen::VectorXd singular;   ///< Φ d0
  Eigen::RowVectorXd normal;  ///< n, the gap's gradient in (x, v)

  /// M(speed), speed > 0.
  Eigen::MatrixXd At(double speed) const;
  /// sign(det K_λ) times K_λ's least singular value, K_λ built with u and n
  /// scaled to unit length: zero exactly where λ becomes a multiplier in
  /// the limit ε → 0, and of the size of the distance to that in the
  /// parameters (unlike det, which carries every other singular value).
  double GrazingLimit(double lambda) const;
};

/// M(ε) of a P(1, q) orbit of `system` (one stop) whose impact happens at
/// time t in state (x, v); v's component at the stop's mass is replaced by ε.
SpeedSplitMonodromy SingleImpactMonodromy(const System& system, double t, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& v, int q);

/// The same at the non-impacting response's closest approach to the stop:
/// on the curve where P(1, q)'s impact vanishes (the response touches the
/// stop there), the limit of the orbit's monodromy as ε → 0.
SpeedSplitMonodromy ResponseTouchMonodromy(const System& system, int q);

}  // namespace impactkit
