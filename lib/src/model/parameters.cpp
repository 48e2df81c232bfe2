#include "impactkit/model/parameters.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>

namespace impactkit {
namespace {

/// Index of the parameter A<i> (1-based in the name), or -1.
int ForcingIndex(std::string_view name, int dof) {
  if (name.size() < 2 || name[0] != 'A') return -1;
  int index = 0;
  for (char ch : name.substr(1)) {
    if (ch < '0' || ch > '9') return -1;
    index = index * 10 + (ch - '0');
    if (index > dof) return -1;
  }
  return index >= 1 ? index - 1 : -1;
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
  s = UniformChain(chain, forcing, s.omega, s.stop, s.restitution);
}

void SetDof(System& s, double value) {
  // The modal decomposition costs O(N³) and every event O(N²): n = 1000
  // takes half a minute per forcing period (docs/performance.md).
  if (!(std::isfinite(value) && value >= 1 && value == std::floor(value) &&
        value <= kMaxDegreesOfFreedom)) {
    throw InvalidInput(fmt::format("n (number of masses) must be a whole number in [1, {}], got {}",
                                   kMaxDegreesOfFreedom, value));
  }
  RebuildChain(s, [&](ChainParameters& c) { c.dof = static_cast<int>(value); });
}

constexpr std::array<ParameterSpec, 8> kTable = {{
    {"omega", "forcing frequency", "> 0", false, [](const System& s) { return s.omega; },
     [](System& s, double v) { s.omega = v; }},
    {"xs", "stop position", "finite", false, [](const System& s) { return s.stop; },
     [](System& s, double v) { s.stop = v; }},
    {"r", "coefficient of restitution", "in [0, 1]", false,
     [](const System& s) { return s.restitution; }, [](System& s, double v) { s.restitution = v; }},
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

[[noreturn]] void UnknownParameter(const System& s, std::string_view name) {
  throw InvalidInput(
      fmt::format("unknown parameter '{}'; known: {}", name, fmt::join(ParameterNames(s), ", ")));
}

}  // namespace

std::span<const ParameterSpec> ParameterTable() { return kTable; }

const ParameterSpec* FindParameter(const System& s, std::string_view name) {
  for (const ParameterSpec& spec : kTable) {
    if (spec.chain_only && !s.chain) continue;
    if (spec.get ? name == spec.name : ForcingIndex(name, s.Dof()) >= 0) return &spec;
  }
  return nullptr;
}

std::vector<std::string> ParameterNames(const System& s) {
  std::vector<std::string> names;
  for (const ParameterSpec& spec : kTable) {
    if (spec.chain_only && !s.chain) continue;
    if (spec.get) {
      names.emplace_back(spec.name);
    } else {
      for (int i = 0; i < s.Dof(); ++i) names.push_back(fmt::format("{}{}", spec.name, i + 1));
    }
  }
  return names;
}

double GetParameter(const System& s, std::string_view name) {
  const ParameterSpec* spec = FindParameter(s, name);
  if (!spec) UnknownParameter(s, name);
  return spec->get ? spec->get(s) : s.forcing(ForcingIndex(name, s.Dof()));
}

void SetParameter(System& s, std::string_view name, double value) {
  const ParameterSpec* spec = FindParameter(s, name);
  if (!spec) UnknownParameter(s, name);
  if (spec->set) {
    spec->set(s, value);
  } else {
    s.forcing(ForcingIndex(name, s.Dof())) = value;
  }
}

}  // namespace impactkit
