#pragma once
/// \file grazing_normal_form.hpp
/// The local map at a grazing orbit: Nordmark's discontinuity-map normal
/// form (Nordmark 1991; Fredriksson & Nordmark 1997; di Bernardo, Budd,
/// Champneys & Kowalczyk 2008, §2.5 and ch. 4), from the exact flow.
///
/// A grazing orbit touches stop c at time t* with speed 0 and turns back
/// (a = −s ẍ_c > 0, s the stop's side). On the stroboscopic section at t*
/// (every q forcing periods), a state x* + z whose flight would pass the
/// stop by δ = n · z + μ (to first order: n picks s x_c; μ the penetration
/// of the family's smooth orbit at the parameter, its clearance's
/// negative) meets it at speed √(2 a δ) and leaves with the jump
///
///     z ↦ z + W √δ,   W = (I − R) f(x*) √(2 / a)
///
/// (the zero-time discontinuity map, to O(δ): R the impact law's
/// Jacobian, f the vector field). Measured from the smooth orbit's point,
/// the grazing orbit's Poincaré map is then
///
///     z ↦ A z                     δ <= 0 (no contact)
///     z ↦ A z + A W √δ            δ >  0,   δ = n · z + μ,
///
/// with A the grazing orbit's monodromy (its flights and other impacts;
/// grazing_limit.hpp's SpeedSplitMonodromy::smooth) and μ = m (p − p*),
/// m the unfolding: the rate at which the family's smooth orbit (the one
/// that ignores the new contact, continued past it) penetrates the stop.
///
/// A sticking orbit's touch lies in a flight before its chatter, and the
/// jump is the same; A is then its stroboscopic monodromy through the
/// chatter, the stuck phases and the releases (the release map's analytic
/// Jacobian, StickingMap::Follow), of rank at most 2N − 2 (sticking
/// forgets the held mass's state), and m is measured on the side where the
/// family keeps off the stop (StickingGrazing::smooth_side): the release
/// map carries the new impact on past the grazing, so the smooth family
/// has no continuation there to difference.
///
/// Where one real multiplier λ of A dominates, with right and left
/// eigenvectors v, w (w · v = 1), the penetration y = δ obeys, once the
/// others have decayed,
///
///     y ↦ λ y + (1 − λ) μ + κ √y [y > 0],   κ = λ (n · v)(w · W),
///
/// and X = d − y / κ², d = μ / κ², turns it into the paper's Eq. 18
/// (X ↦ λ X + s √(d − X) for X <= d, λ X beyond) with s = −sign κ: its λ,
/// s and d (d grows at m / κ² per unit parameter). docs/theory.md §6b.

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/model/system.hpp"
#include "impactkit/orbits/grazing_limit.hpp"
#include "impactkit/orbits/sticking_map.hpp"

namespace impactkit {

/// What a sticking grazing orbit P(∞, q) carries besides its touch: the
/// family it belongs to, as fixed points of the release map.
struct StickingGrazing {
  StickingMapOptions map;       ///< the release map (its stop: the section's)
  int releases = 1;             ///< k: its sticking phases in q periods
  Eigen::VectorXd release;      ///< s: its release state before the touch (within q periods)
  double previous_event = 0.0;  ///< its last impact or release before the touch
  /// The parameter's direction (±1) in which its family keeps off the
  /// touched stop: past the grazing the release map carries the new
  /// impact, so the family's smooth continuation is measured on this side.
  double smooth_side = 1.0;
};

/// A periodic orbit of `system` that touches a stop: its contacts in q
/// forcing periods from the touch, in time order — the touch (speed 0,
/// turning back) first, then its impacts, each at its stop. A sticking
/// orbit (`sticking`) has the touch alone: its chatter, sticking and
/// releases are the release map's (StickingMap::Follow).
struct GrazingOrbit {
  System system;
  int q = 1;
  std::vector<StopContact> contacts;
  std::optional<StickingGrazing> sticking = std::nullopt;
};

/// `orbit` over its shortest period (a sticking orbit's q is its family's
/// already): where its impacts repeat every q / k
/// forcing periods (an orbit whose impact vanishes can leave P(2,1) traced
/// three times, as the P(6,3) of P(7,3)), the touch and one repetition's
/// impacts over q / k periods, whose normal form is the grazing's own (the
/// touch then recurs every q / k periods, where the longer one would miss
/// it); else `orbit` itself. Impacts repeat when their stops match and
/// their states agree to 1e-9 of the orbit's scale.
GrazingOrbit ShortestPeriod(const GrazingOrbit& orbit);

/// The one-dimensional reduction, where it holds.
struct SquareRootReduction {
  double lambda = 0.0;      ///< the dominant multiplier (real)
  double kappa = 0.0;       ///< y ↦ λ y + (1 − λ) μ + κ √y, y the penetration
  double s = 1.0;           ///< Eq. 18's s in its scaling: −sign κ
  double break_rate = 0.0;  ///< Eq. 18's d per unit parameter past the grazing, m / κ²
  double dominance = 0.0;   ///< |λ₂| / |λ|: how fast the other directions decay
};

/// What the motion does past a grazing (analysis/grazing_prediction.hpp
/// computes it). The normal form's attractor at one distance past the grazing.
struct LocalAttractor {
  double distance = 0.0;  ///< p − p*, signed
  /// Its period in iterations of the map and contacts per period (0, 0
  /// when it has no period up to max_period).
  int period = 0;
  int contacts = 0;
  double extent = 0.0;    ///< max |z| over the recorded iterations
  double lyapunov = 0.0;  ///< the map's largest exponent along it, per iteration
  std::string motion;     ///< "P(3,2)", "chaotic", "unresolved"
  /// Its penetration |m distance| is within the normal form's reach
  /// (GrazingNormalForm::reach): beyond it the true map may do otherwise.
  bool within_reach = true;
};

struct GrazingPrediction {
  /// The parameter's direction past the grazing: sign(m), where the smooth
  /// orbit penetrates the stop.
  double side = 1.0;
  /// An attractor stays near the grazing orbit past it.
  bool local = false;
  /// A multiplier of the grazing orbit lies on or outside the unit circle:
  /// nothing stays near it on either side.
  bool unstable_grazing_orbit = false;
  /// The motion just past the grazing, as the command line names motions:
  /// the local attractor's at the nearest distance, or the remote one's.
  std::string motion;
  /// "periodic" (one orbit at every distance), "period_adding" (its period
  /// grows towards the grazing), "chaos", or "jump" (no local attractor:
  /// `motion` is where the system goes).
  std::string scenario;
  double distance = 0.0;  ///< p − p* where `motion` was found
  /// The classical one-dimensional scenario where the map reduces to one
  /// dimension: "no_local_attractor", "period_adding_hysteresis",
  /// "period_adding_chaos", "chaos", "unstable_grazing_orbit"; empty where
  /// it does not reduce.
  std::string one_dimensional;
  std::vector<LocalAttractor> attractors;  ///< at each distance, nearest first
  /// One line: "past the grazing (decreasing): no attractor near the
  /// grazing orbit; the motion jumps to P(3,2)".
  std::string Describe() const;
};

struct GrazingNormalForm {
  std::string parameter;         ///< the unfolding's parameter
  double parameter_value = 0.0;  ///< p*, the grazing
  int stop = 0;                  ///< the stop touched
  int p = 0;                     ///< the grazing orbit's impacts (the touch not counted) ...
  int q = 1;                     ///< ... in q forcing periods: the map's period
  int releases = 0;              ///< its sticking phases in q periods (0: it does not stick)
  double time = 0.0;             ///< t*, the touch: the section's time
  double phase = 0.0;            ///< t* mod T, in [0, T)
  Eigen::VectorXd touch;         ///< x* = (x, v) at t*
  Eigen::MatrixXd linear;        ///< A
  Eigen::VectorXcd eigenvalues;  ///< A's, by decreasing modulus
  Eigen::RowVectorXd normal;     ///< n: δ = n · z + μ
  double curvature = 0.0;        ///< a = −s ẍ_c at the touch (> 0)
  Eigen::VectorXd root;          ///< W: the jump per √δ
  double unfolding = 0.0;        ///< m = dμ/dp
  /// The penetration δ up to which one step of the map, from z = δ s e_c
  /// at the grazing, errs by at most 10 % of its √δ term against the true
  /// map (simulated); its error grows like √δ. Penetrations μ = m (p − p*)
  /// beyond it are outside the normal form's reach. 0 if it errs more at
  /// the smallest penetration tried (1e-10 of the orbit's scale); infinite
  /// for a form not computed from an orbit (then the map is all there is).
  double reach = std::numeric_limits<double>::infinity();
  /// The true map could not be set up beyond `reach` (its contact would
  /// precede the back-flight: TrueGrazingMap) before the error reached
  /// 10 %: the reach is at least `reach`.
  bool reach_bounded = false;
  std::optional<SquareRootReduction> reduced;
  std::string reduction_note;  ///< why there is no reduction, when there is none
  /// What the motion does past it, once predicted (PredictGrazing).
  std::optional<GrazingPrediction> prediction;

  /// The normal form's map at z (measured from the smooth orbit's point)
  /// for the penetration μ of the smooth orbit.
  Eigen::VectorXd Map(const Eigen::VectorXd& z, double mu) const;
  /// One line: "grazing normal form at stop 1, phase ...: multipliers ...;
  /// |W| = ..., penetration ... per unit omega, reach ... in omega; ..."
  std::string Describe() const;
};

/// The true map the normal form approximates: `orbit`'s Poincaré map over
/// its q periods from x* + z at t* (`form` its normal form), the contact
/// near t* included and the next one not, as the departure from x*. x* +
/// z may lie past the stop, where no simulation starts: it is flown back
/// without the stops to t* − Δ (Δ a quarter period, or half the time since
/// the orbit's previous contact), simulated to t* + qT − Δ and flown on
/// without the stops to t* + qT. NaN where the simulation stops early.
Eigen::VectorXd TrueGrazingMap(const GrazingOrbit& orbit, const GrazingNormalForm& form,
                               const Eigen::VectorXd& z);

/// The normal form at `orbit`, unfolded in `parameter` (a name of
/// ParameterNames). Throws InvalidInput for an orbit whose first contact is
/// no touch (speed or gap not 0 to 1e-8, or pressed into the stop rather
/// than turning back), contacts SplitMonodromy refuses, a parameter the
/// system lacks, or a parameter at the end of its range (the unfolding
/// differences it on both sides).
GrazingNormalForm ComputeGrazingNormalForm(const GrazingOrbit& orbit, const std::string& parameter);

}  // namespace impactkit
