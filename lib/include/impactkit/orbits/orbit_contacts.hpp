#pragma once
/// \file orbit_contacts.hpp
/// How near a periodic orbit is to changing its sequence of impacts — the
/// monitors that end smooth continuation (docs/theory.md §6) — and its extent in
/// the contact coordinate x_c.
///
/// Two events end a P(p, q) branch, each watched by a quantity that is
/// positive on the branch, smooth along it and zero at the event:
///  - a new contact: the highest interior maximum of x_c in a free flight
///    rises to the stop; its clearance xs - max is the monitor (with
///    several stops, the least clearance of any mass's interior extremum
///    towards any of its stops: a lower stop's minima);
///  - a vanishing impact: the slowest impact's speed v goes to 0. Its
///    monitor is the depth v² / (2|a|), a = x_c'' on arrival — how far the
///    parabola through the impact would reach past the stop. v itself goes
///    like the square root of the distance to the event (a grazing is a
///    square-root singularity of the impact map); v²/(2|a|) goes linearly,
///    so a secant step locates its zero. With a < 0 the mass turns back
///    (grazing); with a > 0 it is pressed into the stop and the impacts
///    accumulate (sticking onset).

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <vector>

#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {

/// Of a sticking orbit (sticking_orbit.hpp) the extent, the least
/// clearance of its flights (its time and stop) and the sticking monitors
/// are measured; the clearance's flight and the next one are not.
struct OrbitContacts {
  double contact_min = 0.0;  ///< least x_c over the orbit (c: the section stop's mass)
  double contact_max = 0.0;  ///< greatest x_c over the orbit
  /// xs - the highest interior maximum of x_c over the flights; empty when
  /// no flight has an interior maximum.
  std::optional<double> clearance;
  double clearance_time = 0.0;  ///< when the highest interior maximum occurs
  int clearance_flight = 0;     ///< the impact (index) whose flight holds it (impacting orbits)
  int clearance_stop = 0;       ///< the stop it approaches
  /// The same for the next highest interior extremum (another one, in any
  /// flight): on a grazing curve, whose own touch is `clearance`, the
  /// monitor of a second contact. Empty with fewer than two.
  std::optional<double> next_clearance;
  /// v² / (2|a|) of the slowest impact (the one with the least depth); a
  /// sticking orbit's chatter has impacts of every depth down to 0, so
  /// there it is not measured (infinity): its approach impacts are watched
  /// instead (approach_impact_speed).
  double slowest_depth = 0.0;
  int slowest_impact = 0;        ///< its index among the orbit's p impacts
  bool slowest_pressed = false;  ///< a > 0 there: pressed into the stop
  /// Sticking orbits only (infinity otherwise), each 0 where the family
  /// ends: the least Fs(t*) of its stuck phases (the chatter stops ending
  /// in sticking), the least hold margin (an early release), and the
  /// slowest approach impact (a vanishing impact). A cycle's approach
  /// impacts are those of the flights before its chatter: its first impact
  /// after the release and its impacts at other stops than the one that
  /// holds it at the cycle's end (the chatter's own impacts, at that stop,
  /// have speeds down to 0 on every orbit).
  double contact_margin = std::numeric_limits<double>::infinity();
  double hold_margin = std::numeric_limits<double>::infinity();
  double approach_impact_speed = std::numeric_limits<double>::infinity();
  double Range() const { return contact_max - contact_min; }
};

/// The contacts of the orbit through the impact state `eta` (p impacts):
/// the interior extrema of x_c in each flight are the zeros of v_c, found by
/// the certified search of events.hpp. Throws InvalidInput if the map
/// cannot follow p impacts from eta.
OrbitContacts MeasureOrbitContacts(const ImpactMap& map, const Eigen::VectorXd& eta, int p);
/// The same along known impacts: `path` η_0 … η_p (η_p = η_0 a whole number
/// of periods on) at `stops` s_0 … s_p, where the map need not resolve them.
OrbitContacts MeasureOrbitContacts(const ImpactMap& map, const std::vector<Eigen::VectorXd>& path,
                                   const std::vector<int>& stops);

}  // namespace impactkit
