// Two-dimensional grids (analysis/grid_cell, grid_task, parameter_map,
// basins) and their checkpoints (io/checkpoint): each checked against a
// value computed another way.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <set>

#include "closed_form_sdof.hpp"
#include "impactkit/analysis/basins.hpp"
#include "impactkit/analysis/parameter_map.hpp"
#include "impactkit/io/checkpoint.hpp"
#include "impactkit/model/parameters.hpp"

using namespace impactkit;
using namespace impactkit::testing;

namespace {

/// The cells a task computes, unit by unit on one thread: the reference
/// for the threaded runs.
std::vector<GridCell> Sequential(const GridTask& task) {
  std::vector<GridCell> cells;
  for (int unit = 0; unit < task.Units(); ++unit) {
    const std::vector<GridCell> part = task.RunUnit(unit);
    cells.insert(cells.end(), part.begin(), part.end());
  }
  return cells;
}

std::vector<GridCell> Threaded(const GridTask& task, int threads) {
  int next = 0;
  std::vector<GridCell> cells;
  RunUnits(
      task, threads, [&] { return next < task.Units() ? next++ : -1; },
      [&](int, std::vector<GridCell>& part) {
        cells.insert(cells.end(), part.begin(), part.end());
      });
  return InIndexOrder(std::move(cells), task.Cells());
}

/// Bitwise equality, NaN included.
bool Same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool Same(const GridCell& a, const GridCell& b) {
  if (a.orbit.size() != b.orbit.size()) return false;
  for (std::size_t i = 0; i < a.orbit.size(); ++i) {
    if (!Same(a.orbit[i].phase, b.orbit[i].phase) ||
        !Same(a.orbit[i].velocity, b.orbit[i].velocity)) {
      return false;
    }
  }
  return a.index == b.index && a.kind == b.kind && a.p == b.p && a.q == b.q &&
         Same(a.max_v, b.max_v) && Same(a.range_xN, b.range_xN) && Same(a.lyapunov, b.lyapunov) &&
         a.restarted == b.restarted && a.events == b.events;
}

ParameterMapOptions SmallMap() {
  ParameterMapOptions options;
  options.row.from = 0.6;
  options.row.to = 2.4;
  options.row.steps = 7;
  options.row.transient_periods = 200;
  options.row.recorded_periods = 40;
  options.row.chunk_values = 3;
  options.parameter2 = "r";
  options.from2 = 0.5;
  options.to2 = 0.9;
  options.steps2 = 3;
  return options;
}

}  // namespace

TEST_CASE("a cell's text form reads back to the same bits", "[grid]") {
  GridCell cell;
  cell.index = 123456789012;
  cell.kind = MotionKind::kSticking;
  cell.q = 3;
  cell.max_v = 0.1 + 0.2;  // not a short decimal
  cell.range_xN = std::nextafter(1.0, 2.0);
  cell.lyapunov = std::numeric_limits<double>::quiet_NaN();
  cell.restarted = true;
  cell.events = 98765;
  cell.orbit = {{std::numbers::pi / 3, -1e-300}, {5e-324, 1.7976931348623157e308}};
  CHECK(Same(CellFromText(CellToText(cell)), cell));
  CHECK_THROWS_AS(CellFromText("1 periodic 1 1 0.5"), InvalidInput);
  CHECK_THROWS_AS(CellFromText("1 frobnicated 1 1 0 0 0 0 0 0"), InvalidInput);
  CHECK_THROWS_AS(CellFromText(CellToText(cell) + " 7"), InvalidInput);
}

TEST_CASE("a map's rows are the sweeps of its first parameter", "[grid]") {
  const System system = PaperSystem();
  const ParameterMapTask task(system, SmallMap());
  REQUIRE(task.Cells() == 21);
  const std::vector<GridCell> cells = Sequential(task);
  for (int row = 0; row < 3; ++row) {
    System at_r = system;
    SetParameter(at_r, "r", task.Values2()[row]);
    const SweepResult sweep = RunSweep(at_r, SmallMap().row);
    for (int k = 0; k < 7; ++k) {
      CHECK(Same(cells[row * 7 + k], CellOf(row * 7 + k, sweep.points[k])));
    }
  }
  CHECK(task.Values2()[1] == 0.7);
}

TEST_CASE("a grid's cells do not depend on the number of threads", "[grid]") {
  const ParameterMapTask task(PaperSystem(), SmallMap());
  const std::vector<GridCell> one = Sequential(task), three = Threaded(task, 3);
  REQUIRE(one.size() == three.size());
  for (std::size_t i = 0; i < one.size(); ++i) CHECK(Same(one[i], three[i]));
}

TEST_CASE("bad map and basin input is refused before any work", "[grid]") {
  ParameterMapOptions same = SmallMap();
  same.parameter2 = "omega";
  CHECK_THROWS_AS(ParameterMapTask(PaperSystem(), same), InvalidInput);
  ParameterMapOptions invalid = SmallMap();
  invalid.to2 = 1.5;  // r > 1 in the last row
  CHECK_THROWS_WITH(ParameterMapTask(PaperSystem(), invalid),
                    Catch::Contains("map at omega = 0.6, r = 1.5"));
  BasinsOptions basins;
  basins.coordinate1 = "x3";
  CHECK_THROWS_WITH(BasinsTask(PaperSystem(), basins),
                    Catch::Contains("unknown state coordinate 'x3'"));
  CHECK_THROWS_AS(InIndexOrder({GridCell{}, GridCell{}}, 2), InvalidInput);  // index 0 twice
}

TEST_CASE("basins of the N = 1 oscillator: its closed-form P(1,1) and the non-impacting orbit",
          "[grid]") {
  // At xs = 0.3, Ω = 1.7 the free response (amplitude 0.2635) misses the
  // stop, and the closed form has a stable P(1,1) beside it (its other root
  // is a saddle): two attractors, the non-impacting one near its own
  // response at t = 0, (-0.26, 0.04).
  SdofParameters reference;
  reference.xs = 0.3;
  reference.omega = 1.7;
  const System system = UniformChain(ChainParameters{1, reference.m, reference.k, reference.c},
                                     Eigen::VectorXd::Constant(1, reference.a), reference.omega,
                                     reference.xs, reference.r);
  std::vector<SdofP11> stable;
  for (const SdofP11& o : SdofP11Solutions(reference)) {
    if (std::abs(Eigenvalues2(SdofP11Jacobian(reference, o))[0]) < 1.0 &&
        SdofCheckFlight(reference, o).Valid()) {
      stable.push_back(o);
    }
  }
  REQUIRE(stable.size() == 1);
  REQUIRE(reference.SteadyAmplitude() < reference.xs);

  BasinsOptions options;
  options.run.transient_periods = 300;
  options.run.recorded_periods = 20;
  options.coordinate1 = "x1";
  options.from1 = -0.4;
  options.to1 = -0.1;
  options.steps1 = 4;
  options.coordinate2 = "v1";
  options.from2 = -0.1;
  options.to2 = 0.2;
  options.steps2 = 4;
  const BasinsTask task(system, options);
  const std::vector<GridCell> cells = Threaded(task, 2);
  const BasinsResult result =
      IdentifyAttractors(cells, system.ForcingPeriod(), options.orbit_tolerance);
  REQUIRE(result.attractors.size() == 2);
  std::set<MotionKind> kinds;
  for (const Attractor& a : result.attractors) {
    kinds.insert(a.kind);
    if (a.kind != MotionKind::kPeriodic) continue;
    CHECK((a.p == 1 && a.q == 1));
    REQUIRE(!a.orbit.empty());
    for (const AttractorImpact& i : a.orbit) {
      CHECK(i.phase == Approx(std::fmod(stable[0].tau, reference.Period())).margin(1e-6));
      CHECK(i.velocity == Approx(stable[0].u).margin(1e-6));
    }
  }
  CHECK(kinds == std::set<MotionKind>{MotionKind::kPeriodic, MotionKind::kNonImpacting});
  CHECK(result.attractors[0].cells + result.attractors[1].cells == 16);
}

TEST_CASE("attractors are told apart by their orbits, phases compared across T", "[grid]") {
  const double period = 2.0;
  auto cell = [](std::int64_t index, double phase, double velocity) {
    GridCell c;
    c.index = index;
    c.kind = MotionKind::kPeriodic;
    c.p = c.q = 1;
    c.orbit = {{phase, velocity}};
    return c;
  };
  // Two P(1,1) orbits; the third cell is the first's orbit seen across the
  // period's end (phase 1.99999 against 1e-6), the fourth the second's.
  const std::vector<GridCell> cells = {cell(0, 1e-6, 1.0), cell(1, 0.5, 1.0),
                                       cell(2, period - 1e-5, 1.00001), cell(3, 0.5, 1.00001)};
  const BasinsResult result = IdentifyAttractors(cells, period, 1e-4);
  REQUIRE(result.attractors.size() == 2);
  CHECK(result.attractor == std::vector<int>{0, 1, 0, 1});
  CHECK(result.attractors[0].cells == 2);
  CHECK(result.attractors[1].first_cell == 1);
}

TEST_CASE("a checkpoint returns what it recorded and refuses another run", "[grid]") {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / "impactkit-test-checkpoint";
  std::filesystem::remove_all(directory);
  GridCell a;
  a.index = 4;
  a.max_v = 0.1 + 0.2;
  {
    Checkpoint checkpoint(directory, "run one", 3);
    CHECK(checkpoint.Finished().empty());
    checkpoint.Record(2, {a});
  }
  const Checkpoint reopened(directory, "run one", 3);
  REQUIRE(reopened.Finished().size() == 1);
  CHECK(Same(reopened.Finished().at(2).front(), a));
  CHECK_THROWS_WITH(Checkpoint(directory, "run two", 3), Catch::Contains("another run"));
  CHECK_THROWS_WITH(Checkpoint(directory, "run one", 4), Catch::Contains("another run"));
  std::filesystem::remove_all(directory);
}

namespace {

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("a checkpoint unit edited, cut or emptied is computed again, a damaged run.txt refused",
          "[grid]") {
  namespace fs = std::filesystem;
  const fs::path directory = fs::temp_directory_path() / "impactkit-test-checkpoint-damage";
  fs::remove_all(directory);
  auto cell = [](int index) {
    GridCell c;
    c.index = index;
    c.kind = MotionKind::kPeriodic;
    c.p = c.q = 1;
    c.max_v = 0.25 * index;
    return c;
  };
  {
    Checkpoint checkpoint(directory, "run", 5);
    for (int unit = 0; unit < 5; ++unit) checkpoint.Record(unit, {cell(unit)});
  }
  auto unit_file = [&](int unit) { return directory / ("unit-" + std::to_string(unit) + ".txt"); };
  std::string edited = ReadBytes(unit_file(1));
  edited.replace(edited.find("periodic"), 8, "chaotic");  // still a cell that parses
  WriteBytes(unit_file(1), edited);
  const std::string whole = ReadBytes(unit_file(2));
  WriteBytes(unit_file(2), whole.substr(0, whole.size() - 5));      // cut inside its checksum
  WriteBytes(unit_file(3), whole.substr(0, whole.find('\n') + 1));  // its checksum line gone
  WriteBytes(unit_file(4), "");

  const Checkpoint reopened(directory, "run", 5);
  REQUIRE(reopened.Finished().size() == 1);
  CHECK(Same(reopened.Finished().at(0).front(), cell(0)));
  REQUIRE(reopened.Damaged().size() == 4);
  const std::vector<std::string> reasons = {
      "its CRC-32 does not match its contents", "its last line is no CRC-32: cut short or added to",
      "its last line is no CRC-32: cut short or added to", "empty"};
  for (int k = 0; k < 4; ++k) {
    const DamagedUnit& damaged = reopened.Damaged()[k];
    CHECK(damaged.unit == k + 1);
    CHECK(damaged.file == unit_file(k + 1));
    CHECK(damaged.reason == reasons[k]);
  }

  // A unit recorded again replaces the damaged file.
  Checkpoint(directory, "run", 5).Record(1, {cell(1)});
  const Checkpoint repaired(directory, "run", 5);
  CHECK(Same(repaired.Finished().at(1).front(), cell(1)));
  CHECK(repaired.Damaged().size() == 3);

  // run.txt with one byte changed is damaged, not another run's.
  std::string run = ReadBytes(directory / "run.txt");
  run[0] = run[0] == 'r' ? 'R' : 'r';
  WriteBytes(directory / "run.txt", run);
  CHECK_THROWS_WITH(Checkpoint(directory, "run", 5),
                    Catch::Contains("run.txt is damaged") && !Catch::Contains("another run"));
  fs::remove_all(directory);
}
