#include "impactkit/orbits/orbit_contacts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "impactkit/dynamics/events.hpp"

namespace impactkit {

OrbitContacts MeasureOrbitContacts(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  const MapResult image = map.Apply(eta, p, false);
  if (image.status != MapStatus::kOk) {
    throw InvalidInput(fmt::format("no orbit through this impact state: after {} of {} impacts, {}",
                                   image.impacts_done, p, ToString(image.status)));
  }
  const System& system = map.GetSystem();
  const int c = system.stops[0].dof;
  const EventOptions events{1e-13, 1.0};
  OrbitContacts contacts;
  contacts.contact_min = contacts.contact_max = system.stops[0].position;
  contacts.slowest_depth = std::numeric_limits<double>::infinity();
  Eigen::VectorXd from = eta;
  for (int k = 0; k < p; ++k) {
    const Eigen::VectorXd& to = image.path[k];
    const double t0 = from(map.TimeIndex()), t1 = to(map.TimeIndex());
    const Signal x = map.FlightCoordinate(from, c);
    for (double t : SignChanges(x.Derivative(), t0, t1, events)) {
      double value, slope, curvature;
      x.ValueSlopeCurvature(t, &value, &slope, &curvature);
      contacts.contact_min = std::min(contacts.contact_min, value);
      contacts.contact_max = std::max(contacts.contact_max, value);
      if (curvature < 0) {
        const double clearance = system.stops[0].position - value;
        if (!contacts.clearance || clearance < *contacts.clearance) {
          contacts.clearance = clearance;
          contacts.clearance_time = t;
          contacts.clearance_flight = k;
        }
      }
    }
    double value, speed, acceleration;
    x.ValueSlopeCurvature(t1, &value, &speed, &acceleration);
    // The depth of a parabola x_c'' = a through the impact; infinite when
    // a = 0 (the mass would run on into the stop: no nearby event).
    const double depth = acceleration == 0.0 ? std::numeric_limits<double>::infinity()
                                             : speed * speed / (2.0 * std::abs(acceleration));
    if (k == 0 || depth < contacts.slowest_depth) {
      contacts.slowest_depth = depth;
      contacts.slowest_impact = (k + 1) % p;
      contacts.slowest_pressed = acceleration > 0;
    }
    from = to;
  }
  return contacts;
}

}  // namespace impactkit
