#pragma once
/// \file basins.hpp
/// Basins of attraction at fixed parameters: a grid of initial states over
/// two state coordinates (x1..xN, v1..vN; the others from a base state), each
/// run to steady state and classified as one sweep value is (sweep.hpp,
/// start kFixed), then sorted into attractors by their orbit:
///
///     same kind and period P(p, q), and every impact (phase, speed) of one
///     orbit's last q recorded periods within `orbit_tolerance` of an
///     impact of the other's, both ways
///
/// so two different P(1,1) orbits are two attractors. Motions without an
/// orbit to compare are grouped by kind and period: all non-impacting cells are
/// one attractor (a damped linear system has one steady response), all
/// chaotic cells one, all unresolved cells one. Attractors are numbered in
/// the order of their first cell, so the result is independent of how the
/// cells were computed. A row of initial states is one work unit.

#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_task.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

struct BasinsOptions {
  /// The run of each cell: transient and recorded periods, classification,
  /// simulation. Its parameter, range, start, chunks and threads are unused.
  SweepOptions run;
  /// The state whose other coordinates every start shares; rest when empty.
  std::optional<HybridState> base;
  std::string coordinate1 = "x1";  ///< varies along a row (cell index % K)
  double from1 = -1.0;
  double to1 = 1.0;
  int steps1 = 41;                 ///< K >= 1
  std::string coordinate2 = "v1";  ///< varies from row to row (ascending)
  double from2 = -1.0;
  double to2 = 1.0;
  int steps2 = 41;  ///< L >= 1
  /// Relative distance under which two impacts are the same: phases within
  /// tolerance * T, speeds within tolerance * max(1, |v|).
  double orbit_tolerance = 1e-4;
  bool IsValid(std::string* error) const;
};

class BasinsTask : public GridTask {
 public:
  /// Checks the options, the coordinate names and every start state before
  /// any work. Throws InvalidInput.
  BasinsTask(const System& system, BasinsOptions options);

  int Units() const override { return static_cast<int>(values2_.size()); }
  std::int64_t Cells() const override;
  std::vector<GridCell> RunUnit(int unit) const override;
  std::string Identity() const override;

  const BasinsOptions& Options() const { return options_; }
  const std::vector<double>& Values1() const { return values1_; }
  const std::vector<double>& Values2() const { return values2_; }

 private:
  HybridState StartOf(std::int64_t cell) const;

  System system_;
  BasinsOptions options_;
  std::vector<double> values1_;
  std::vector<double> values2_;
};

struct Attractor {
  MotionKind kind = MotionKind::kUnresolved;
  int p = 0;
  int q = 0;
  std::vector<AttractorImpact> orbit;  ///< that of its first cell
  std::int64_t first_cell = 0;
  std::int64_t cells = 0;  ///< the basin's size
};

struct BasinsResult {
  std::vector<Attractor> attractors;  ///< in the order of their first cell
  std::vector<int> attractor;         ///< per cell (index order), into `attractors`
};

/// Sorts cells (in index order) into attractors as the file comment says;
/// `period` is the forcing period T.
BasinsResult IdentifyAttractors(const std::vector<GridCell>& cells, double period,
                                double orbit_tolerance);

/// The index of a state coordinate "x1".."xN" or "v1".."vN" in (x, v), or
/// throws InvalidInput listing the names of an N-mass system.
int StateCoordinate(const System& system, const std::string& name);

}  // namespace impactkit
