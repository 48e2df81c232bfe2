#pragma once
/// \file normal_form_json.hpp (private)
/// A grazing's normal form (orbits/grazing_normal_form.hpp) as the JSON
/// object that branch, diagram and paper files carry under `normal_form`
/// (docs/continuation.md, "What a grazing will do").

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "impactkit/orbits/grazing_normal_form.hpp"

namespace impactkit {

/// `parameter`, `param` (its value at the grazing), `stop` (from 1),
/// `time`, `phase`, `touch`, `linear` (rows), `eigenvalues` ([re, im]
/// pairs, by decreasing modulus), `normal`, `curvature`, `root`,
/// `unfolding`, `reduced` ({lambda, kappa, s, break_rate, dominance} or
/// null) and, when null, `reduction_note`; once predicted, `prediction`
/// (side, local, motion, scenario, distance, one_dimensional or null,
/// description, and the normal form's attractors at each distance).
nlohmann::json NormalFormJson(const GrazingNormalForm& form);

/// A prediction's object: `side`, `local`, `unstable_grazing_orbit`,
/// `motion`, `scenario`, `distance`, `one_dimensional` (or null),
/// `description` and `attractors`.
nlohmann::json PredictionJson(const GrazingPrediction& prediction);

/// Adds `normal_form` to a grazing's JSON object `j`: the form, or null and
/// `normal_form_note` saying why there is none.
void AddNormalForm(const std::optional<GrazingNormalForm>& form, const std::string& note,
                   nlohmann::json* j);

}  // namespace impactkit
