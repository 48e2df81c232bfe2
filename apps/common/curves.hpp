#pragma once
/// \file common/curves.hpp
/// Reading the curves of `impactkit curve --json` to overlay on a map. The
/// format assumed (issue 11): {"curves": [{"type": "fold", "p": 1, "q": 2,
/// "params": ["omega", "r"], "points": [{"omega": 1.1, "r": 0.7, ...}, ...]},
/// ...]}; other keys are ignored.

#include <string>
#include <vector>

#include "common/plot.hpp"

namespace impactkit::cli {

/// A two-parameter curve's entry in a figure's key, the same in every figure
/// (examples/parameter_planes.sh writes the same words): "P(1,2) fold",
/// "P(1,1) period doubling"; the grazing of the non-impacting response (p =
/// 0) by what it means for the impacting orbits, "impact of P(1,q) vanishes".
std::string CurveKey(std::string type, int p, int q);

/// The curves of the files `paths` in the plane (x_name, y_name), as
/// polylines titled by CurveKey; curves in other parameters are left out.
/// Throws InvalidInput naming the file and what is wrong.
std::vector<Curve> ReadCurves(const std::vector<std::string>& paths, const std::string& x_name,
                              const std::string& y_name);

}  // namespace impactkit::cli
