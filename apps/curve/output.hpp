#pragma once
/// \file curve/output.hpp
/// Two-parameter curves as `impactkit curve` writes them: the JSON format
/// of docs/curves-json.md (which `impactkit map --curves` reads), the CSV
/// table, the parameter-plane chart and the summary lines.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/plot.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/io/csv.hpp"

namespace impactkit::cli {

/// Multipliers farther outside the unit circle than this count as
/// unstable: the curve's own critical multiplier (on the circle to the
/// corrector's tolerance) does not.
inline constexpr double kOutsideUnitCircle = 1e-6;

/// {"provenance", "params", "curves": [...], "codim2_points": [...], "system"}.
nlohmann::json CurvesJson(const std::vector<impactkit::Curve>& curves,
                          const nlohmann::json& provenance, const std::string& system_json);

/// name1, name2, arclength, mod1.., outside, codim2.
std::vector<std::string> CurveColumns(const impactkit::Curve& curve);
/// One row per point, the located codim-2 points named in the last column.
void WriteCurveRows(CsvWriter& csv, const impactkit::Curve& curve);

/// The curves in the parameter plane, codim-2 points marked and labelled
/// with their type, one legend entry per kind.
LineChart CurveChart(const std::vector<impactkit::Curve>& curves);

/// The curve, its ends and codim-2 points, on stdout.
void PrintCurve(const impactkit::Curve& curve);

}  // namespace impactkit::cli
