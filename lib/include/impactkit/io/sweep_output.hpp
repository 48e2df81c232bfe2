#pragma once
/// \file sweep_output.hpp
/// A sweep's tables (`impactkit sweep --summary` and `--out`): their
/// columns and rows, in the library so that every face writes one schema.

#include <string>
#include <vector>

#include "impactkit/analysis/sweep.hpp"
#include "impactkit/io/csv.hpp"

namespace impactkit {

/// One row per value: `PARAMETER,kind,p,q,range_xN,range_x1,range_xN_min,
/// range_x1_min,impacts,velocity_min,velocity_max,lyapunov,restarted` — the largest and
/// smallest per-period max − min, the impact speeds' extremes, the largest
/// Lyapunov exponent where computed; kind, p, q as grid_output.hpp's
/// LabelsOf; an empty field where undefined.
std::vector<std::string> SweepSummaryColumns(const std::string& parameter);
/// The row of one value, its line break included.
std::string SweepSummaryRow(const SweepPoint& point);

/// One row per recorded impact: `PARAMETER,t,phase,velocity,stop` (t from
/// the start of that value's run, velocity the speed towards the stop, stop counted from 1
/// as in system files).
std::vector<std::string> SweepImpactColumns(const std::string& parameter);
void WriteSweepImpactRows(CsvWriter& csv, const SweepResult& result);

}  // namespace impactkit
