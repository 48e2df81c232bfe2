#pragma once
/// \file curve_output.hpp
/// Two-parameter curves as result files carry them: the curves file of
/// docs/curves-json.md (which `impactkit map --curves` reads) and the CSV
/// table, the one schema that `impactkit curve` and Python's Curve write.

#include <string>
#include <vector>

#include "impactkit/continuation/curve.hpp"
#include "impactkit/io/csv.hpp"

namespace impactkit {

/// Multipliers farther outside the unit circle than this count as
/// unstable (`outside`): the curve's own critical multiplier, on the
/// circle to the corrector's tolerance, does not.
inline constexpr double kOutsideUnitCircle = 1e-6;

/// The curves file, as text: `params`, `curves` (each with type, p, q,
/// params, begin and end reasons and messages, seconds and its points with
/// their multipliers and `outside`) and `codim2_points`; with `system_json`
/// (SystemToJson's text) not empty, `system` too.
std::string CurvesJson(const std::vector<Curve>& curves, const std::string& system_json = "");

/// The CSV columns of `curve`: its two parameters by name, arclength,
/// mod1.. (the multipliers' moduli), outside, codim2.
std::vector<std::string> CurveColumns(const Curve& curve);
/// One row per point, the located codimension-two points named in the
/// last column; a point without an orbit (the response's grazing, a corner
/// where an impact vanishes) has empty multiplier cells.
void WriteCurveRows(CsvWriter& csv, const Curve& curve);

}  // namespace impactkit
