#include "impactkit/model/parameters.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>

#include "core/require.hpp"

namespace impactkit {
namespace {

/// k - 1 for a name `base`<k> with 1 <= k <= count (A2 -> 1), or -1.
int NumberedIndex(std::string_view name, std::string_view base, int count) {
  if (name.size() <= base.size() || !name.starts_with(base)) return -1;
  int index = 0;
  for (char ch : name.substr(base.size())) {
    if (ch < '0' || ch > '9') return -1;
    index = index * 10 + (ch - '0');
    if (index > count) return -1;
  }
  return index >= 1 ? index - 1 : -1;
}

/// Index of the parameter A<i> (1-based in the name), or -1.
int ForcingIndex(std::string_view name, int dof) { return NumberedIndex(name, "A", dof); }

/// The stop a stop parameter's name refers to: 0 for the plain name (xs,
/// r), k - 1 for xs<k>, r<k> with 2 <= k <= the number of stops; -1 for
/// any other name.
int StopIndex(std::string_view name, std::string_view base, const System& s) {
  if (name == base) return 0;
  const int index = NumberedIndex(name, base, s.StopCount());
  return index >= 1 ? index : -1;
}

/// Applies `change` to the chain's parameters and rebuilds its matrices; A
/// keeps the entries the new size has room for.
template <typename Change>
void RebuildChain(System& s, Change change) {
  ChainParameters chain = *s.chain;
  change(chain);
  Eigen::VectorXd forcing = Eigen::VectorXd::Zero(chain.dof);
  const int kept = std::min<int>(chain.dof, static_cast<int>(s.forcing.size()));
  forcing.head(kept) = s.forcing.head(kept);
  // One stop on the last mass stays on the last mass as n changes (the
  // paper's chain); stops given on other masses stay on them.
  const bool follows_last = s.StopCount() == 1 && s.stops[0].dof == s.Dof() - 1;
  std::vector<StopParameters> stops = s.stops;
  s = UniformChain(chain, forcing, s.omega, stops[0].position, stops[0].restitution);
  if (!follows_last) s.stops = std::move(stops);
}

void SetDof(System& s, double value) {
  // A chain's set-up costs O(N²) and every event O(N²): n = 1000 starts in
  // about half a second, and each event costs ~1.5 ms (docs/performance.md,
  // "Long chains").
  if (!(std::isfinite(value) && value >= 1 && value == std::floor(value) &&
        value <= kMaxDegreesOfFreedom)) {
    throw InvalidInput(fmt::format("n (number of masses) must be a whole number in [1, {}], got {}",
                                   kMaxDegreesOfFreedom, value));
  }
  RebuildChain(s, [&](ChainParameters& c) { c.dof = static_cast<int>(value); });
}

constexpr ParameterSpec kOmega = {"omega",
                                  "forcing frequency",
                                  "> 0",
                                  false,
                                  [](const System& s) { return s.omega; },
                                  [](System& s, double v) { s.omega = v; }};

/// The parameters after the stops' own.
constexpr std::array<ParameterSpec, 5> kSystemParameters = {{
    {"A", "forcing amplitude on mass i", "finite", false, nullptr, nullptr},
    {"m", "mass", "> 0", true, [](const System& s) { return s.chain->mass; },
     [](System& s, double v) { RebuildChain(s, [&](ChainParameters& c) { c.mass = v; }); }},
    {"k", "stiffness", "> 0", true, [](const System& s) { return s.chain->stiffness; },
     [](System& s, double v) { RebuildChain(s, [&](ChainParameters& c) { c.stiffness = v; }); }},
    {"c", "damping", ">= 0", true, [](const System& s) { return s.chain->damping; },
     [](System& s, double v) { RebuildChain(s, [&](ChainParameters& c) { c.damping = v; }); }},
    {"n", "number of masses", "a whole number in [1, 1000]", true,
     [](const System& s) { return static_cast<double>(s.chain->dof); }, SetDof},
}};

/// omega, then a row per stop parameter (hybrid/stop_parameters.hpp), then
/// the rest: a contact law's new parameter joins without an edit here.
constexpr auto BuildTable() {
  std::array<ParameterSpec, 1 + kStopParameterRows.size() + kSystemParameters.size()> table{};
  auto next = table.begin();
  *next++ = kOmega;
  for (const StopParameterRow& row : kStopParameterRows) {
    *next++ = {row.name, row.meaning, row.range, false, nullptr, nullptr, &row};
  }
  for (const ParameterSpec& spec : kSystemParameters) *next++ = spec;
  return table;
}

constexpr auto kTable = BuildTable();

[[noreturn]] void UnknownParameter(const System& s, std::string_view name) {
  throw InvalidInput(
      fmt::format("unknown parameter '{}'; known: {}", name, fmt::join(ParameterNames(s), ", ")));
}

}  // namespace

std::span<const ParameterSpec> ParameterTable() { return kTable; }

const ParameterSpec* FindParameter(const System& s, std::string_view name) {
  for (const ParameterSpec& spec : kTable) {
    if (spec.chain_only && !s.chain) continue;
    if (spec.stop  ? StopIndex(name, spec.name, s) >= 0
        : spec.get ? name == spec.name
                   : ForcingIndex(name, s.Dof()) >= 0) {
      return &spec;
    }
  }
  return nullptr;
}

std::vector<std::string> ParameterNames(const System& s) {
  std::vector<std::string> names;
  for (const ParameterSpec& spec : kTable) {
    if (spec.chain_only && !s.chain) continue;
    if (spec.stop) {
      for (int k = 0; k < s.StopCount(); ++k) names.push_back(StopParameterName(spec.name, k));
    } else if (spec.get) {
      names.emplace_back(spec.name);
    } else {
      for (int i = 0; i < s.Dof(); ++i) names.push_back(fmt::format("{}{}", spec.name, i + 1));
    }
  }
  return names;
}

NamedParameter::NamedParameter(const System& s, std::string_view name)
    : name_(name), spec_(FindParameter(s, name)) {
  if (!spec_) UnknownParameter(s, name);
  if (spec_->stop) {
    index_ = StopIndex(name, spec_->name, s);
  } else if (!spec_->get) {
    index_ = ForcingIndex(name, s.Dof());
  }
}

double NamedParameter::Get(const System& s) const {
  if (spec_->get) return spec_->get(s);
  if (spec_->stop) return s.stops.at(index_).*spec_->stop->member;
  Require(index_ < s.Dof(), "{}: the system has {} masses", name_, s.Dof());
  return s.forcing(index_);
}

void NamedParameter::Set(System& s, double value) const {
  if (spec_->set) {
    spec_->set(s, value);
  } else if (spec_->stop) {
    Require(index_ < s.StopCount(), "{}: the system has {} stops", name_, s.StopCount());
    s.stops[index_].*spec_->stop->member = value;
  } else {
    Require(index_ < s.Dof(), "{}: the system has {} masses", name_, s.Dof());
    s.forcing(index_) = value;
  }
}

double GetParameter(const System& s, std::string_view name) {
  return NamedParameter(s, name).Get(s);
}

void SetParameter(System& s, std::string_view name, double value) {
  NamedParameter(s, name).Set(s, value);
}

}  // namespace impactkit
