#pragma once
/// \file section_map.hpp
/// A Poincaré map of the hybrid motion on a section of one stop's events:
/// its impacts (the impact map, impact_map.hpp) or its releases (the
/// release map, sticking_map.hpp). What a periodic orbit needs of either:
/// the k-th iterate with its Jacobian, the section's size and where its
/// time sits. A periodic orbit of k events in q forcing periods is a zero of
///
///     U(x) = P^k(x) − x − q T e_t,
///
/// solved the same way on either map (orbits/fixed_point.hpp).

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "impactkit/model/system.hpp"

namespace impactkit {

/// One event of an iterate: the section's state just before it, its stop,
/// and the Jacobian of the step that reached it.
struct SectionStep {
  Eigen::VectorXd state;
  int stop = 0;
  Eigen::MatrixXd jacobian;
};

/// P^k(x), or why the map could not follow it.
struct SectionImage {
  Eigen::VectorXd state;     ///< P^k(x), when ok
  Eigen::MatrixXd jacobian;  ///< D P^k(x), when asked and ok
  /// The k steps, when asked for the Jacobian and ok, from a map whose
  /// ParameterRate chains them (the impact map, where they fit in
  /// MapResult::kKeptStepEntries numbers); else empty.
  std::vector<SectionStep> steps;
  /// Empty when ok; else what stopped the map, and after how many of the k
  /// events ("after 0 of 1 impacts, lost impact (no further impact)").
  std::string failure;
  /// The release map's chatter stopped ending in sticking (beyond a
  /// sticking family's end); false for the impact map.
  bool stops_sticking = false;
  bool Ok() const { return failure.empty(); }
};

class SectionMap {
 public:
  virtual ~SectionMap() = default;

  /// The dimension of the section's coordinates x.
  virtual int Size() const = 0;
  /// The index of the event's absolute time in x.
  virtual int TimeIndex() const = 0;
  /// The stop whose events are the section (an index into System::stops).
  virtual int SectionStop() const = 0;
  virtual const System& GetSystem() const = 0;
  /// P^k(x) and, if `with_jacobian`, its analytic Jacobian; not ok (no
  /// exception) where x is no state of the section or the map fails.
  virtual SectionImage Iterate(const Eigen::VectorXd& x, int k, bool with_jacobian) const = 0;
  /// The relative step of the map's central differences: near the cube
  /// root of its event-time rounding (FiniteDifferenceJacobian).
  virtual double FiniteDifferenceStep() const = 0;
  /// The relative step δ of ParameterRate's differences at a state where
  /// D P^k = `jacobian`.
  virtual double ParameterStep(const Eigen::MatrixXd& jacobian) const = 0;
  /// ∂P^k(x; μ)/∂μ at fixed x (in `state`) for a scalar parameter μ, of
  /// which `below` and `above` are this map's kind at μ − δ₋ and μ + δ₊
  /// (δ₋ + δ₊ = `delta`; either may be this map). `at_x`, if not null, is
  /// this map's Iterate(x, k, true), whose steps a map that chains them
  /// reuses rather than follows again. By default the difference of the
  /// images of `below` and `above`; not ok where either fails.
  virtual SectionImage ParameterRate(const Eigen::VectorXd& x, int k, const SectionMap& below,
                                     const SectionMap& above, double delta,
                                     const SectionImage* at_x = nullptr) const;

  /// x with its time moved into [0, T): the map commutes with shifts by T,
  /// and small times keep event times precise.
  Eigen::VectorXd WithPhase(Eigen::VectorXd x) const {
    x(TimeIndex()) = GetSystem().Phase(x(TimeIndex()));
    return x;
  }
};

/// D P^k(x) by central differences (the paper's method, Foale & Thompson):
/// steps `relative_step` × max(1, |x_j|), the forcing period for the time;
/// 2 Size() map applications. Empty if a perturbed map fails.
Eigen::MatrixXd FiniteDifferenceJacobian(const SectionMap& map, const Eigen::VectorXd& x, int k,
                                         double relative_step);
inline Eigen::MatrixXd FiniteDifferenceJacobian(const SectionMap& map, const Eigen::VectorXd& x,
                                                int k) {
  return FiniteDifferenceJacobian(map, x, k, map.FiniteDifferenceStep());
}

}  // namespace impactkit
