#include "impactkit/analysis/grid_cell.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

#include "impactkit/core/errors.hpp"

namespace impactkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Largest(const std::vector<double>& values) {
  return values.empty() ? kNaN : *std::max_element(values.begin(), values.end());
}

/// Reads the next whitespace-separated field of `in` as T; throws with the
/// field's name when it is missing or not a T.
template <typename T>
T Field(std::istringstream& in, const char* name, std::string_view line) {
  std::string text;
  if (!(in >> text)) throw InvalidInput(fmt::format("grid cell '{}': no {}", line, name));
  if constexpr (std::is_same_v<T, double>) {
    // from_chars, unlike strtod, ignores the locale: it reads exactly what
    // fmt wrote, "nan" included, back to the same bits.
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc() && end == text.data() + text.size()) return value;
  } else {
    T value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc() && end == text.data() + text.size()) return value;
  }
  throw InvalidInput(fmt::format("grid cell '{}': bad {} '{}'", line, name, text));
}

}  // namespace

GridCell CellOf(std::int64_t index, const SweepPoint& point) {
  const Classification& c = point.classification;
  GridCell cell;
  cell.index = index;
  cell.kind = c.kind;
  // The same rule as the sweep's summary: a period only for motions that repeat.
  if (c.period.periodic && c.kind != MotionKind::kUnresolved && c.kind != MotionKind::kChaotic) {
    cell.p = c.kind == MotionKind::kSticking ? 0 : c.period.p;
    cell.q = c.period.q;
  }
  cell.max_v = kNaN;
  for (const SweepImpact& i : point.impacts) {
    cell.max_v = std::isnan(cell.max_v) ? i.velocity : std::max(cell.max_v, i.velocity);
  }
  cell.range_xN = Largest(point.range_contact);
  cell.lyapunov = c.lyapunov_computed && c.lyapunov.valid ? c.lyapunov.largest : kNaN;
  cell.restarted = point.restarted;
  cell.events = point.events;
  return cell;
}

MotionKind MotionKindFromName(std::string_view name) {
  for (MotionKind kind : {MotionKind::kPeriodic, MotionKind::kSticking, MotionKind::kChaotic,
                          MotionKind::kNonImpacting, MotionKind::kUnresolved}) {
    if (ToString(kind) == name) return kind;
  }
  throw InvalidInput(fmt::format("unknown motion kind '{}'", name));
}

std::string CellToText(const GridCell& cell) {
  std::string text = fmt::format("{} {} {} {} {} {} {} {} {} {}", cell.index, ToString(cell.kind),
                                 cell.p, cell.q, cell.max_v, cell.range_xN, cell.lyapunov,
                                 cell.restarted ? 1 : 0, cell.events, cell.orbit.size());
  for (const AttractorImpact& i : cell.orbit) text += fmt::format(" {} {}", i.phase, i.velocity);
  return text;
}

GridCell CellFromText(std::string_view line) {
  std::istringstream in{std::string(line)};
  GridCell cell;
  cell.index = Field<std::int64_t>(in, "index", line);
  std::string kind;
  in >> kind;
  cell.kind = MotionKindFromName(kind);
  cell.p = Field<int>(in, "p", line);
  cell.q = Field<int>(in, "q", line);
  cell.max_v = Field<double>(in, "max_v", line);
  cell.range_xN = Field<double>(in, "range_xN", line);
  cell.lyapunov = Field<double>(in, "lyapunov", line);
  cell.restarted = Field<int>(in, "restarted", line) != 0;
  cell.events = Field<std::int64_t>(in, "events", line);
  const int n = Field<int>(in, "orbit size", line);
  Require(n >= 0, fmt::format("grid cell '{}': negative orbit size", line));
  for (int k = 0; k < n; ++k) {
    const double phase = Field<double>(in, "phase", line);
    cell.orbit.push_back({phase, Field<double>(in, "velocity", line)});
  }
  std::string rest;
  Require(!(in >> rest), fmt::format("grid cell '{}': unexpected '{}' at the end", line, rest));
  return cell;
}

}  // namespace impactkit
