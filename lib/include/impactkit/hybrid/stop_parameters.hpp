#pragma once
/// \file stop_parameters.hpp
/// A stop's parameters as data, declared beside the law that reads them
/// (hybrid/stop.hpp), so that a contact law and its parameters are one
/// folder. This header includes nothing of the library: the model's System
/// holds its stops as these values, and everything that names, reads,
/// writes or checks a stop's parameter (GetParameter and --set, system
/// files, Python's stop dicts, provenance lines, checkpoints' identities,
/// Validate) goes through kStopParameterRows, so a new parameter of a
/// contact law is a field here and a row of that table.

#include <array>
#include <cmath>
#include <string>
#include <string_view>

namespace impactkit {

/// Which way a stop limits its mass.
enum class StopSide {
  kUpper,  ///< x_i <= position: met moving up (v_i > 0)
  kLower,  ///< x_i >= position: met moving down (v_i < 0)
};

/// One rigid stop: the mass it limits, from which side, where, and the
/// coefficient of restitution of its impacts.
struct StopParameters {
  int dof = 1;                       ///< the mass it limits (0-based)
  StopSide side = StopSide::kUpper;  ///< which way
  double position = 0.1;             ///< xs
  double restitution = 0.7;          ///< r in [0, 1]
  /// +1 for an upper stop, -1 for a lower one: Sign() (x_i - position) is
  /// the gap (< 0 inside) and Sign() v_i the speed towards the stop.
  double Sign() const { return side == StopSide::kUpper ? 1.0 : -1.0; }
  bool operator==(const StopParameters&) const = default;
};

/// A scalar parameter every stop has.
struct StopParameterRow {
  /// The first stop's name (xs); stop k's is name<k> (xs2, xs3, …).
  std::string_view name;
  std::string_view meaning;  ///< with one stop: "stop position"
  std::string_view of_stop;  ///< with several: "position" (of stop k)
  std::string_view range;    ///< the values `accepts` takes, e.g. "finite"
  bool (*accepts)(double value);
  double StopParameters::*member;
  std::string_view key;  ///< its key in a system file's `stops` entries and Python's stop dicts
  bool required;         ///< a `stops` entry must give it (else the paper's stop's value)
};

inline constexpr std::array<StopParameterRow, 2> kStopParameterRows = {{
    {"xs", "stop position", "position", "finite", [](double v) { return std::isfinite(v); },
     &StopParameters::position, "position", true},
    {"r", "coefficient of restitution", "restitution", "in [0, 1]",
     [](double v) { return v >= 0 && v <= 1; }, &StopParameters::restitution, "restitution", false},
}};

/// The name of a stop's parameter as files and the command line write it:
/// `base` for the first stop (xs, r), base<k> for stop k >= 2 (xs2, r2).
std::string StopParameterName(std::string_view base, int stop);

/// How messages name parameter `row` of stop `stop` of `stop_count`:
/// "xs (stop position)" for a sole stop, "xs2 (position of stop 2)".
std::string StopParameterLabel(const StopParameterRow& row, int stop, int stop_count);

/// Throws InvalidInput naming the first parameter of stop `stop` (of
/// `stop_count`) outside its row's range.
void CheckStopParameterRanges(const StopParameters& values, int stop, int stop_count);

}  // namespace impactkit
