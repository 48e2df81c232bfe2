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

/// The curves of the files `paths` in the plane (x_name, y_name), as
/// polylines titled "fold P(1,2)"; curves in other parameters are left out.
/// Throws InvalidInput naming the file and what is wrong.
std::vector<Curve> ReadCurves(const std::vector<std::string>& paths, const std::string& x_name,
                              const std::string& y_name);

}  // namespace impactkit::cli
