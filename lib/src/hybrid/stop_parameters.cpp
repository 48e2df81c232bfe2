#include "impactkit/hybrid/stop_parameters.hpp"

#include <fmt/format.h>

#include "impactkit/core/errors.hpp"

namespace impactkit {

std::string StopParameterName(std::string_view base, int stop) {
  return stop == 0 ? std::string(base) : fmt::format("{}{}", base, stop + 1);
}

std::string StopParameterLabel(const StopParameterRow& row, int stop, int stop_count) {
  return stop_count == 1 ? fmt::format("{} ({})", row.name, row.meaning)
                         : fmt::format("{} ({} of stop {})", StopParameterName(row.name, stop),
                                       row.of_stop, stop + 1);
}

void CheckStopParameterRanges(const StopParameters& values, int stop, int stop_count) {
  for (const StopParameterRow& row : kStopParameterRows) {
    const double value = values.*row.member;
    if (!row.accepts(value)) {
      throw InvalidInput(fmt::format("{} must be {}, got {}",
                                     StopParameterLabel(row, stop, stop_count), row.range, value));
    }
  }
}

}  // namespace impactkit
