#pragma once
/// \file grazing_prediction.hpp
/// What the motion does just past a grazing, from its normal form
/// (orbits/grazing_normal_form.hpp), and where it goes when nothing stays
/// near the grazing orbit (docs/theory.md §6b).
///
/// Past the grazing (the side where the family's smooth orbit penetrates
/// the stop, μ = m (p − p*) > 0) the normal form's map is iterated from the
/// smooth orbit's point at a few distances. An attractor that stays near
/// the grazing orbit shrinks with μ (like √μ: the kicks are W √δ); one that
/// does not shrink lies outside the normal form's reach, and the motion
/// leaves the grazing orbit: then the system itself is simulated from the
/// grazing orbit, just past the grazing, and its steady motion classified.
/// A periodic attractor of the map with period N and I contacts per
/// period is the orbit P(N p + I, N q), p and q the grazing orbit's.
///
/// Where the map reduces to one dimension (SquareRootReduction), the
/// classical results for y ↦ λ y + (1 − λ) μ + κ √y (Nordmark 1991; Chin,
/// Ott, Nusse & Grebogi 1994) are reported beside it: no attractor near
/// the grazing for κ > 0 or λ < 0; for κ < 0 and 0 < λ < 1/4 a
/// period-adding sequence with consecutive periods coexisting, for 1/4 <
/// λ < 2/3 one with chaos between its windows, for 2/3 < λ < 1 chaos.

#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/classify.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/continuation/diagram_graph.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/grazing_normal_form.hpp"

namespace impactkit {

struct GrazingPredictionOptions {
  /// Distances past the grazing, relative to max(1, |p*|), at which the
  /// normal form is iterated, increasing, each 100 times the last (the
  /// attractor's shrinking is measured between consecutive ones).
  std::vector<double> distances = {1e-8, 1e-6, 1e-4};
  int transient_iterations = 4000;  ///< of the map, discarded
  int recorded_iterations = 1000;   ///< of the map, where its period is sought
  int max_period = 200;             ///< the longest period sought
  /// The remote attractor: simulated at this relative distance past the
  /// grazing, from the grazing orbit, for these forcing periods.
  double remote_distance = 1e-3;
  int transient_periods = 500;
  int recorded_periods = 100;
  ClassifyOptions classify;
  bool IsValid(std::string* error) const;
};

/// Brute-force sweeps through a grazing, the paper's method, to check a
/// prediction against.
struct GrazingSweepOptions {
  /// The sweeps run over p* ± span, relative to max(1, |p*|) ...
  double span = 2e-3;
  int steps = 41;  ///< ... at this many values, both ends included (odd: p* among them)
  int transient_periods = 500;  ///< at each value, from the previous value's state
  int recorded_periods = 100;
  /// Periods run from the grazing orbit at a sweep's first value before it
  /// starts, so that it starts on that side's attractor.
  int settle_periods = 500;
  bool IsValid(std::string* error) const;
};

/// Two sweeps through the grazing: `toward` from the side before it
/// (started on the grazing orbit's family) past it, `back` from past it
/// (started where the motion goes there) back.
struct GrazingSweeps {
  std::vector<double> values;       ///< increasing
  std::vector<std::string> toward;  ///< the motion at each value, swept towards the past side
  std::vector<std::string> back;    ///< the same, swept back
  double past_distance = 0.0;       ///< p − p* of the first value past the grazing
  std::string past;                 ///< `toward`'s motion there
  /// What the prediction expects there: the normal form's attractor at that
  /// distance if one stays near the grazing orbit, else the motion the
  /// system goes to from the grazing orbit at that distance.
  std::string expected;
  /// Where `expected` is the normal form's attractor: the first value past
  /// lies within its reach (LocalAttractor::within_reach). A disagreement
  /// beyond it tests the leading-order map where it does not hold.
  bool expected_within_reach = true;
  /// Where the grazing orbit is stable and `toward` shows its P(p, q) at
  /// the last two values before the grazing: the largest difference
  /// between `toward`'s impact speeds at the last one and the grazing
  /// orbit's (over one period, each sorted by stop and speed) ...
  std::optional<double> family_speed_gap;
  /// ... and between `toward`'s at the two, both relative to the grazing
  /// orbit's largest speed. Absent otherwise, and where they cannot be
  /// paired (other numbers of impacts, other stops).
  std::optional<double> family_speed_step;
  /// `toward` follows the grazing orbit up to the grazing: family_speed_gap
  /// is at most 3 family_speed_step. Along the grazing orbit's family the
  /// gap is about one step (2.4 steps where a fold or a vanishing impact
  /// lies just past the grazing); a coexisting orbit with the grazing
  /// orbit's label lies O(1) away. Only then does the motion past the
  /// grazing test the prediction. Not so where the grazing orbit is
  /// unstable, or another attractor holds the sweep, with its label or not.
  bool follows = false;
  bool agrees = false;      ///< follows, and past == expected
  bool hysteresis = false;  ///< the two sweeps differ at some value
};

/// The sweeps at the grazing of `form` (of `system` at the grazing), and
/// what its prediction (`form.prediction`, required) expects. Throws
/// InvalidInput for invalid options or a form without its prediction.
GrazingSweeps SweepThroughGrazing(const System& system, const GrazingNormalForm& form,
                                  const GrazingSweepOptions& options = {},
                                  const GrazingPredictionOptions& prediction_options = {});

/// A grazing of a diagram, its prediction and the sweeps that check it.
struct GrazingCheck {
  double parameter = 0.0;
  std::string grazing_orbit;  ///< the orbit that touches: "P(1,1)", "P(inf,1)" or "non-impacting"
  bool new_contact = true;    ///< located as a new contact (else as a vanishing impact)
  GrazingPrediction prediction;
  GrazingSweeps sweeps;
};

/// Every grazing node of `diagram` (of `system`) with a prediction
/// (PredictGrazings), checked by SweepThroughGrazing, in parameter order.
std::vector<GrazingCheck> CheckGrazings(const System& system, const Diagram& diagram,
                                        const GrazingSweepOptions& options = {});

/// The prediction at the grazing whose normal form is `form`, of `system`
/// (at the grazing: form.parameter = form.parameter_value). Throws
/// InvalidInput for invalid options.
GrazingPrediction PredictGrazing(const System& system, const GrazingNormalForm& form,
                                 const GrazingPredictionOptions& options = {});

/// Each grazing's normal form of `branch` (of `system`'s family) given its
/// prediction (GrazingNormalForm::prediction).
void PredictGrazings(const System& system, Branch* branch,
                     const GrazingPredictionOptions& options = {});
/// The same for every branch of `diagram` (of `system`) and its grazing nodes.
void PredictGrazings(const System& system, Diagram* diagram,
                     const GrazingPredictionOptions& options = {});
/// The same for the codimension-two points of `curve` (of `system`'s
/// family) that carry a normal form.
void PredictGrazings(const System& system, Curve* curve,
                     const GrazingPredictionOptions& options = {});

}  // namespace impactkit
