/// Tests of the io area: system files (JSON, TOML), CSV tables,
/// whole-or-nothing output files and the colours of motion classes.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "impactkit/io/class_colors.hpp"
#include "impactkit/io/csv.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/modal.hpp"
#include "impactkit/model/parameters.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;
using namespace impactkit;
namespace fs = std::filesystem;

namespace {

/// A fresh directory under the system's temporary directory, removed with
/// everything in it when the test ends, passed or failed.
class ScratchDir {
 public:
  ScratchDir() {
    std::random_device random;
    const fs::path base = fs::temp_directory_path();
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ =
          base / ("impactkit-test-io-" + std::to_string(random()) + "-" + std::to_string(random()));
      if (fs::create_directory(path_)) return;
    }
    throw std::runtime_error("cannot create a scratch directory in " + base.string());
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const fs::path& Path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

  /// The names in the directory, sorted: what a run left behind, temporary
  /// files included (they are hidden, not absent).
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  REQUIRE(out.good());
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The lines of `text`, without their '\n'.
std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The message of the `Error` that `action` throws; a failed check (and "")
/// if it throws nothing. Any other exception fails the test case.
template <typename Error, typename Action>
std::string MessageOf(Action&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  FAIL_CHECK("no exception thrown");
  return "";
}

/// Field by field, exactly: every caller expects bit-identical values (a
/// lossless round trip, or values the reader takes verbatim from a literal).
void CheckSameSystem(const System& actual, const System& expected) {
  REQUIRE(actual.Dof() == expected.Dof());
  REQUIRE(actual.mass.cols() == expected.mass.cols());
  REQUIRE(actual.damping.rows() == expected.damping.rows());
  REQUIRE(actual.damping.cols() == expected.damping.cols());
  REQUIRE(actual.stiffness.rows() == expected.stiffness.rows());
  REQUIRE(actual.stiffness.cols() == expected.stiffness.cols());
  REQUIRE(actual.forcing.size() == expected.forcing.size());
  CHECK(actual.mass == expected.mass);
  CHECK(actual.damping == expected.damping);
  CHECK(actual.stiffness == expected.stiffness);
  CHECK(actual.forcing == expected.forcing);
  CHECK(actual.omega == expected.omega);
  CHECK(actual.stops[0].position == expected.stops[0].position);
  CHECK(actual.stops[0].restitution == expected.stops[0].restitution);
  CHECK(actual.stops[0].dof == expected.stops[0].dof);
  REQUIRE(actual.chain.has_value() == expected.chain.has_value());
  if (expected.chain) {
    CHECK(actual.chain->dof == expected.chain->dof);
    CHECK(actual.chain->mass == expected.chain->mass);
    CHECK(actual.chain->stiffness == expected.chain->stiffness);
    CHECK(actual.chain->damping == expected.chain->damping);
  }
}

System FromJson(const std::string& text) {
  return ParseSystem(text, SystemFileFormat::kJson, "test.json");
}

System FromToml(const std::string& text) {
  return ParseSystem(text, SystemFileFormat::kToml, "test.toml");
}

/// The chain coupling matrix E written out, not computed by the library.
Eigen::MatrixXd E2() { return (Eigen::MatrixXd(2, 2) << 2, -1, -1, 1).finished(); }
Eigen::MatrixXd E3() { return (Eigen::MatrixXd(3, 3) << 2, -1, 0, -1, 2, -1, 0, -1, 1).finished(); }

/// The three-mass system of docs/system-files.md and
/// examples/systems/three-mass.toml, built directly.
System ThreeMassSystem() {
  Eigen::MatrixXd mass(3, 3), stiffness(3, 3), damping(3, 3);
  mass << 1.0, 0.0, 0.0, 0.0, 0.8, 0.0, 0.0, 0.0, 1.2;
  stiffness << 2.5, -1.5, 0.0, -1.5, 2.5, -1.0, 0.0, -1.0, 1.0;
  damping << 0.15, -0.05, 0.0, -0.05, 0.10, -0.05, 0.0, -0.05, 0.05;
  return GeneralSystem(mass, damping, stiffness, Eigen::Vector3d(0.5, 0.0, 0.0), 1.2, 0.1, 0.7, 2);
}

constexpr const char* kThreeMassToml = R"(# the three-mass example
mass = [
  [1.0, 0.0, 0.0],
  [0.0, 0.8, 0.0],
  [0.0, 0.0, 1.2],
]
stiffness = [
  [ 2.5, -1.5,  0.0],
  [-1.5,  2.5, -1.0],
  [ 0.0, -1.0,  1.0],
]
damping = [
  [ 0.15, -0.05,  0.0 ],
  [-0.05,  0.10, -0.05],
  [ 0.0,  -0.05,  0.05],
]
forcing = [0.5, 0.0, 0.0]
omega = 1.2
xs = 0.1
r = 0.7
contact_dof = 3
)";

constexpr const char* kThreeMassJson = R"({
  "mass": [[1.0, 0.0, 0.0], [0.0, 0.8, 0.0], [0.0, 0.0, 1.2]],
  "stiffness": [[2.5, -1.5, 0.0], [-1.5, 2.5, -1.0], [0.0, -1.0, 1.0]],
  "damping": [[0.15, -0.05, 0.0], [-0.05, 0.10, -0.05], [0.0, -0.05, 0.05]],
  "forcing": [0.5, 0.0, 0.0],
  "omega": 1.2, "xs": 0.1, "r": 0.7, "contact_dof": 3
})";

}  // namespace

// Exact equality throughout the round trips: SystemToJson prints each double
// in the shortest decimal form that reads back to the same double, and the
// JSON reader rounds correctly, so nothing may change, not even in the last
// bit. The values are chosen to have no short decimal form (1/3, 1/7) or to
// be extreme (1e-300), where a fixed-precision format would lose bits.

TEST_CASE("SystemToJson reads back to the same uniform chain", "[io]") {
  const System chain = UniformChain(
      {3, 1.0 / 3.0, 2.7, 0.1}, Eigen::Vector3d(0.1, -1.0 / 3.0, 1e-300), 1.0 / 7.0, -0.05, 0.85);
  const std::string json = SystemToJson(chain);
  INFO(json);
  // The chain form: m, k, c and n stay changeable by name after reading.
  CHECK_THAT(json, Contains("\"chain\""));
  CHECK_THAT(json, !Contains("\"mass\""));
  CheckSameSystem(ParseSystem(json, SystemFileFormat::kJson, "chain.json"), chain);
}

TEST_CASE("SystemToJson reads back to the same general system", "[io]") {
  Eigen::MatrixXd mass(3, 3), damping(3, 3), stiffness(3, 3);
  mass << 1.0, 0.1, 0.0, 0.1, 0.8, 0.0, 0.0, 0.0, 1.0 / 3.0;
  // Diagonally dominant with a non-negative diagonal, hence positive
  // semi-definite; not of the form a M + b K.
  damping << 0.15, -1.0 / 30.0, 0.0, -1.0 / 30.0, 0.1, -0.05, 0.0, -0.05, 0.05;
  stiffness << 2.5, -1.5, 0.0, -1.5, 2.5, -1.0, 0.0, -1.0, 1.0;
  // Contact on mass 1 (0-based 0), not the default last mass.
  const System general = GeneralSystem(
      mass, damping, stiffness, Eigen::Vector3d(0.5, -1.0 / 3.0, 0.25), 1.2, 1.0 / 7.0, 0.0, 0);
  REQUIRE_FALSE(ComputeModalData(general).proportional);
  const std::string json = SystemToJson(general);
  INFO(json);
  CHECK_THAT(json, Contains("\"contact_dof\": 1"));  // 1-based in files
  CheckSameSystem(ParseSystem(json, SystemFileFormat::kJson, "general.json"), general);

  // A uniform chain meeting the stop at another mass than the last has no
  // chain form: it must come back with the same matrices and contact DOF.
  System chain_elsewhere =
      UniformChain({2, 1.5, 1.0 / 3.0, 0.1}, Eigen::Vector2d(0.5, 0.25), 0.9, 0.1, 0.7);
  chain_elsewhere.stops[0].dof = 0;
  System expected = chain_elsewhere;
  expected.chain.reset();
  CheckSameSystem(FromJson(SystemToJson(chain_elsewhere)), expected);
}

TEST_CASE("every stop parameter row is a name, a stops key and a sole stop's key, read back",
          "[io]") {
  // hybrid/stop_parameters.hpp is where a stop parameter is declared: each
  // row must be set by name on stop 2 (xs2, r2, ...), appear under its key
  // in every `stops` entry and, for a sole stop, under its name at the top
  // level, and read back to the same value.
  System system = PaperSystem(0.9);
  system.stops.push_back({0, StopSide::kLower, -0.2, 0.5});
  for (const StopParameterRow& row : kStopParameterRows) {
    const std::string name = StopParameterName(row.name, 1);
    const double value = system.stops[1].*row.member + 1.0 / 64.0;
    SetParameter(system, name, value);
    CHECK(system.stops[1].*row.member == value);
    CHECK(GetParameter(system, name) == value);
  }
  const nlohmann::json written = nlohmann::json::parse(SystemToJson(system));
  for (const StopParameterRow& row : kStopParameterRows) {
    CHECK(written["stops"][1][std::string(row.key)].get<double>() == system.stops[1].*row.member);
  }
  CheckSameSystem(FromJson(written.dump()), system);

  System sole = PaperSystem(0.9);
  for (const StopParameterRow& row : kStopParameterRows) sole.stops[0].*row.member -= 1.0 / 64.0;
  const nlohmann::json one = nlohmann::json::parse(SystemToJson(sole));
  for (const StopParameterRow& row : kStopParameterRows) {
    CHECK(one[std::string(row.name)].get<double>() == sole.stops[0].*row.member);
  }
  CheckSameSystem(FromJson(one.dump()), sole);
}

TEST_CASE("a TOML and a JSON file of the same system read the same", "[io]") {
  ScratchDir dir;
  SECTION("general matrices (docs/system-files.md)") {
    WriteText(dir / "three.toml", kThreeMassToml);
    WriteText(dir / "three.json", kThreeMassJson);
    // Exact: both readers round a decimal literal correctly, as the compiler
    // does for the literals in ThreeMassSystem().
    CheckSameSystem(ReadSystemFile(dir / "three.toml"), ThreeMassSystem());
    CheckSameSystem(ReadSystemFile(dir / "three.json"), ThreeMassSystem());
  }
  SECTION("a uniform chain") {
    WriteText(dir / "chain.toml",
              "forcing = [0.25, 0, 0.125]\nomega = 1.4\nxs = 0.05\nr = 0.5\n"
              "[chain]\nn = 3\nm = 2.0\nk = 3\nc = 0.05\n");
    WriteText(dir / "chain.json",
              R"({"chain": {"n": 3, "m": 2, "k": 3.0, "c": 0.05},)"
              R"( "forcing": [0.25, 0, 0.125], "omega": 1.4, "xs": 0.05, "r": 0.5})");
    const System expected =
        GeneralSystem(2.0 * Eigen::MatrixXd::Identity(3, 3), 0.05 * E3(), 3.0 * E3(),
                      Eigen::Vector3d(0.25, 0.0, 0.125), 1.4, 0.05, 0.5);
    System toml = ReadSystemFile(dir / "chain.toml");
    const System json = ReadSystemFile(dir / "chain.json");
    CheckSameSystem(json, toml);
    REQUIRE(toml.chain);
    CHECK(toml.chain->dof == 3);
    CHECK(toml.chain->mass == 2.0);
    CHECK(toml.chain->stiffness == 3.0);
    CHECK(toml.chain->damping == 0.05);
    toml.chain.reset();
    CheckSameSystem(toml, expected);
  }
}

TEST_CASE("the shipped example system files", "[io]") {
  const fs::path systems = fs::path(IMPACTKIT_SOURCE_DIR) / "examples" / "systems";
  CheckSameSystem(ReadSystemFile(systems / "paper.json"), PaperSystem());
  CheckSameSystem(ReadSystemFile(systems / "three-mass.toml"), ThreeMassSystem());
}

TEST_CASE("missing fields take the paper's values", "[io]") {
  // The paper's values written out: m = k = 1, c = 0.1, A = (0.5, 0, ...),
  // Ω = 1, xs = 0.1, r = 0.7, contact at the last mass.
  const System paper = UniformChain({2, 1.0, 1.0, 0.1}, Eigen::Vector2d(0.5, 0.0), 1.0, 0.1, 0.7);
  CheckSameSystem(PaperSystem(), paper);
  CheckSameSystem(FromJson("{}"), paper);
  CheckSameSystem(FromToml(""), paper);
  CheckSameSystem(FromToml("# nothing but a comment\n"), paper);

  System omega = paper;
  omega.omega = 1.3;
  CheckSameSystem(FromJson(R"({"omega": 1.3})"), omega);

  // A chain of another size: its gaps filled, A padded with zeros.
  CheckSameSystem(FromToml("[chain]\nn = 3\nc = 0.05\n"),
                  UniformChain({3, 1.0, 1.0, 0.05}, Eigen::Vector3d(0.5, 0.0, 0.0), 1.0, 0.1, 0.7));

  // General form: N from the matrix given, the other matrices the paper
  // chain's of that size, contact at the last mass, no chain parameters.
  const Eigen::MatrixXd mass = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  CheckSameSystem(
      FromJson(R"({"mass": [[1, 0, 0], [0, 2, 0], [0, 0, 3]]})"),
      GeneralSystem(mass, 0.1 * E3(), E3(), Eigen::Vector3d(0.5, 0.0, 0.0), 1.0, 0.1, 0.7, 2));
  CheckSameSystem(FromToml("contact_dof = 1\nxs = 0.2\n"),
                  GeneralSystem(Eigen::MatrixXd::Identity(2, 2), 0.1 * E2(), E2(),
                                Eigen::Vector2d(0.5, 0.0), 1.0, 0.2, 0.7, 0));
}

TEST_CASE("every error in a system file is one line naming the file and the field", "[io]") {
  struct BadFile {
    const char* source;  ///< its name; the extension gives the syntax
    const char* text;
    std::vector<std::string> expected;  ///< fragments of the message
  };
  // One case a line or two; clang-format would give each field its own.
  // clang-format off
  const std::vector<BadFile> cases = {
      // Unknown keys, with what is allowed.
      {"bad.json", R"({"omgea": 1.2})",
       {"unknown key \"omgea\"", "allowed: chain, mass, damping, stiffness, forcing, omega"}},
      {"bad.json", R"({"chain": {"n": 2, "q": 1}})",
       {"unknown key \"q\" in 'chain'; allowed: n, m, k, c"}},
      {"bad.toml", "omega = 1.2\nomgea = 1.2\n", {"unknown key \"omgea\""}},
      {"bad.json", "[1, 2]", {"the top level must be an object"}},
      {"bad.json", R"({"chain": {"n": 2}, "mass": [[1]]})",
       {"'chain' cannot be combined with mass"}},
      // Wrong lengths and shapes.
      {"bad.json", R"({"forcing": [0.5, 0, 0]})", {"A (forcing) must have N = 2 entries, got 3"}},
      {"bad.toml", "mass = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\nforcing = [0.5, 0]\n",
       {"A (forcing) must have N = 3 entries, got 2"}},
      {"bad.json", R"({"mass": [[1, 0], [0]]})",
       {"'mass' must be an array of N rows of N numbers; row 2 has 1 entries, row 1 has 2"}},
      {"bad.json", R"({"mass": [[1, 0], [0, 1]], "stiffness": [[1]]})",
       {"K (stiffness matrix) must be 2 x 2"}},
      // Values that are not numbers.
      {"bad.json", R"({"omega": "1.2"})", {"'omega' must be a number, got string \"1.2\""}},
      {"bad.json", R"({"forcing": [0.5, "x"]})",
       {"entry 2 of 'forcing' must be a number, got string"}},
      {"bad.json", R"({"damping": [[0.2, -0.1], [-0.1, null]]})",
       {"entry 2 of row 2 of 'damping' must be a number, got null"}},
      {"bad.toml", "xs = true\n", {"'xs' must be a number, got boolean"}},
      {"bad.toml", "omega = 1979-05-27\n", {"bad.toml:1:", "dates and times"}},
      {"bad.json", R"({"chain": {"n": 2.5}})",
       {"'chain.n' must be a whole number in [1, 1000], got 2.5"}},
      {"bad.json", R"({"contact_dof": 0})",
       {"'contact_dof' must be a whole number in [1, 1000], got 0"}},
      // Malformed syntax, with the place.
      {"bad.json", R"({"omega": 1, })", {"invalid JSON", "line 1, column 14"}},
      {"bad.json", "{\n  \"omega\": 1.2\n  \"xs\": 0.1\n}", {"invalid JSON", "line 3"}},
      {"bad.json", "", {"invalid JSON"}},
      {"bad.toml", "omega = 1.2\nxs = \n", {"bad.toml:2:", "invalid TOML"}},
      {"bad.toml", "[chain\nn = 2\n", {"bad.toml:1:", "invalid TOML"}},
      // Values out of range, caught when the whole system is validated.
      {"bad.json", R"({"r": 2})", {"r (coefficient of restitution) must be in [0, 1], got 2"}},
      {"bad.toml", "r = 2\n", {"r (coefficient of restitution) must be in [0, 1], got 2"}},
      {"bad.toml", "omega = nan\n", {"omega (forcing frequency) must be finite"}},
      {"bad.toml", "xs = -inf\n", {"xs (stop position) must be finite"}},
      {"bad.json", R"({"chain": {"m": -1}})", {"m (mass) must be finite and > 0, got -1"}},
      {"bad.json", R"({"stiffness": [[2, -1], [-0.5, 1]]})",
       {"K (stiffness matrix) must be symmetric"}},
      {"bad.json", R"({"contact_dof": 3})", {"contact DOF must be in [1, 2], got 3"}},
      // Stop lists.
      {"bad.json", R"({"xs": 0.2, "stops": [{"position": 0.1}]})",
       {"'stops' cannot be combined with xs, r or contact_dof"}},
      {"bad.json", R"({"stops": []})", {"'stops' must be a non-empty array of stops"}},
      {"bad.json", R"({"stops": [{"dof": 2}]})", {"'stops[1].position' is required"}},
      {"bad.json", R"({"stops": [{"position": 0.1, "side": "left"}]})",
       {"'stops[1].side' must be \"upper\" (x <= position) or \"lower\"", "got \"left\""}},
      {"bad.json", R"({"stops": [{"position": 0.1}, {"position": -0.1, "sid": "lower"}]})",
       {"unknown key \"sid\" in 'stops[2]'; allowed: dof, side, position, restitution"}},
      {"bad.toml", "[[stops]]\nposition = 0.1\n[[stops]]\nposition = 0.2\n",
       {"stops 1 and 2 both limit mass 2 from above"}},
      {"bad.toml", "[[stops]]\nposition = 0.1\n[[stops]]\nposition = 0.2\nside = \"lower\"\n",
       {"the stops of mass 2 leave it no room: the lower one at 0.2 must be below the upper one at 0.1"}},
      {"bad.toml", "[[stops]]\nposition = 0.1\n[[stops]]\nposition = -0.1\nside = \"lower\"\nrestitution = 2\n",
       {"r2 (restitution of stop 2) must be in [0, 1], got 2"}},
  };
  // clang-format on
  for (const BadFile& bad : cases) {
    const std::string source = bad.source;
    const SystemFileFormat format =
        source.ends_with(".json") ? SystemFileFormat::kJson : SystemFileFormat::kToml;
    INFO(source << " containing:\n" << bad.text);
    const std::string message =
        MessageOf<InvalidInput>([&] { ParseSystem(bad.text, format, source); });
    CHECK_THAT(message, StartsWith(source + ":"));
    for (const std::string& fragment : bad.expected) CHECK_THAT(message, Contains(fragment));
    CHECK(message.find('\n') == std::string::npos);
  }
}

// nlohmann reports a number that overflows a double as out_of_range.406, not
// as a parse_error; it must still come out as InvalidInput naming the file.
TEST_CASE("a JSON number too large for a double is an InvalidInput naming the file", "[io]") {
  const std::string message = MessageOf<InvalidInput>(
      [] { ParseSystem(R"({"omega": 1e400})", SystemFileFormat::kJson, "bad.json"); });
  CHECK_THAT(message, StartsWith("bad.json:") && Contains("1e400"));
}

TEST_CASE("a key given twice, or nesting far beyond a system file's, is refused", "[io]") {
  for (const auto& [text, format, expected] :
       {std::tuple{R"({"omega": 1.0, "omega": 2.0})", SystemFileFormat::kJson,
                   "key \"omega\" is given twice"},
        std::tuple{R"({"chain": {"n": 2, "n": 3}})", SystemFileFormat::kJson,
                   "key \"n\" is given twice"},
        std::tuple{"omega = 1.0\nomega = 2.0\n", SystemFileFormat::kToml,
                   "cannot redefine existing"}}) {
    INFO(text);
    const std::string message = MessageOf<InvalidInput>([&] { ParseSystem(text, format, "dup"); });
    CHECK_THAT(message, StartsWith("dup") && Contains(expected));
  }
  // 100,000 levels (200 kB) once overflowed the stack; the depth is checked
  // while parsing, before any of it is built.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  CHECK_THAT(
      MessageOf<InvalidInput>([&] { ParseSystem(deep, SystemFileFormat::kJson, "deep.json"); }),
      Equals("deep.json: invalid JSON: nested deeper than 16 levels"));
}

// A key with a line break (legal in a JSON string or a quoted TOML key) is
// escaped in the message, which stays on one line.
TEST_CASE("an unknown key with a line break still gives a one-line message", "[io]") {
  for (const auto& [text, format] : {std::pair{R"({"a\nb": 1})", SystemFileFormat::kJson},
                                     std::pair{R"("a\nb" = 1)", SystemFileFormat::kToml}}) {
    INFO(text);
    const std::string message = MessageOf<InvalidInput>([&] { ParseSystem(text, format, "bad"); });
    CHECK_THAT(message, Contains("unknown key"));
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("a system file that is missing or of an unknown type", "[io]") {
  ScratchDir dir;
  const fs::path missing = dir / "missing.json";
  CHECK_THAT(MessageOf<InvalidInput>([&] { ReadSystemFile(missing); }),
             StartsWith(missing.string() + ": no such system file"));
  // A directory is not a system file either, and the message says so,
  // whatever its name ends with.
  for (const char* name : {"directory.json", "directory"}) {
    fs::create_directory(dir / name);
    CHECK_THAT(MessageOf<InvalidInput>([&] { ReadSystemFile(dir / name); }),
               Equals((dir / name).string() + ": is a directory, not a system file"));
  }
  WriteText(dir / "system.yaml", "omega: 1.2\n");
  CHECK_THAT(MessageOf<InvalidInput>([&] { ReadSystemFile(dir / "system.yaml"); }),
             Contains("unknown system file type '.yaml'; use .json or .toml"));
  // Errors in a file read from disk name it by its path.
  const fs::path bad = dir / "bad.toml";
  WriteText(bad, "omega = 1.2\nr = 2\n");
  CHECK_THAT(MessageOf<InvalidInput>([&] { ReadSystemFile(bad); }),
             StartsWith(bad.string() + ": r (coefficient of restitution)"));
}

TEST_CASE("CsvWriter: provenance, header, and values that read back exactly", "[io]") {
  ScratchDir dir;
  const fs::path path = dir / "table.csv";
  std::vector<std::vector<double>> rows = {
      {0.1, 1.0 / 3.0, 1e-300, -2.5e17},
      {-0.0, 4.9406564584124654e-324, DBL_MAX, -DBL_MIN},
      {1.0, std::nextafter(1.0, 2.0), 123456789.125, -1e-5},
  };
  // Enough rows to pass the writer's 64 KiB buffer several times.
  for (int i = 1; i <= 5000; ++i) {
    rows.push_back({i * 0.01, std::sin(i) / i, std::exp(-i / 100.0), -i / 7.0});
  }
  {
    CsvWriter csv(path, "impactkit test\nparameters: omega=1.4 xs=0.1", {"t", "x1", "x2", "v1"});
    CHECK(csv.Columns() == 4);
    for (const auto& row : rows) csv.WriteRow(row);
    CHECK_FALSE(fs::exists(path));  // nothing before Commit()
    csv.Commit();
  }
  const std::vector<std::string> lines = Lines(ReadText(path));
  REQUIRE(lines.size() == 3 + rows.size());
  // The header first: numpy.genfromtxt(names=True) names the columns by the
  // first line, comment or not.
  CHECK(lines[0] == "t,x1,x2,v1");
  CHECK(lines[1] == "# impactkit test");
  CHECK(lines[2] == "# parameters: omega=1.4 xs=0.1");
  // Exact: the writer prints the shortest decimal that reads back to the same
  // double and strtod rounds correctly, so every bit must survive.
  for (std::size_t i = 0; i < rows.size(); ++i) {
    INFO("row " << i + 1 << ": " << lines[i + 3]);
    std::vector<double> values;
    const char* cursor = lines[i + 3].c_str();
    for (;;) {
      char* end = nullptr;
      values.push_back(std::strtod(cursor, &end));
      REQUIRE(end != cursor);  // a number was read
      if (*end != ',') {
        REQUIRE(*end == '\0');  // and nothing but numbers and commas
        break;
      }
      cursor = end + 1;
    }
    CHECK(values == rows[i]);
  }
  CHECK(std::signbit(std::strtod(lines[4].c_str(), nullptr)));  // -0.0 keeps its sign
}

TEST_CASE("CsvWriter rejects misuse", "[io]") {
  ScratchDir dir;
  CHECK_THROWS_AS(CsvWriter(dir / "a.csv", "carriage\rreturn", {"t"}), std::invalid_argument);
  CHECK_THROWS_AS(CsvWriter(dir / "b.csv", "no columns", {}), std::invalid_argument);
  {
    CsvWriter csv(dir / "c.csv", "short row", {"t", "x1"});
    const std::vector<double> short_row = {1.0};
    CHECK_THROWS_AS(csv.WriteRow(short_row), std::invalid_argument);
  }
  CHECK(dir.Entries().empty());  // no table, no temporary
}

TEST_CASE("AtomicOutputFile: the file appears whole on Commit, or not at all", "[io]") {
  ScratchDir dir;
  const fs::path target = dir / "out.csv";
  SECTION("without Commit nothing is left behind") {
    {
      AtomicOutputFile file(target);
      file.Write("half a table\n");
      CHECK_FALSE(fs::exists(target));
      CHECK(dir.Entries().size() == 1);  // the hidden temporary, beside the target
    }
    CHECK(dir.Entries().empty());
  }
  SECTION("Commit moves the content into place, replacing an older file") {
    const std::string old_content = "an older, longer table that must disappear entirely\n";
    WriteText(target, old_content);
    {
      AtomicOutputFile file(target);
      CHECK(file.Path() == target);
      file.Write("t,x1\n");
      file.Write("0.5,0.25\n");
      CHECK(ReadText(target) == old_content);  // untouched until Commit()
      file.Commit();
      CHECK_THROWS_AS(file.Write("more"), OutputError);
      CHECK_THROWS_AS(file.Commit(), OutputError);
    }
    CHECK(ReadText(target) == "t,x1\n0.5,0.25\n");
    CHECK(dir.Entries() == std::vector<std::string>{"out.csv"});
  }
  SECTION("a directory is refused as the target") {
    fs::create_directory(target);
    for (const fs::path& directory : {dir.Path(), target, dir / ""}) {
      INFO(directory);
      CHECK_THAT(MessageOf<OutputError>([&] { AtomicOutputFile file(directory); }),
                 Contains(directory.string()) && Contains("names a directory"));
    }
    CHECK(dir.Entries() == std::vector<std::string>{"out.csv"});  // no temporary
  }
  SECTION("a missing directory fails at once, naming the file") {
    const fs::path nowhere = dir / "no" / "such" / "out.csv";
    CHECK_THAT(MessageOf<OutputError>([&] { AtomicOutputFile file(nowhere); }),
               Contains("cannot create " + nowhere.string()));
  }
}

TEST_CASE("AtomicOutputFile: any valid file name works, and empty paths are refused", "[io]") {
  ScratchDir dir;
  // NAME_MAX bytes: the temporary's name must not grow with the target's.
  const std::string longest(NAME_MAX, 'a');
  {
    AtomicOutputFile file(dir / longest);
    CHECK(file.TemporaryPath().parent_path() == dir.Path());
    CHECK(file.TemporaryPath().filename().string().size() < 100);
    CHECK_THAT(file.TemporaryPath().filename().string(),
               StartsWith(".impactkit." + std::to_string(::getpid()) + "."));
    file.Write("x");
    file.Commit();
  }
  CHECK(dir.Entries() == std::vector<std::string>{longest});
  CHECK_THAT(MessageOf<OutputError>([&] { AtomicOutputFile file(""); }), Contains("empty name"));
}

TEST_CASE("OutputSet: every file appears on Commit, or none does", "[io]") {
  ScratchDir dir;
  WriteText(dir / "keep.csv", "old\n");
  SECTION("a file that cannot be created fails at once and changes nothing") {
    {
      OutputSet outputs;
      outputs.AddCsv(dir / "keep.csv", "test", {"t"}).WriteRow(std::vector<double>{1.0});
      fs::create_directory(dir / "taken.json");  // a directory where a file should go
      CHECK_THROWS_AS(outputs.AddFile(dir / "taken.json"), OutputError);
      CHECK_THROWS_AS(outputs.AddFile(dir / "no" / "such" / "x.png"), OutputError);
    }
    CHECK(ReadText(dir / "keep.csv") == "old\n");
    CHECK(dir.Entries() == std::vector<std::string>{"keep.csv", "taken.json"});
  }
  SECTION("Commit moves every file into place") {
    {
      OutputSet outputs;
      AtomicOutputFile& main = outputs.AddFile(dir / "keep.csv");
      AtomicOutputFile& json = outputs.AddFile(dir / "result.json");
      outputs.AddCsv(main, "test", {"t", "x"}).WriteRow(std::vector<double>{0.5, 1.5});
      json.Write("{}\n");
      CHECK(outputs.Size() == 2);
      CHECK(ReadText(dir / "keep.csv") == "old\n");  // nothing before Commit
      outputs.Commit();
    }
    CHECK(ReadText(dir / "keep.csv") == "t,x\n# test\n0.5,1.5\n");
    CHECK(ReadText(dir / "result.json") == "{}\n");
    CHECK(dir.Entries() == std::vector<std::string>{"keep.csv", "result.json"});
  }
  SECTION("one path named twice is bad input") {
    OutputSet outputs;
    outputs.AddFile(dir / "a.png");
    CHECK_THAT(MessageOf<InvalidInput>([&] { outputs.AddFile(dir / "." / "a.png"); }),
               Contains("named twice"));
  }
}

TEST_CASE("temporaries of processes that no longer run are removed", "[io]") {
  ScratchDir dir;
  // A PID that has just ended: a child reaped at once.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) ::_exit(0);
  REQUIRE(::waitpid(child, nullptr, 0) == child);
  const std::string stale = TemporaryFileName(child, 0);
  const std::string live = TemporaryFileName(::getpid(), 999);
  const std::string other_host = ".impactkit." + std::to_string(child) + ".0.elsewhere.tmp";
  for (const std::string& name : {stale, live, other_host, std::string("data.csv")}) {
    WriteText(dir / name, "x");
  }
  CHECK(RemoveStaleTemporaries(dir.Path()) == 1);
  std::vector<std::string> left = {live, other_host, "data.csv"};
  std::sort(left.begin(), left.end());
  CHECK(dir.Entries() == left);
}

TEST_CASE("SIGTERM and SIGINT remove the temporaries and still end the process", "[io]") {
  for (int signal : {SIGTERM, SIGINT}) {
    ScratchDir dir;
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The child's own dispositions: default, as in a program run from a shell.
      ::signal(signal, SIG_DFL);
      AtomicOutputFile a(dir / "a.csv");
      AtomicOutputFile b(dir / "b.png");
      a.Write("half a table");
      ::raise(signal);
      ::_exit(3);  // not reached: the signal ends the process
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    INFO("signal " << signal);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal);
    CHECK(dir.Entries().empty());
  }
}

namespace {

/// CIELAB (D65) of "#rrggbb", for distances as the eye sees them: the
/// colour table's claim is checked in this space, not in RGB.
std::array<double, 3> Lab(const std::string& hex) {
  std::array<double, 3> linear{};
  for (int i = 0; i < 3; ++i) {
    const double c = std::stoi(hex.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
    linear[i] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  const double x = (0.4124 * linear[0] + 0.3576 * linear[1] + 0.1805 * linear[2]) / 0.95047;
  const double y = 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2];
  const double z = (0.0193 * linear[0] + 0.1192 * linear[1] + 0.9505 * linear[2]) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

double LabDistance(const std::string& a, const std::string& b) {
  const std::array<double, 3> p = Lab(a), q = Lab(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

}  // namespace

TEST_CASE("ClassColor: the common classes 25 CIELAB units apart, every class its own colour",
          "[io]") {
  using impactkit::ClassColor;
  using impactkit::MotionKind;
  // The classes the paper's maps hold most (docs/grids.md) and the kinds
  // without a period.
  std::vector<std::string> common;
  for (const auto& [p, q] : std::vector<std::pair<int, int>>{{1, 1},
                                                             {1, 2},
                                                             {2, 1},
                                                             {2, 2},
                                                             {3, 1},
                                                             {4, 1},
                                                             {3, 2},
                                                             {4, 4},
                                                             {5, 1},
                                                             {6, 1},
                                                             {7, 1},
                                                             {2, 4},
                                                             {3, 3},
                                                             {4, 2},
                                                             {2, 3},
                                                             {8, 1}}) {
    common.push_back(ClassColor(MotionKind::kPeriodic, p, q));
  }
  for (int q : {1, 2}) common.push_back(ClassColor(MotionKind::kSticking, 0, q));
  for (MotionKind kind :
       {MotionKind::kNonImpacting, MotionKind::kChaotic, MotionKind::kUnresolved}) {
    common.push_back(ClassColor(kind, 0, 0));
  }
  for (std::size_t i = 0; i < common.size(); ++i) {
    for (std::size_t j = i + 1; j < common.size(); ++j) {
      INFO(common[i] << " and " << common[j]);
      CHECK(LabDistance(common[i], common[j]) >= 25.0);
    }
  }
  // Every other period up to P(30,30) keeps 15 units from the common ones,
  // and the periods of a cascade (p to p + 3 at one q) 10 units from each
  // other; a sticking class's colour does not depend on p, which means nothing.
  for (int q = 1; q <= 30; ++q) {
    for (int p = 1; p <= 30; ++p) {
      const std::string color = ClassColor(MotionKind::kPeriodic, p, q);
      if (std::find(common.begin(), common.end(), color) == common.end()) {
        for (const std::string& c : common) {
          INFO("P(" << p << "," << q << ") " << color << " and " << c);
          CHECK(LabDistance(color, c) >= 15.0);
        }
      }
      for (int next = p + 1; next <= std::min(30, p + 3); ++next) {
        INFO("P(" << p << "," << q << ") and P(" << next << "," << q << ")");
        CHECK(LabDistance(color, ClassColor(MotionKind::kPeriodic, next, q)) >= 10.0);
      }
    }
    CHECK(ClassColor(MotionKind::kSticking, 7, q) == ClassColor(MotionKind::kSticking, 0, q));
  }
  CHECK(ClassColor(MotionKind::kChaotic, 3, 4) == ClassColor(MotionKind::kChaotic, 0, 0));
  // A second and third attractor of one class: shades of its colour, told
  // apart from it and from each other.
  const std::string base = ClassColor(MotionKind::kPeriodic, 1, 1);
  const std::string darker = ClassColor(MotionKind::kPeriodic, 1, 1, 1);
  const std::string lighter = ClassColor(MotionKind::kPeriodic, 1, 1, 2);
  CHECK(LabDistance(base, darker) >= 10.0);
  CHECK(LabDistance(base, lighter) >= 10.0);
  CHECK(LabDistance(darker, lighter) >= 10.0);
  CHECK(Lab(darker)[0] < Lab(base)[0]);
  CHECK(Lab(lighter)[0] > Lab(base)[0]);
}
