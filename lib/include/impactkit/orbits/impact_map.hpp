#pragma once
/// \file impact_map.hpp
/// The impact map P_I: from the state just BEFORE one impact to the state
/// just before the next (the paper's §2.2). Coordinates, following the paper,
///
///     η = (x_j for j != c, τ, v_1 … v_N)        (size 2N)
///
/// with c the DOF of the stop hit, x_c = xs implied, τ the absolute impact
/// time and s v_c > 0 the impact speed (s = +1 at an upper stop, -1 at a
/// lower one). One application: v_c <- -r v_c, exact free flight, the next
/// impact at any stop found and judged as the simulator does
/// (hybrid/phase_events.hpp).
///
/// With several stops an impact state belongs to the stop it is at: the
/// map's section is one stop's impacts (ImpactMapOptions::stop), and
/// P_I^p goes from the section back to it through impacts at any stops
/// (MapResult::stops names them); Follow() goes from an impact at any stop.
///
/// The analytic Jacobian chains, per impact, the restitution (a diagonal
/// map), the flow's state transition e^{S(t'-τ)} with the derivative of the
/// flight's start time (-e^{S(t'-τ)} f(y+, τ)), and the saltation at the
/// next impact: with G = ∂y(t')/∂η at fixed t', the implicit function
/// theorem on x_c(t') = xs gives dt' = -e_cᵀ G dη / v_c(t'-) and
/// dy(t'-) = (I - f(y(t'-), t') e_cᵀ / v_c(t'-)) G dη, c the DOF of the
/// stop the next impact is at.

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "impactkit/core/termination.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/section_map.hpp"

namespace impactkit {

struct ImpactMapOptions {
  /// A flight longer than this many forcing periods counts as a lost impact.
  double max_flight_periods = 64.0;
  /// The arrival rule: an arrival whose bounce height is unresolved
  /// (SimulationOptions::bounce_height_resolution, the rounding by
  /// default) is no impact and ends the map (grazing or chatter), as the
  /// simulator makes it a landing.
  SimulationOptions simulation;
  /// The section: the stop (an index into System::stops) whose impacts η
  /// describes, where P_I^p starts and must end.
  int stop = 0;
  bool IsValid(std::string* error) const;
};

/// The result of P_I^p(η).
struct MapResult {
  /// kCompleted (p impacts followed: the result is valid), kNoImpact (no
  /// further impact within max_flight_periods), kGrazing (an arrival too
  /// slow to be an impact, its height unresolved: the simulator's rule,
  /// with the mass moving away after it), kSticking (such an arrival with
  /// the mass pressed into the stop) or kOtherStop (the p-th impact is at
  /// another stop than the section's).
  Termination termination = Termination::kCompleted;
  int impacts_done = 0;               ///< impacts followed before the status
  Eigen::VectorXd eta;                ///< P_I^p(η) (valid when kOk)
  Eigen::MatrixXd jacobian;           ///< D(P_I^p)(η), when asked and kOk
  std::vector<Eigen::VectorXd> path;  ///< η after each impact (size p when kOk)
  std::vector<int> stops;             ///< the stop of each of them (its η's coordinates)
  /// Each impact's D P_I, when asked, kOk and all p of them fit in
  /// kKeptStepEntries numbers (the product is `jacobian`); else empty.
  std::vector<Eigen::MatrixXd> step_jacobians;
  /// 32 MB: a long orbit of a long chain (2N × 2N a step) keeps only its
  /// product, as it did before the steps were kept.
  static constexpr Eigen::Index kKeptStepEntries = Eigen::Index{1} << 22;
};

class ImpactMap : public SectionMap {
 public:
  /// Throws InvalidInput for an invalid system or options.
  explicit ImpactMap(const System& system, const ImpactMapOptions& options = {});
  /// On a hybrid system already decomposed (shared with a simulator, say).
  /// Throws InvalidInput for invalid options.
  explicit ImpactMap(std::shared_ptr<const HybridSystem> hybrid,
                     const ImpactMapOptions& options = {});

  /// P_I^p(η) and, if `with_jacobian`, its analytic Jacobian, from an
  /// impact at the section's stop; kOtherStop if the p-th impact is at
  /// another. Throws InvalidInput if η is not an impact state (wrong size,
  /// non-finite, moving away from the stop) or p < 1.
  MapResult Apply(const Eigen::VectorXd& eta, int p, bool with_jacobian) const;
  /// p impacts on from an impact at stop `stop`, wherever they fall.
  MapResult Follow(const Eigen::VectorXd& eta, int stop, int p, bool with_jacobian) const;

  /// SectionMap: P_I^p as Apply, its failures (a state that is no impact
  /// state at the section's stop included) as SectionImage::failure.
  int Size() const override { return 2 * GetSystem().Dof(); }
  SectionImage Iterate(const Eigen::VectorXd& eta, int p, bool with_jacobian) const override;
  /// Each map carries event-time rounding of ~1e-12, so the best step is
  /// near its cube root: 1e-5 (of the period for τ) gives ~1e-7 relative
  /// accuracy, 1e-6 only ~1e-6.
  double FiniteDifferenceStep() const override { return 1e-5; }
  /// 1e-6 at every state: ParameterRate differences each flight alone and
  /// chains the impacts through their analytic Jacobians, so a slow
  /// impact's 1/v is exact rather than differenced.
  double ParameterStep(const Eigen::MatrixXd&) const override { return 1e-6; }
  /// ParameterDerivative, for `below` and `above` impact maps, on the
  /// steps of `at_eta` where given.
  SectionImage ParameterRate(const Eigen::VectorXd& eta, int p, const SectionMap& below,
                             const SectionMap& above, double delta,
                             const SectionImage* at_eta = nullptr) const override;

  /// ∂P_I^p(η; μ)/∂μ at fixed η, for a scalar parameter μ of which `below`
  /// and `above` are this map's system at μ - δ₋ and μ + δ₊ (δ₋ + δ₊ =
  /// `delta`; either may be this map). A plain difference of P_I^p is
  /// useless near grazing, where the impact time varies like 1/v; here only
  /// the flights' states at FIXED times are differenced (they are smooth in
  /// μ), and the impact times follow by the implicit function theorem on
  /// x_c(t') = xs(μ), as in the analytic Jacobian. The impacts and their
  /// Jacobians are `steps` (Iterate(eta, p, true)'s) where it has p of
  /// them, else followed here. Empty if the map fails.
  Eigen::VectorXd ParameterDerivative(const Eigen::VectorXd& eta, int p, const ImpactMap& below,
                                      const ImpactMap& above, double delta,
                                      std::span<const SectionStep> steps = {}) const;

  /// η of the state just before an impact at time t at stop `stop` (the
  /// section's by default).
  Eigen::VectorXd ToEta(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
    return ToEta(t, x, v, SectionStop());
  }
  Eigen::VectorXd ToEta(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                        int stop) const;
  /// The hybrid state just before the impact described by η at `stop`.
  HybridState ToState(const Eigen::VectorXd& eta) const { return ToState(eta, SectionStop()); }
  HybridState ToState(const Eigen::VectorXd& eta, int stop) const;
  /// x_i(t) in the free flight that follows the impact η at `stop`
  /// (restitution applied at τ), as a Signal valid from τ up to the next
  /// impact. It refers to this map's flow: use it while the map lives.
  Signal FlightCoordinate(const Eigen::VectorXd& eta, int dof) const {
    return FlightCoordinate(eta, dof, SectionStop());
  }
  Signal FlightCoordinate(const Eigen::VectorXd& eta, int dof, int stop) const;
  /// The state at time t (>= τ) of the free flight after the impact η at
  /// `stop`, ignoring the stops.
  HybridState FlightState(const Eigen::VectorXd& eta, double t) const {
    return FlightState(eta, t, SectionStop());
  }
  HybridState FlightState(const Eigen::VectorXd& eta, double t, int stop) const;
  /// How the flight after the impact η at `stop` first meets a stop, up to
  /// t_end: where the event search finds an arrival, and whether the
  /// simulator's arrival rule makes it an impact.
  struct FlightEnd {
    HybridState start;  ///< just after the impact η (its reset applied)
    HybridState state;  ///< just before the arrival, x_c = the stop's position
    int stop = 0;
    /// False for an arrival whose height is unresolved (a landing, or a
    /// grazing touch): what the map reports as kChatter or kGrazing.
    bool impact = true;
    bool pressed = false;  ///< the free acceleration there leads into the stop
  };
  /// None if the flight reaches no stop by t_end (to the search's
  /// resolution). Throws InvalidInput as ValidateEta.
  std::optional<FlightEnd> FirstArrival(const Eigen::VectorXd& eta, int stop, double t_end) const;
  /// The state just after the impact η at `stop` (its reset applied).
  HybridState Departure(const Eigen::VectorXd& eta, int stop) const;
  /// ∂y/∂η at `stop`: the embedding of η into y = (x, v) (x_c = xs fixed, τ
  /// no part of y).
  Eigen::MatrixXd Embedding(int stop) const;
  /// G = ∂y(t)/∂η at a fixed time t of the free flight after an impact at
  /// `stop` whose Departure is `departure`: the reset, then the flow, with
  /// τ's column −e^{S(t−τ)} f(y+, τ) (hybrid/event_time.hpp's AtFixedTime).
  Eigen::MatrixXd FlightJacobian(int stop, const HybridState& departure, double t) const;
  /// ∂η'/∂p of the impact `arrival` at stop `stop` that ends a flight, from
  /// G = ∂y(t')/∂p at its time t' held fixed: the event-time correction
  /// (saltation) of hybrid/event_time.hpp, in η's coordinates.
  Eigen::MatrixXd ArrivalJacobian(const Eigen::MatrixXd& g, int stop,
                                  const HybridState& arrival) const;
  /// Index of τ in η (N - 1).
  int TimeIndex() const override { return GetSystem().Dof() - 1; }
  /// The impact speed s v_c of η at `stop` (> 0 for an impact state).
  double Speed(const Eigen::VectorXd& eta, int stop) const;
  int SectionStop() const override { return options_.stop; }
  const System& GetSystem() const override { return hybrid_->GetSystem(); }

  /// Throws InvalidInput naming the problem if η is not an impact state at
  /// `stop` (the section's by default).
  void ValidateEta(const Eigen::VectorXd& eta) const { ValidateEta(eta, SectionStop()); }
  void ValidateEta(const Eigen::VectorXd& eta, int stop) const;

 private:
  /// One impact at `stop` and the flight to the next impact, at *next_stop;
  /// false with `status` set when it fails.
  bool Step(const Eigen::VectorXd& eta, int stop, Eigen::VectorXd* next, int* next_stop,
            Eigen::MatrixXd* jacobian, Termination* status) const;
  /// The flow's transient coordinates just after the impact η at `stop`.
  Eigen::VectorXd FlightTransient(const Eigen::VectorXd& eta, int stop) const;

  std::shared_ptr<const HybridSystem> hybrid_;
  ImpactMapOptions options_;
};

}  // namespace impactkit
