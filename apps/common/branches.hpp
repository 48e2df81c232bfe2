#pragma once
/// \file common/branches.hpp
/// The branches of a diagram (impactkit/continuation/diagram.hpp) as the
/// command line shows them: labelled, printed, written as CSV and JSON,
/// drawn — shared by `impactkit continue`, `impactkit diagram` and
/// `impactkit paper`. The tracing, switching and the files' schema
/// (io/branch_output.hpp) are the library's.

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/plot.hpp"
#include "impactkit/continuation/diagram.hpp"
#include "impactkit/io/branch_output.hpp"
#include "impactkit/io/diagram_output.hpp"

namespace impactkit::cli {

/// A traced branch as the outputs name it.
struct TracedBranch {
  std::string label;   ///< "main" (or "seed2", ...), "pd1", "graze2", "bp3"
  std::string origin;  ///< how it was started
  Branch branch;
};

/// The diagram's branches, labelled: the first seed's "main", other seeds'
/// "seed<k>", and the born ones by the node they start from and their index
/// ("pd1" at a period doubling, "graze2" at a grazing, "bp3" at a branch
/// point).
std::vector<TracedBranch> LabelBranches(const Diagram& diagram);

/// FILE.csv for the main branch, FILE.<label>.csv for the others.
std::string BranchPath(const std::string& path, const std::string& label);

/// The library's JSON object of the branch (io/branch_output.hpp), under
/// its label and origin.
nlohmann::json BranchJson(const TracedBranch& traced);

/// The key entry of a special-point type, with the marker (shape and
/// colour) that type has in every chart; its data are left to the caller.
Curve SpecialPointMarks(SpecialPointType type);

/// Two key entries in `color`, "stable" solid and "unstable" dashed, that
/// explain the line styles once for all branches.
std::vector<Curve> StabilityKey(const std::string& color = "#555555");

/// Impact velocities against the parameter, a colour per branch (one key
/// entry each; a branch lying on another is drawn once, the entry naming
/// both), stable stretches solid, unstable dashed, special points marked by
/// type.
LineChart BranchChart(const std::vector<TracedBranch>& branches);

/// "P(1,1) stable 0.856 to 1.613, unstable 1.613 to 2.5": the branch's
/// stretches of one stability.
std::string DescribeStability(const Branch& branch);

/// The branch, its special points and its ends, on stdout.
void PrintBranch(const TracedBranch& traced);

}  // namespace impactkit::cli
