#include "impactkit/analysis/parameter_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "impactkit/core/errors.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {
namespace {

/// The column parameter's sweep: its values by the sweep's own rule.
SweepOptions ColumnSweep(const ParameterMapOptions& options) {
  SweepOptions column = options.row;
  column.parameter = options.parameter2;
  column.from = options.from2;
  column.to = options.to2;
  column.steps = options.steps2;
  column.direction = SweepDirection::kUp;
  return column;
}

System RowSystem(const System& base, const ParameterMapOptions& options, double value2) {
  System system = base;
  SetParameter(system, options.parameter2, value2);
  return system;
}

}  // namespace

bool ParameterMapOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (parameter2 == row.parameter) {
    return fail(fmt::format("the two parameters are both '{}': a map needs two", parameter2));
  }
  if (steps2 < 1) return fail(fmt::format("steps2 must be >= 1, got {}", steps2));
  if (!std::isfinite(from2) || !std::isfinite(to2)) {
    return fail(fmt::format("from2 and to2 must be finite, got {} and {}", from2, to2));
  }
  if (steps2 > 1 && from2 == to2) {
    return fail(fmt::format("from2 and to2 are both {}: {} steps need a range (or steps2 = 1)",
                            from2, steps2));
  }
  return row.IsValid(error);
}

ParameterMapTask::ParameterMapTask(const System& system, ParameterMapOptions options)
    : system_(system), options_(std::move(options)) {
  std::string error;
  Require(options_.IsValid(&error), error);
  GetParameter(system_, options_.row.parameter);  // throws for an unknown name
  GetParameter(system_, options_.parameter2);
  values1_ = SweepValues(options_.row);
  values2_ = SweepValues(ColumnSweep(options_));
  chunks_ = SweepChunks(options_.row);
  // Every cell's parameters, before any work (RunSweep checks a row only
  // when it starts, which may be hours in).
  for (double value2 : values2_) {
    System row = RowSystem(system_, options_, value2);
    for (double value1 : values1_) {
      System cell = row;
      SetParameter(cell, options_.row.parameter, value1);
      try {
        ValidateParameters(cell);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("map at {} = {}, {} = {}: {}", options_.row.parameter,
                                       value1, options_.parameter2, value2, e.what()));
      }
    }
  }
}

std::int64_t ParameterMapTask::Cells() const {
  return static_cast<std::int64_t>(values1_.size()) * static_cast<std::int64_t>(values2_.size());
}

std::vector<GridCell> ParameterMapTask::RunUnit(int unit) const {
  const int row = unit / chunks_, chunk = unit % chunks_;
  const std::vector<SweepPoint> points =
      RunSweepChunk(RowSystem(system_, options_, values2_.at(row)), options_.row, chunk);
  // The chunk's first value: chunks before it are all full.
  const std::int64_t first =
      static_cast<std::int64_t>(row) * values1_.size() +
      static_cast<std::int64_t>(chunk) *
          (options_.row.chunk_values == 0 ? values1_.size() : options_.row.chunk_values);
  std::vector<GridCell> cells;
  cells.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    cells.push_back(CellOf(first + static_cast<std::int64_t>(k), points[k]));
  }
  return cells;
}

std::string ParameterMapTask::Identity() const {
  return fmt::format("map {} {} param2={} from2={} to2={} steps2={}", SystemIdentity(system_),
                     SweepIdentity(options_.row), options_.parameter2, options_.from2, options_.to2,
                     options_.steps2);
}

}  // namespace impactkit
