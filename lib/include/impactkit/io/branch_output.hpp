#pragma once
/// \file branch_output.hpp
/// A branch as result files carry it: the one schema of its CSV table and
/// its JSON object, written by `impactkit continue`, `diagram` and `paper`
/// (docs/cli.md) and by Python's Branch.to_json and write_csv.

#include <string>
#include <string_view>
#include <vector>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/io/csv.hpp"

namespace impactkit {

/// The CSV columns of `branch`: the parameter (by its name), `arclength`;
/// for a sticking family `stick_phase1..k`, `release_phase1..k`,
/// `stuck1..k`; the leading impacts' `phase1..` and `v1..`, `range_xN`,
/// the multipliers' moduli `mod1..`, `stable`, `clearance`, `depth` (a
/// sticking family's `contact_margin`) and `special` (a special point's
/// type by name, empty for an ordinary point).
std::vector<std::string> BranchColumns(const Branch& branch);

/// One row per point of `branch`, in BranchColumns' order. Never a NaN: a
/// flight without an interior maximum has the range as its clearance.
void WriteBranchRows(CsvWriter& csv, const Branch& branch);

/// The JSON object of `branch`, as text: `label` and `origin` name it in a
/// network ("main", "pd3"; how it was started), then its section, p, q,
/// releases, stop (from 1), point count, end (and begin) reason and
/// message, seconds, `param_range` and `special_points`.
std::string BranchJson(const Branch& branch, std::string_view label, std::string_view origin);

/// A grazing's normal form, with its prediction once made, as the JSON
/// object a grazing's `normal_form` holds in these files, as text.
std::string GrazingNormalFormJson(const GrazingNormalForm& form);

}  // namespace impactkit
