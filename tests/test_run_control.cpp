// One RunControl for every long run (core/run_control.hpp): progress
// reports in order, and cancellation that returns what was done with
// termination kStopped, for sweeps, branches, curves and diagrams.

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "curve_plane.hpp"
#include "impactkit/analysis/parameter_map.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/continuation/diagram.hpp"
#include "impactkit/model/system.hpp"
#include "seeded_orbit.hpp"

namespace impactkit {
namespace {

/// The paper's P(1,1) at Ω = 1 and continuation options on [0.9, 1.3].
struct PaperBranchStart {
  BranchStart start;
  ContinuationOptions options;
};

PaperBranchStart P11() {
  const System system = PaperSystem(1.0);
  ContinuationOptions options;
  options.parameter = "omega";
  options.from = 0.9;
  options.to = 1.3;
  options.orbit.p = options.orbit.q = 1;
  return {{system, testing::SeededOrbit(system, 1, 1), {}}, options};
}

TEST_CASE("a branch reports each accepted point and stops when cancelled", "[run_control]") {
  const PaperBranchStart p11 = P11();
  std::vector<Progress> reports;
  const RunControl control([&](const Progress& progress) {
    reports.push_back(progress);
    if (reports.size() == 5) control.Cancel();
  });
  const Branch branch = ContinueBranch(p11.start, p11.options, control);
  CHECK(branch.end == Termination::kStopped);
  CHECK(branch.end_message == "stopped on request");
  REQUIRE(reports.size() == 5);
  // The start and the five points accepted before the cancellation.
  REQUIRE(branch.points.size() == 6);
  for (std::size_t k = 0; k < reports.size(); ++k) {
    CHECK(reports[k].stage == "branch");
    CHECK(reports[k].done == static_cast<std::int64_t>(k + 1));
    CHECK(reports[k].total == 0);
    CHECK(reports[k].parameter == branch.points[k + 1].parameter);
  }
  // Uncancelled, the same options follow the branch to its end.
  const Branch whole = ContinueBranch(p11.start, p11.options);
  CHECK(whole.end != Termination::kStopped);
  CHECK(whole.points.size() > branch.points.size());
}

TEST_CASE("a cancelled sweep returns its leading chunks, as the whole sweep has them",
          "[run_control]") {
  SweepOptions options;
  options.from = 1.0;
  options.to = 2.0;
  options.steps = 24;
  options.transient_periods = 50;
  options.recorded_periods = 20;
  options.chunk_values = 4;
  options.threads = 2;
  const System system = PaperSystem();
  std::vector<std::int64_t> done;
  const RunControl control([&](const Progress& progress) {
    CHECK(progress.stage == "sweep");
    CHECK(progress.total == 24);
    done.push_back(progress.done);
    if (progress.done == 3) control.Cancel();
  });
  const SweepResult stopped = RunSweep(system, options, control);
  const SweepResult whole = RunSweep(system, options);
  CHECK(whole.termination == Termination::kCompleted);
  CHECK(whole.iterations == 24);
  REQUIRE(stopped.termination == Termination::kStopped);
  // Reports come one at a time, counting up.
  for (std::size_t k = 0; k < done.size(); ++k) CHECK(done[k] == static_cast<std::int64_t>(k + 1));
  // The chunks running when cancelled (one per thread) finish; no other starts.
  CHECK(stopped.points.size() % 4 == 0);
  CHECK(stopped.points.size() <= 8);
  CHECK(stopped.iterations == static_cast<std::int64_t>(stopped.points.size()));
  for (std::size_t k = 0; k < stopped.points.size(); ++k) {
    CHECK(stopped.points[k].value == whole.points[k].value);
    CHECK(stopped.points[k].classification.kind == whole.points[k].classification.kind);
    CHECK(stopped.points[k].impacts.size() == whole.points[k].impacts.size());
  }
}

TEST_CASE("a cancelled grid returns the cells of its finished units, as the whole grid has them",
          "[run_control]") {
  ParameterMapOptions options;
  options.row.from = 1.0;
  options.row.to = 2.0;
  options.row.steps = 6;
  options.row.transient_periods = 40;
  options.row.recorded_periods = 20;
  options.row.chunk_values = 3;
  options.from2 = 0.6;
  options.to2 = 0.8;
  options.steps2 = 3;
  const ParameterMapTask task(PaperSystem(), options);
  REQUIRE(task.Units() == 6);
  std::vector<std::int64_t> done;
  const RunControl control([&](const Progress& progress) {
    CHECK(progress.stage == "grid");
    CHECK(progress.total == 18);
    done.push_back(progress.done);
    control.Cancel();
  });
  const GridResult stopped = RunGrid(task, 2, control);
  const GridResult whole = RunGrid(task, 2);
  CHECK(whole.termination == Termination::kCompleted);
  REQUIRE(whole.cells.size() == 18);
  REQUIRE(stopped.termination == Termination::kStopped);
  // One unit per thread was running when cancelled: one or two finish.
  CHECK((stopped.iterations == 1 || stopped.iterations == 2));
  CHECK(stopped.cells.size() == 3 * static_cast<std::size_t>(stopped.iterations));
  CHECK(done.back() == static_cast<std::int64_t>(stopped.cells.size()));
  for (const GridCell& cell : stopped.cells) {
    const GridCell& same = whole.cells[static_cast<std::size_t>(cell.index)];
    CHECK(cell.kind == same.kind);
    CHECK(cell.p == same.p);
    CHECK(cell.q == same.q);
    CHECK(cell.max_v == same.max_v);
  }
}

TEST_CASE("a cancelled diagram stops its branches and the network", "[run_control]") {
  const PaperBranchStart p11 = P11();
  DiagramOptions options;
  options.continuation = p11.options;
  int reports = 0;
  const RunControl control([&](const Progress& progress) {
    CHECK(progress.stage == "diagram");
    CHECK(progress.done == 0);  // the seed's branch is the first
    CHECK(std::isfinite(progress.parameter));
    if (++reports == 3) control.Cancel();
  });
  const Diagram diagram =
      TraceDiagram({{p11.start.system, p11.start.orbit, "seed", ContinuationDirection::kBoth}},
                   options, control);
  CHECK(diagram.termination == Termination::kStopped);
  REQUIRE(diagram.branches.size() == 1);
  CHECK(diagram.branches[0].branch.end == Termination::kStopped);
  CHECK(diagram.iterations == 1);
}

TEST_CASE("a cancelled curve ends both ways at once", "[run_control]") {
  const CurveStart start =
      testing::Start(PaperSystem(1.5), SpecialPointType::kPeriodDoubling, 1, 1);
  int reports = 0;
  const RunControl control([&](const Progress& progress) {
    CHECK(progress.stage == "curve");
    CHECK(std::isfinite(progress.parameter2));
    if (++reports == 4) control.Cancel();
  });
  const Curve curve = ContinueCurve(start, testing::Plane("r", 0.5, 0.95, 1, 1), control);
  CHECK(curve.end == Termination::kStopped);
  CHECK(curve.begin == Termination::kStopped);
  // The start and three points the first way (four reports); the other
  // way stops at the start, reported again.
  CHECK(curve.points.size() == 4);
}

}  // namespace
}  // namespace impactkit
