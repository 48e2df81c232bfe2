#pragma once
/// \file simulate/summary.hpp
/// What `impactkit simulate` reports about its window: printed for a person,
/// and as JSON (--json) for scripts. Both say the same things.

#include <string>

#include "common/provenance.hpp"
#include "simulate/run.hpp"

namespace impactkit::cli {

/// "P(2,1)", "P(inf,1)", or "no period up to q = 10".
std::string MotionLabel(const WindowAnalysis& analysis);

/// The motion in words: "P(2,1) (2 impacts in 1 forcing period)",
/// "P(inf,1) sticking (...)", "no period up to q = 64 in the recorded window".
std::string DescribeMotion(const WindowAnalysis& analysis);

/// The printed summary, one "key: value" line per topic, ending with the
/// files written.
std::string SummaryText(const SimulateResult& result);

/// The summary as a JSON document; the system in system-file form
/// (docs/system-files.md), with `provenance`.
std::string SummaryJson(const SimulateResult& result, const Provenance& provenance);

}  // namespace impactkit::cli
