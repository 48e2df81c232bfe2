#pragma once
/// \file impact_map.hpp
/// The impact map P_I: from the state just BEFORE one impact to the state
/// just before the next (the paper's §2.2). Coordinates, following the paper,
///
///     η = (x_j for j != c, τ, v_1 … v_N)        (size 2N)
///
/// with x_c = xs implied, τ the absolute impact time and v_c > 0 the impact
/// speed v_c(τ-). One application: v_c <- -r v_c, exact free flight, the
/// next impact found by the certified event search (events.hpp).
///
/// The analytic Jacobian chains, per impact, the restitution (a diagonal
/// map), the flow's state transition e^{S(t'-τ)} with the derivative of the
/// flight's start time (-e^{S(t'-τ)} f(y+, τ)), and the saltation at the
/// next impact: with G = ∂y(t')/∂η at fixed t', the implicit function
/// theorem on x_c(t') = xs gives dt' = -e_cᵀ G dη / v_c(t'-) and
/// dy(t'-) = (I - f(y(t'-), t') e_cᵀ / v_c(t'-)) G dη.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// What happened when the map was applied.
enum class MapStatus {
  kOk,        ///< p impacts followed, result valid
  kNoImpact,  ///< no further impact within max_flight_periods: an impact was lost
  kGrazing,   ///< an impact with speed below min_speed, the mass moving away after it
  kChatter,   ///< an impact with speed below min_speed pressed into the stop: chatter/sticking
};

std::string ToString(MapStatus status);

struct ImpactMapOptions {
  /// A flight longer than this many forcing periods counts as a lost impact.
  double max_flight_periods = 64.0;
  /// Impacts slower than this (velocity units) end the map (grazing or chatter).
  double min_speed = 1e-8;
  bool IsValid(std::string* error) const;
};

/// The result of P_I^p(η).
struct MapResult {
  MapStatus status = MapStatus::kOk;
  int impacts_done = 0;               ///< impacts followed before the status
  Eigen::VectorXd eta;                ///< P_I^p(η) (valid when kOk)
  Eigen::MatrixXd jacobian;           ///< D(P_I^p)(η), when asked and kOk
  std::vector<Eigen::VectorXd> path;  ///< η after each impact (size p when kOk)
};

class ImpactMap {
 public:
  /// Throws InvalidInput for an invalid system or options.
  explicit ImpactMap(const System& system, const ImpactMapOptions& options = {});
  /// On a hybrid system already decomposed (shared with a simulator, say).
  /// Throws InvalidInput for invalid options.
  explicit ImpactMap(std::shared_ptr<const HybridSystem> hybrid,
                     const ImpactMapOptions& options = {});

  /// P_I^p(η) and, if `with_jacobian`, its analytic Jacobian.
  /// Throws InvalidInput if η is not an impact state (wrong size, non-finite,
  /// v_c <= 0) or p < 1.
  MapResult Apply(const Eigen::VectorXd& eta, int p, bool with_jacobian) const;

  /// The Jacobian of P_I^p by central differences (the paper's method,
  /// Foale & Thompson): 2N map applications per side. Empty if a perturbed
  /// map fails. Each map carries event-time rounding of ~1e-12, so the
  /// best step is near its cube root: 1e-5 (of the period for τ) gives
  /// ~1e-7 relative accuracy, 1e-6 only ~1e-6.
  Eigen::MatrixXd FiniteDifferenceJacobian(const Eigen::VectorXd& eta, int p,
                                           double relative_step = 1e-5) const;

  /// ∂P_I^p(η; μ)/∂μ at fixed η, for a scalar parameter μ of which `below`
  /// and `above` are this map's system at μ - δ₋ and μ + δ₊ (δ₋ + δ₊ =
  /// `delta`; either may be this map). A plain difference of P_I^p is
  /// useless near grazing, where the impact time varies like 1/v; here only
  /// the flights' states at FIXED times are differenced (they are smooth in
  /// μ), and the impact times follow by the implicit function theorem on
  /// x_c(t') = xs(μ), as in the analytic Jacobian. Empty if the map fails.
  Eigen::VectorXd ParameterDerivative(const Eigen::VectorXd& eta, int p, const ImpactMap& below,
                                      const ImpactMap& above, double delta) const;

  /// η of the state just before an impact at time t.
  Eigen::VectorXd ToEta(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  /// The hybrid state just before the impact described by η.
  HybridState ToState(const Eigen::VectorXd& eta) const;
  /// x_i(t) in the free flight that follows the impact η (restitution
  /// applied at τ), as a Signal valid from τ up to the next impact. It
  /// refers to this map's flow: use it while the map lives.
  Signal FlightCoordinate(const Eigen::VectorXd& eta, int dof) const;
  /// The state at time t (>= τ) of the free flight after the impact η,
  /// ignoring the stop.
  HybridState FlightState(const Eigen::VectorXd& eta, double t) const;
  /// Index of τ in η (N - 1).
  int TimeIndex() const { return GetSystem().Dof() - 1; }
  const System& GetSystem() const { return hybrid_->GetSystem(); }

  /// Throws InvalidInput naming the problem if η is not an impact state.
  void ValidateEta(const Eigen::VectorXd& eta) const;

 private:
  /// One impact and flight; false with `status` set when it fails.
  bool Step(const Eigen::VectorXd& eta, Eigen::VectorXd* next, Eigen::MatrixXd* jacobian,
            MapStatus* status) const;
  /// The flow's transient coordinates just after the impact η.
  Eigen::VectorXd FlightTransient(const Eigen::VectorXd& eta) const;
  /// ∂y(τ+)/∂η: the embedding of η into y(τ−) (x_c = xs fixed, τ no part
  /// of y), then the stop's reset.
  Eigen::MatrixXd ResetInEta() const;

  std::shared_ptr<const HybridSystem> hybrid_;
  ImpactMapOptions options_;
};

}  // namespace impactkit
