#pragma once
/// \file curve/output.hpp
/// Two-parameter curves as `impactkit curve` shows them: the
/// parameter-plane chart and the summary lines. Their files' schema is the
/// library's (io/curve_output.hpp).

#include <string>
#include <vector>

#include "common/plot.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/io/curve_output.hpp"

namespace impactkit::cli {

/// The curves in the parameter plane, codim-2 points marked and labelled
/// with their type, one legend entry per kind.
LineChart CurveChart(const std::vector<impactkit::Curve>& curves);

/// The curve, its ends and codim-2 points, on stdout.
void PrintCurve(const impactkit::Curve& curve);

}  // namespace impactkit::cli
