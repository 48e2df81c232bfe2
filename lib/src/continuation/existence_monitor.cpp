#include "continuation/existence_monitor.hpp"

#include <fmt/format.h>

namespace impactkit::detail {

std::optional<double> LinearMonitor(const PeriodicOrbit& orbit, Monitor monitor,
                                    bool next_clearance) {
  const OrbitContacts& c = orbit.contacts;
  if (monitor == Monitor::kClearance) return next_clearance ? c.next_clearance : c.clearance;
  if (!std::isfinite(c.slowest_depth)) return std::nullopt;
  return std::sqrt(c.slowest_depth);
}

double MonitorLength(double linear, Monitor monitor) {
  return monitor == Monitor::kClearance ? linear : linear * linear;
}

std::string ShortOfEvent(const OrbitContacts& c, double within, std::string_view where,
                         bool clearance) {
  if (c.slowest_depth < within) {
    return fmt::format("; impact {} vanishes {} (depth {:.1e}, not located to {:.0e})",
                       c.slowest_impact + 1, where, c.slowest_depth, kGrazingTolerance);
  }
  if (clearance && c.clearance && *c.clearance < within) {
    return fmt::format("; a new contact is born {} (clearance {:.1e}, not located to {:.0e})",
                       where, *c.clearance, kGrazingTolerance);
  }
  return "";
}

}  // namespace impactkit::detail
