#pragma once
/// \file grazing_limit.hpp
/// The linearisation of a periodic orbit as one of its impacts' speed goes
/// to zero, and where a fold or period-doubling curve ends on the curve
/// along which that impact vanishes.
///
/// From just before that impact (speed ε towards the stop) once round the
/// orbit, q forcing periods, the monodromy is
///
///     M(ε) = G S(ε),   S(ε) = R + (f⁺ − R f⁻) nᵀ / ε,
///
/// G the rest of the period (flows Φ and the other impacts' saltation
/// matrices; Φ(qT) alone for P(1, q)), R the reset's Jacobian, f∓ the
/// vector field before and after the reset, n the gap's gradient (n · f⁻ =
/// ε): the saltation matrix. f⁺ − R f⁻ is affine in ε (the vector field is
/// affine in the velocities, the reset linear), d0 + ε d1, so
///
///     M(ε) = G (R + d1 nᵀ) + G d0 nᵀ / ε:
///
/// a part that stays finite and a rank-one part that grows like 1/ε — why
/// the multipliers grow like 1/v near a vanishing impact (docs/theory.md
/// §6a). With B = G (R + d1 nᵀ) − λ I and u = G d0, the matrix determinant
/// lemma gives
///
///     ε det(M(ε) − λ I) = ε det B − det [B u; nᵀ 0],
///
/// smooth in ε. On a fold (λ = 1) or period-doubling (λ = −1) curve it is
/// zero, so as the curve reaches the vanishing impact (ε → 0) the bordered
/// matrix K_λ = [B u; nᵀ 0] becomes singular: det K_λ = 0 at the grazing
/// orbit (the orbit without that impact, touching the stop) is the corner's
/// second condition, regular where the multiplier test itself is undefined.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "impactkit/model/system.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {

/// M(ε) = regular + singular · normal / ε.
struct SpeedSplitMonodromy {
  Eigen::MatrixXd regular;    ///< G (R + d1 nᵀ)
  Eigen::VectorXd singular;   ///< G d0
  Eigen::RowVectorXd normal;  ///< n, the gap's gradient in (x, v)
  /// G itself: the monodromy of the orbit that only touches where the split
  /// contact is (its flights and other impacts, from that contact round):
  /// the grazing orbit's own, the linear part of its normal form.
  Eigen::MatrixXd smooth;
  /// d0 = (I − R) f at a touch (R x = x there, so f⁺ = f⁻ = f): the jump
  /// of the state across the contact per unit speed of arrival.
  Eigen::VectorXd jump;

  /// M(speed), speed > 0.
  Eigen::MatrixXd At(double speed) const;
  /// sign(det K_λ) times K_λ's least singular value, K_λ built with u and n
  /// scaled to unit length: zero exactly where λ becomes a multiplier in
  /// the limit ε → 0, and of the size of the distance to that in the
  /// parameters (unlike det, which carries every other singular value).
  double GrazingLimit(double lambda) const;
};

/// A contact of an orbit: the state just before it and the stop (an index
/// into System::stops) it is at, whose reset and gap it meets.
struct StopContact {
  HybridState state;
  int stop = 0;
};

/// M(ε) of an orbit of `system` whose contacts in q forcing periods are
/// `contacts`, in time order, each the state just before it at its stop:
/// the first is the one split (its speed towards its stop replaced by ε;
/// it may be a touch, speed 0), the others impacts at their own speeds.
/// Throws InvalidInput for an empty list, one not within q periods, or a
/// stop the system lacks.
SpeedSplitMonodromy SplitMonodromy(const System& system, const std::vector<StopContact>& contacts,
                                   int q);

/// The non-impacting response's closest approach to `stop`, as a touch
/// (speed 0): on the curve where P(1, q)'s impact vanishes (the response
/// touches that stop there: the one it comes closest to), the contact whose
/// SplitMonodromy is the limit of that orbit's monodromy as ε → 0. Throws
/// InvalidInput for a stop the system lacks.
StopContact ResponseTouch(const System& system, int stop);

/// The contacts of the orbit of `map` with p impacts through η (at the
/// map's section stop), q periods, touching stop `stop` at time t in flight
/// `flight` (0: the one after η): the touch first, then the p impacts
/// after it (the orbit's first ones a period on), each at the stop the map
/// finds it at (MapResult::stops). Where P(p + 1, q)'s impact there
/// vanishes, their SplitMonodromy is the limit of that orbit's monodromy.
/// Empty if the map fails along the orbit.
std::optional<std::vector<StopContact>> TouchContacts(const ImpactMap& map,
                                                      const Eigen::VectorXd& eta, int p, int q,
                                                      int flight, double t, int stop);

}  // namespace impactkit
