#pragma once
/// \file grazing_output.hpp
/// A diagram's grazings, each predicted and checked by sweeps
/// (`impactkit diagram --grazings`, analysis/grazing_prediction.hpp's
/// CheckGrazings), as one JSON document and as lines of text.

#include <string>
#include <vector>

#include "impactkit/analysis/grazing_prediction.hpp"

namespace impactkit {

/// `parameter` and `grazings`: one object per grazing, in parameter order,
/// with `param`, `grazing_orbit` ("P(1,1)", or "non-impacting"), `contact`
/// (`new` or `vanishing`: how it was located), `prediction` (as a normal
/// form's, io/branch_output.hpp) and `sweeps`: `values`, the motions
/// `toward` (swept from before the grazing past it) and `back`,
/// `past_distance`, `past` (toward's motion there), `expected` (the
/// prediction's there), `follows`, `agrees` and `hysteresis`.
std::string GrazingChecksJson(const std::vector<GrazingCheck>& checks,
                              const std::string& parameter);

/// One line: "omega = 0.8564343745, P(1,1) (new contact): predicted P(3,2)
/// (jump), swept P(3,2): agrees; hysteresis".
std::string DescribeGrazingCheck(const GrazingCheck& check, const std::string& parameter);

}  // namespace impactkit
