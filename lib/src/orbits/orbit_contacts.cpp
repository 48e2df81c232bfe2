#include "impactkit/orbits/orbit_contacts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "impactkit/dynamics/events.hpp"

namespace impactkit {

namespace {

/// The interior extrema of the flight's coordinates that approach each
/// stop (maxima below an upper stop, minima above a lower one): the least
/// clearance among them, into `contacts`; and the extent of x_c, the
/// section stop's mass.
void MeasureFlight(const ImpactMap& map, const Eigen::VectorXd& from, int from_stop, double t1,
                   int flight, OrbitContacts* contacts) {
  const System& system = map.GetSystem();
  const EventOptions events{1e-13, 1.0};
  const double t0 = from(map.TimeIndex());
  const int section_dof = system.stops[map.SectionStop()].dof;
  for (int dof = 0; dof < system.Dof(); ++dof) {
    std::vector<int> stops;
    for (int j = 0; j < system.StopCount(); ++j) {
      if (system.stops[j].dof == dof) stops.push_back(j);
    }
    if (stops.empty()) continue;
    const Signal x = map.FlightCoordinate(from, dof, from_stop);
    for (double t : SignChanges(x.Derivative(), t0, t1, events)) {
      double value, slope, curvature;
      x.ValueSlopeCurvature(t, &value, &slope, &curvature);
      if (dof == section_dof) {
        contacts->contact_min = std::min(contacts->contact_min, value);
        contacts->contact_max = std::max(contacts->contact_max, value);
      }
      for (int j : stops) {
        const StopParameters& stop = system.stops[j];
        if (!(stop.Sign() * curvature < 0)) continue;  // turning away from this stop
        const double clearance = stop.Sign() * (stop.position - value);
        if (!contacts->clearance || clearance < *contacts->clearance) {
          contacts->next_clearance = contacts->clearance;
          contacts->clearance = clearance;
          contacts->clearance_time = t;
          contacts->clearance_flight = flight;
          contacts->clearance_stop = j;
        } else if (!contacts->next_clearance || clearance < *contacts->next_clearance) {
          contacts->next_clearance = clearance;
        }
      }
    }
  }
}

}  // namespace

OrbitContacts MeasureOrbitContacts(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  const MapResult image = map.Apply(eta, p, false);
  if (image.termination != Termination::kCompleted) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, Describe(image.termination)));
  }
  std::vector<Eigen::VectorXd> path{eta};
  path.insert(path.end(), image.path.begin(), image.path.end());
  std::vector<int> stops{map.SectionStop()};
  stops.insert(stops.end(), image.stops.begin(), image.stops.end());
  return MeasureOrbitContacts(map, path, stops);
}

OrbitContacts MeasureOrbitContacts(const ImpactMap& map, const std::vector<Eigen::VectorXd>& path,
                                   const std::vector<int>& stops) {
  const System& system = map.GetSystem();
  const int p = static_cast<int>(path.size()) - 1;
  OrbitContacts contacts;
  contacts.contact_min = contacts.contact_max = system.stops[map.SectionStop()].position;
  contacts.slowest_depth = std::numeric_limits<double>::infinity();
  for (int k = 0; k < p; ++k) {
    const Eigen::VectorXd &from = path[k], &to = path[k + 1];
    const double t1 = to(map.TimeIndex());
    MeasureFlight(map, from, stops[k], t1, k, &contacts);
    const StopParameters& arrival = system.stops[stops[k + 1]];
    double value, speed, acceleration;
    map.FlightCoordinate(from, arrival.dof, stops[k])
        .ValueSlopeCurvature(t1, &value, &speed, &acceleration);
    // The depth of a parabola x_c'' = a through the impact; infinite when
    // a = 0 (the mass would run on into the stop: no nearby event).
    const double depth = acceleration == 0.0 ? std::numeric_limits<double>::infinity()
                                             : speed * speed / (2.0 * std::abs(acceleration));
    if (k == 0 || depth < contacts.slowest_depth) {
      contacts.slowest_depth = depth;
      contacts.slowest_impact = (k + 1) % p;
      contacts.slowest_pressed = arrival.Sign() * acceleration > 0;
    }
  }
  return contacts;
}

}  // namespace impactkit
