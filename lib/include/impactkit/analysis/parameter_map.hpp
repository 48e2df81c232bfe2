#pragma once
/// \file parameter_map.hpp
/// A two-parameter brute-force map: a grid of K values of one named
/// parameter (the row parameter, SweepOptions) by L values of another (the
/// column parameter), each cell's motion classified. Each row is exactly the
/// sweep (sweep.hpp) of the row parameter with the column parameter fixed at
/// that row's value: the row's cells are that sweep's points, with its
/// start rule (previous value's final state or a fixed state) and its
/// chunks. A chunk of a row is one work unit (grid_task.hpp), run by
/// RunSweepChunk, so the map is identical for any number of threads or
/// processes, and a map of few rows still has many units to share out.

#include <string>
#include <vector>

#include "impactkit/analysis/grid_task.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

struct ParameterMapOptions {
  /// The sweep along each row: its parameter, range, steps, periods, start
  /// rule, chunks and classification (its `threads` is ignored).
  SweepOptions row;
  std::string parameter2 = "r";  ///< the column parameter, not row.parameter
  double from2 = 0.3;            ///< one end of its range
  double to2 = 0.95;             ///< the other (either order; ascending rows)
  int steps2 = 66;               ///< L >= 1 rows, both ends included
  bool IsValid(std::string* error) const;
};

class ParameterMapTask : public GridTask {
 public:
  /// Checks the options, both parameter names, and every cell's parameters
  /// before any work. Throws InvalidInput.
  ParameterMapTask(const System& system, ParameterMapOptions options);

  int Units() const override { return static_cast<int>(values2_.size()) * chunks_; }
  std::int64_t Cells() const override;
  std::vector<GridCell> RunUnit(int unit) const override;
  std::string Identity() const override;

  const ParameterMapOptions& Options() const { return options_; }
  /// The row parameter's K values in sweep order (cell index % K).
  const std::vector<double>& Values1() const { return values1_; }
  /// The column parameter's L values, ascending (cell index / K).
  const std::vector<double>& Values2() const { return values2_; }

 private:
  System system_;
  ParameterMapOptions options_;
  std::vector<double> values1_;
  std::vector<double> values2_;
  int chunks_ = 1;  ///< per row
};

}  // namespace impactkit
