#pragma once
/// \file continue/branches.hpp
/// Continued branches as the command line shows them: traced with the
/// branches born at their special points, printed, written as CSV and JSON,
/// drawn — shared by `impactkit continue` and `impactkit paper`.

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/plot.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/io/csv.hpp"

namespace impactkit::cli {

/// A progress line on stderr while a person watches (silent otherwise).
class BranchProgress {
 public:
  explicit BranchProgress(std::string parameter);
  /// Erases the line.
  ~BranchProgress();
  BranchProgress(const BranchProgress&) = delete;
  BranchProgress& operator=(const BranchProgress&) = delete;

  /// One more point on the branch `label`.
  void operator()(const std::string& label, const BranchPoint& point);

 private:
  const bool enabled_;
  const std::string parameter_;
  int points_ = 0;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

/// A traced branch and where it came from.
struct TracedBranch {
  std::string label;   ///< "main", "pd1", "graze1", ...
  std::string origin;  ///< how it was started
  Branch branch;
};

/// Which branches to start at the special points of a traced branch.
struct BranchSwitches {
  bool period_doubling = false;  ///< the P(2p,2q) branch at each period doubling
  bool grazing = false;          ///< the orbit with one impact more or fewer at a grazing
};

/// The branch through `start` ("main"), then the branches born at its
/// special points as `switches` asks ("pd1", "graze2", ...).
std::vector<TracedBranch> TraceBranches(const System& system, const PeriodicOrbit& start,
                                        const ContinuationOptions& options, BranchSwitches switches,
                                        BranchProgress& progress);

/// The CSV columns of `branch` (docs/cli.md, `impactkit continue`).
std::vector<std::string> BranchColumns(const Branch& branch);

/// One row per point of `branch`, in the columns of BranchColumns.
void WriteBranchRows(CsvWriter& csv, const Branch& branch);

/// FILE.csv for the main branch, FILE.<label>.csv for the others.
std::string BranchPath(const std::string& path, const std::string& label);

/// label, origin, p, q, points, end_reason (begin_reason), param_range, special_points.
nlohmann::json BranchJson(const TracedBranch& traced);

/// Impact velocities against the parameter: stable solid, unstable dashed,
/// special points marked.
LineChart BranchChart(const std::vector<TracedBranch>& branches);

/// The branch, its special points and its ends, on stdout.
void PrintBranch(const TracedBranch& traced);

}  // namespace impactkit::cli
