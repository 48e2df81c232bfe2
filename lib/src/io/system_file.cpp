#include "impactkit/io/system_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <sstream>

#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/model/parameters.hpp"
#include "io/toml_json.hpp"

namespace impactkit {
namespace {

using Json = nlohmann::json;
using Keys = std::span<const std::string_view>;

/// The top-level keys: with one stop, its parameters by their names (xs,
/// r: hybrid/stop_parameters.hpp) and contact_dof; else a `stops` list.
std::vector<std::string_view> TopLevelKeys() {
  std::vector<std::string_view> keys = {"chain",     "mass",    "damping",
                                        "stiffness", "forcing", "omega"};
  for (const StopParameterRow& row : kStopParameterRows) keys.push_back(row.name);
  keys.insert(keys.end(), {"contact_dof", "stops"});
  return keys;
}

/// "xs, r or contact_dof": the top-level keys of a file's sole stop.
std::string SoleStopKeys() {
  std::vector<std::string_view> names;
  for (const StopParameterRow& row : kStopParameterRows) names.push_back(row.name);
  return fmt::format("{} or contact_dof", fmt::join(names, ", "));
}

/// A `stops` entry's keys: dof, side and each stop parameter's key.
std::vector<std::string_view> StopKeys() {
  std::vector<std::string_view> keys = {"dof", "side"};
  for (const StopParameterRow& row : kStopParameterRows) keys.push_back(row.key);
  return keys;
}

/// The chain's keys are the model's chain parameters (model/parameters.hpp),
/// n first: it sizes the chain the others fill.
std::vector<std::string_view> ChainKeys() {
  std::vector<std::string_view> keys;
  for (const ParameterSpec& spec : ParameterTable()) {
    if (spec.chain_only) keys.push_back(spec.name);
  }
  std::stable_partition(keys.begin(), keys.end(), [](std::string_view key) { return key == "n"; });
  return keys;
}

/// One entry of `stops`: its values over the paper's stop's, and its mass
/// if given (the last one, known once N is, by default).
struct StopFields {
  std::optional<int> dof;  ///< 1-based, as in the file
  StopParameters values;   ///< side and the stop parameters; dof not yet set
};

/// What a file states, before the paper's defaults fill the gaps.
struct SystemFields {
  std::optional<ChainParameters> chain;  ///< the chain form, its gaps already filled
  std::optional<Eigen::MatrixXd> mass, damping, stiffness;
  std::optional<Eigen::VectorXd> forcing;
  std::optional<double> omega;
  /// The one stop of a file without `stops`: the paper's stop's values
  /// under the top-level keys given (xs, r); unset if none is.
  std::optional<StopParameters> sole_stop;
  std::optional<int> contact_dof;  ///< 1-based, as in the file
  std::optional<std::vector<StopFields>> stops;
  bool General() const { return mass || damping || stiffness || contact_dof; }
};

/// Largest N accepted in a file, as for `n` in SetParameter: a typo such as
/// n = 1000000 must fail here, not in allocating an N x N matrix.
constexpr int kMaxDof = kMaxDegreesOfFreedom;

/// 'name', as fields are named in messages.
std::string Field(std::string_view name) { return fmt::format("'{}'", name); }

/// Reads typed fields from a parsed document. Every error names the file and
/// the field ("entry 2 of 'forcing'": entries and rows count from 1, like
/// A1..AN) and says what is allowed.
class FieldReader {
 public:
  explicit FieldReader(std::string_view source) : source_(source) {}

  [[noreturn]] void Fail(std::string_view subject, std::string_view problem) const {
    throw InvalidInput(fmt::format("{}: {} {}", source_, subject, problem));
  }

  /// `value` must be an object whose keys are all in `allowed`; `name` is
  /// empty for the top level.
  void RequireObject(const Json& value, std::string_view name, Keys allowed) const {
    if (!value.is_object()) {
      Fail(name.empty() ? "the top level" : Field(name),
           fmt::format("must be an object with keys {}, got {}", fmt::join(allowed, ", "),
                       Describe(value)));
    }
    for (const auto& [key, unused] : value.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      const std::string where = name.empty() ? "" : fmt::format(" in {}", Field(name));
      // dump() quotes and escapes the key: a key with a line break must not
      // break the one-line error.
      throw InvalidInput(fmt::format("{}: unknown key {}{}; allowed: {}", source_, Json(key).dump(),
                                     where, fmt::join(allowed, ", ")));
    }
  }

  double Number(const Json& value, std::string_view subject) const {
    if (!value.is_number()) Fail(subject, fmt::format("must be a number, got {}", Describe(value)));
    return value.get<double>();
  }

  int WholeNumber(const Json& value, std::string_view subject, int min) const {
    const double number = Number(value, subject);
    if (!(number >= min && number <= kMaxDof && number == std::floor(number))) {
      Fail(subject,
           fmt::format("must be a whole number in [{}, {}], got {}", min, kMaxDof, number));
    }
    return static_cast<int>(number);
  }

  Eigen::VectorXd Vector(const Json& value, std::string_view subject) const {
    if (!value.is_array()) {
      Fail(subject, fmt::format("must be an array of numbers, got {}", Describe(value)));
    }
    Eigen::VectorXd vector(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      vector(static_cast<Eigen::Index>(i)) =
          Number(value[i], fmt::format("entry {} of {}", i + 1, subject));
    }
    return vector;
  }

  std::string Text(const Json& value, std::string_view subject) const {
    if (!value.is_string()) Fail(subject, fmt::format("must be a string, got {}", Describe(value)));
    return value.get<std::string>();
  }

  /// A matrix is an array of rows of equal length (whether it is N x N is
  /// the model's to check).
  Eigen::MatrixXd Matrix(const Json& value, std::string_view name) const {
    const std::string expected = "must be an array of N rows of N numbers";
    if (!value.is_array() || value.empty()) {
      Fail(Field(name), fmt::format("{}, got {}", expected, Describe(value)));
    }
    std::vector<Eigen::VectorXd> rows;
    for (std::size_t i = 0; i < value.size(); ++i) {
      rows.push_back(Vector(value[i], fmt::format("row {} of {}", i + 1, Field(name))));
      if (rows.back().size() != rows.front().size()) {
        Fail(Field(name), fmt::format("{}; row {} has {} entries, row 1 has {}", expected, i + 1,
                                      rows.back().size(), rows.front().size()));
      }
    }
    Eigen::MatrixXd matrix(rows.size(), rows.front().size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      matrix.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    }
    return matrix;
  }

 private:
  /// The offending value, shortened: one line however large it is.
  static std::string Describe(const Json& value) {
    if (value.is_null()) return "null";
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return fmt::format("{} {}", value.type_name(), text);
  }

  std::string source_;
};

ChainParameters ReadChain(const Json& value, const ChainParameters& defaults,
                          const FieldReader& reader) {
  reader.RequireObject(value, "chain", ChainKeys());
  ChainParameters chain = defaults;
  if (value.contains("n")) chain.dof = reader.WholeNumber(value["n"], Field("chain.n"), 1);
  if (value.contains("m")) chain.mass = reader.Number(value["m"], Field("chain.m"));
  if (value.contains("k")) chain.stiffness = reader.Number(value["k"], Field("chain.k"));
  if (value.contains("c")) chain.damping = reader.Number(value["c"], Field("chain.c"));
  return chain;
}

StopFields ReadStop(const Json& value, std::size_t index, const StopParameters& defaults,
                    const FieldReader& reader) {
  const std::string name = fmt::format("stops[{}]", index + 1);
  reader.RequireObject(value, name, StopKeys());
  auto field = [&](const char* key) { return Field(fmt::format("{}.{}", name, key)); };
  StopFields stop{std::nullopt, defaults};
  stop.values.side = StopSide::kUpper;
  if (value.contains("dof")) stop.dof = reader.WholeNumber(value["dof"], field("dof"), 1);
  if (value.contains("side")) {
    const std::string side = reader.Text(value["side"], field("side"));
    if (side != "upper" && side != "lower") {
      reader.Fail(field("side"), fmt::format("must be \"upper\" (x <= position) or \"lower\" (x >= "
                                             "position), got {}",
                                             Json(side).dump()));
    }
    stop.values.side = side == "upper" ? StopSide::kUpper : StopSide::kLower;
  }
  for (const StopParameterRow& row : kStopParameterRows) {
    const std::string key(row.key);
    if (value.contains(key)) {
      stop.values.*row.member = reader.Number(value[key], field(key.c_str()));
    } else if (row.required) {
      reader.Fail(field(key.c_str()), "is required");
    }
  }
  return stop;
}

std::vector<StopFields> ReadStops(const Json& value, const StopParameters& defaults,
                                  const FieldReader& reader) {
  if (!value.is_array() || value.empty()) {
    reader.Fail(Field("stops"), fmt::format("must be a non-empty array of stops, each {{{}}}",
                                            fmt::join(StopKeys(), ", ")));
  }
  std::vector<StopFields> stops;
  for (std::size_t i = 0; i < value.size(); ++i) {
    stops.push_back(ReadStop(value[i], i, defaults, reader));
  }
  return stops;
}

/// The fields of `document`; the gaps of the chain and of each stop are
/// filled from `paper`.
SystemFields ReadFields(const Json& document, const System& paper, const FieldReader& reader) {
  reader.RequireObject(document, "", TopLevelKeys());
  auto number = [&](const char* key) -> std::optional<double> {
    if (!document.contains(key)) return std::nullopt;
    return reader.Number(document[key], Field(key));
  };
  auto matrix = [&](const char* key) -> std::optional<Eigen::MatrixXd> {
    if (!document.contains(key)) return std::nullopt;
    return reader.Matrix(document[key], key);
  };
  SystemFields fields;
  if (document.contains("chain")) fields.chain = ReadChain(document["chain"], *paper.chain, reader);
  fields.mass = matrix("mass");
  fields.damping = matrix("damping");
  fields.stiffness = matrix("stiffness");
  if (document.contains("forcing")) {
    fields.forcing = reader.Vector(document["forcing"], Field("forcing"));
  }
  fields.omega = number("omega");
  for (const StopParameterRow& row : kStopParameterRows) {
    const std::string key(row.name);
    if (!document.contains(key)) continue;
    if (!fields.sole_stop) fields.sole_stop = paper.stops[0];
    *fields.sole_stop.*row.member = reader.Number(document[key], Field(key));
  }
  if (document.contains("contact_dof")) {
    fields.contact_dof = reader.WholeNumber(document["contact_dof"], Field("contact_dof"), 1);
  }
  if (document.contains("stops")) {
    if (fields.sole_stop || fields.contact_dof) {
      reader.Fail(Field("stops"), fmt::format("cannot be combined with {}: give the one stop by "
                                              "those keys or every stop in 'stops'",
                                              SoleStopKeys()));
    }
    fields.stops = ReadStops(document["stops"], paper.stops[0], reader);
  }
  if (fields.chain && fields.General()) {
    reader.Fail(Field("chain"),
                "cannot be combined with mass, damping, stiffness or contact_dof: "
                "describe either a uniform chain or general matrices");
  }
  return fields;
}

/// The paper's forcing for N masses: its first entries, then zeros (as
/// SetParameter does when n grows).
Eigen::VectorXd DefaultForcing(const System& paper, int dof) {
  Eigen::VectorXd forcing = Eigen::VectorXd::Zero(dof);
  const int kept = std::min<int>(dof, static_cast<int>(paper.forcing.size()));
  forcing.head(kept) = paper.forcing.head(kept);
  return forcing;
}

/// N of a general system: the size of the first matrix given (the others
/// default to the paper chain's matrices of that size).
int GeneralDof(const SystemFields& fields, const System& paper) {
  for (const auto* matrix : {&fields.mass, &fields.stiffness, &fields.damping}) {
    if (*matrix) return static_cast<int>((*matrix)->rows());
  }
  return paper.Dof();
}

/// The system the fields describe but for a `stops` list: one stop, by the
/// keys xs, r and contact_dof.
System BuildWithoutStopList(const SystemFields& fields, const System& paper) {
  const double omega = fields.omega.value_or(paper.omega);
  const StopParameters& sole = fields.sole_stop.value_or(paper.stops[0]);
  System system;
  if (!fields.General()) {
    const ChainParameters chain = fields.chain.value_or(*paper.chain);
    system = UniformChain(chain, fields.forcing.value_or(DefaultForcing(paper, chain.dof)), omega,
                          sole.position, sole.restitution);
  } else {
    ChainParameters chain = *paper.chain;
    chain.dof = GeneralDof(fields, paper);
    const Eigen::VectorXd forcing = fields.forcing.value_or(DefaultForcing(paper, chain.dof));
    const System defaults = UniformChain(chain, forcing, omega, sole.position, sole.restitution);
    std::optional<int> contact_dof;
    if (fields.contact_dof) contact_dof = *fields.contact_dof - 1;
    system = GeneralSystem(fields.mass.value_or(defaults.mass),
                           fields.damping.value_or(defaults.damping),
                           fields.stiffness.value_or(defaults.stiffness), forcing, omega,
                           sole.position, sole.restitution, contact_dof);
  }
  // Every stop parameter, those the constructors above do not take too.
  const int dof = system.stops[0].dof;
  system.stops[0] = sole;
  system.stops[0].dof = dof;
  return system;
}

/// The stops of a `stops` list, each on its mass or the last.
std::vector<StopParameters> BuildStops(const std::vector<StopFields>& fields, int dof) {
  std::vector<StopParameters> stops;
  for (const StopFields& given : fields) {
    stops.push_back(given.values);
    stops.back().dof = given.dof.value_or(dof) - 1;
  }
  return stops;
}

/// The system the fields describe, gaps filled from `paper`. Throws
/// InvalidInput (without the file name) for values the model rejects.
System Build(const SystemFields& fields, const System& paper) {
  System system = BuildWithoutStopList(fields, paper);
  if (fields.stops) system.stops = BuildStops(*fields.stops, system.Dof());
  return system;
}

/// A system file is at most a few levels deep (top level, chain, matrix
/// rows); far deeper nesting is no system file, and nlohmann's DOM would
/// recurse once per level building and destroying it.
constexpr int kMaxJsonDepth = 16;

/// Rejects, while parsing, nesting beyond kMaxJsonDepth and a key given
/// twice in one object (nlohmann keeps the last silently; which was meant
/// cannot be guessed).
class JsonGuard {
 public:
  explicit JsonGuard(std::string_view source) : source_(source) {}

  bool operator()(int depth, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        if (depth >= kMaxJsonDepth) {
          throw InvalidInput(fmt::format("{}: invalid JSON: nested deeper than {} levels", source_,
                                         kMaxJsonDepth));
        }
        if (event == Json::parse_event_t::object_start) keys_.emplace_back();
        break;
      case Json::parse_event_t::object_end:
        keys_.pop_back();
        break;
      case Json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        std::vector<std::string>& seen = keys_.back();
        if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
          throw InvalidInput(
              fmt::format("{}: key {} is given twice in one object", source_, Json(key).dump()));
        }
        seen.push_back(key);
        break;
      }
      default:
        break;
    }
    return true;
  }

 private:
  std::string_view source_;
  std::vector<std::vector<std::string>> keys_;  ///< per open object
};

Json ParseJson(std::string_view text, std::string_view source) {
  try {
    return Json::parse(text, JsonGuard(source));
  } catch (const Json::exception& error) {
    // Syntax errors, and numbers too large for a double (out_of_range.406).
    // what() is "[json.exception.parse_error.101] parse error at line 1, ...":
    // keep the part a user can act on.
    const std::string what = error.what();
    const std::size_t start = what.find("] ");
    throw InvalidInput(fmt::format("{}: invalid JSON: {}", source,
                                   start == std::string::npos ? what : what.substr(start + 2)));
  }
}

std::optional<SystemFileFormat> FormatOf(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  if (extension == ".json") return SystemFileFormat::kJson;
  if (extension == ".toml") return SystemFileFormat::kToml;
  return std::nullopt;
}

/// Says which of the common mistakes it is: no such file, a directory, or
/// something else that is not a file (a device, a pipe).
void RequireRegularFile(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_regular_file(status)) return;
  if (std::filesystem::is_directory(status)) {
    throw InvalidInput(fmt::format("{}: is a directory, not a system file", path.string()));
  }
  if (status.type() == std::filesystem::file_type::not_found) {
    throw InvalidInput(fmt::format("{}: no such system file", path.string()));
  }
  if (error) {
    throw InvalidInput(
        fmt::format("{}: cannot read the system file: {}", path.string(), error.message()));
  }
  throw InvalidInput(fmt::format("{}: not a regular file, so not a system file", path.string()));
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InvalidInput(fmt::format("{}: cannot read the system file", path.string()));
  return text.str();
}

std::vector<std::vector<double>> Rows(const Eigen::MatrixXd& matrix) {
  std::vector<std::vector<double>> rows;
  for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
    rows.emplace_back(matrix.row(i).begin(), matrix.row(i).end());
  }
  return rows;
}

}  // namespace

System ReadSystemFile(const std::filesystem::path& path) {
  RequireRegularFile(path);  // first: "is a directory" says more than its extension would
  const std::optional<SystemFileFormat> format = FormatOf(path);
  if (!format) {
    throw InvalidInput(fmt::format("{}: unknown system file type '{}'; use .json or .toml",
                                   path.string(), path.extension().string()));
  }
  return ParseSystem(ReadText(path), *format, path.string());
}

System ParseSystem(std::string_view text, SystemFileFormat format, std::string_view source) {
  const Json document =
      format == SystemFileFormat::kJson ? ParseJson(text, source) : ParseTomlAsJson(text, source);
  const System paper = PaperSystem();
  const SystemFields fields = ReadFields(document, paper, FieldReader(source));
  try {
    System system = Build(fields, paper);
    Validate(system);
    return system;
  } catch (const InvalidInput& error) {
    throw InvalidInput(fmt::format("{}: {}", source, error.what()));
  }
}

std::string SystemToJson(const System& system) {
  nlohmann::ordered_json json;
  // One upper stop is written by the keys xs, r (and contact_dof), as
  // before stop lists; the chain form is exact only when that stop is on
  // the chain's last mass or the stops are listed.
  const bool one_stop = system.StopCount() == 1 && system.stops[0].side == StopSide::kUpper;
  const bool chain_form = system.chain && (!one_stop || system.stops[0].dof == system.Dof() - 1);
  if (chain_form) {
    json["chain"] = {{"n", system.chain->dof},
                     {"m", system.chain->mass},
                     {"k", system.chain->stiffness},
                     {"c", system.chain->damping}};
  } else {
    json["mass"] = Rows(system.mass);
    json["damping"] = Rows(system.damping);
    json["stiffness"] = Rows(system.stiffness);
  }
  json["forcing"] = std::vector<double>(system.forcing.begin(), system.forcing.end());
  json["omega"] = system.omega;
  if (one_stop) {
    for (const StopParameterRow& row : kStopParameterRows) {
      json[std::string(row.name)] = system.stops[0].*row.member;
    }
    if (!chain_form) json["contact_dof"] = system.stops[0].dof + 1;
  } else {
    json["stops"] = nlohmann::ordered_json::array();
    for (const StopParameters& stop : system.stops) {
      nlohmann::ordered_json entry = {{"dof", stop.dof + 1},
                                      {"side", stop.side == StopSide::kUpper ? "upper" : "lower"}};
      for (const StopParameterRow& row : kStopParameterRows) {
        entry[std::string(row.key)] = stop.*row.member;
      }
      json["stops"].push_back(entry);
    }
  }
  return json.dump(2);
}

}  // namespace impactkit
