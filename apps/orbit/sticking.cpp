#include "orbit/sticking.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"

namespace impactkit::cli {
namespace {

/// The impacts of stuck phase k's cycle (from the release before it to its
/// accumulation) faster than the bound: the chatter's tail of ever slower
/// impacts left out.
std::vector<OrbitImpact> FastImpacts(const PeriodicOrbit& orbit, std::size_t k, double min_speed) {
  std::vector<OrbitImpact> fast;
  for (const OrbitImpact& impact : CycleImpacts(orbit, k)) {
    if (impact.velocity > min_speed) fast.push_back(impact);
  }
  return fast;
}

/// " at stop 2", " at stops 1 and 2": where the orbit sticks, 1-based;
/// nothing for a system of one stop.
std::string StuckStops(const System& system, const PeriodicOrbit& orbit) {
  if (system.StopCount() == 1) return "";
  std::vector<int> stops;
  for (const StuckPhase& stuck : orbit.stuck) stops.push_back(stuck.stop + 1);
  std::sort(stops.begin(), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
  if (stops.size() == 1) return fmt::format(" at stop {}", stops[0]);
  const int last = stops.back();
  stops.pop_back();
  return fmt::format(" at stops {} and {}", fmt::join(stops, ", "), last);
}

void Print(const System& system, const PeriodicOrbit& orbit, const OrbitSummary& summary,
           double min_speed) {
  fmt::print("system:      {}\n", DescribeSystem(system));
  const std::string at_stop = StuckStops(system, orbit);
  fmt::print("orbit:       sticking P(inf,{}) at omega = {}, {} sticking phase{}{}, {}\n", orbit.q,
             orbit.omega, orbit.releases, orbit.releases == 1 ? "" : "s", at_stop,
             orbit.stable ? "stable" : "unstable");
  const bool several = system.StopCount() > 1;
  fmt::print(
      "sticking:    stick phase          release phase        stuck duration  {}"
      "(t mod T, T = {:.6g})\n",
      several ? "stop  " : "", system.ForcingPeriod());
  for (const StuckPhase& stuck : orbit.stuck) {
    fmt::print("             {:<20.12f} {:<20.12f} {:.12f}{}\n", stuck.stick_phase,
               stuck.release_phase, stuck.Duration(),
               several ? fmt::format("  {}", stuck.stop + 1) : "");
  }
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    const std::vector<OrbitImpact> fast = FastImpacts(orbit, k, min_speed);
    fmt::print("impacts:     {} before the accumulation at phase {:.12f}, {} faster than {}:\n",
               orbit.stuck[k].impacts, orbit.stuck[k].stick_phase, fast.size(), min_speed);
    for (const OrbitImpact& i : fast) {
      const std::string at = system.StopCount() > 1 ? fmt::format("  stop {}", i.stop + 1) : "";
      fmt::print("             phase {:<22.12f} velocity {:.12f}{}\n", i.phase, i.velocity, at);
    }
  }
  fmt::print("multipliers: on the release section (sticking collapses x{0}, v{0})\n",
             system.stops[orbit.stop].dof + 1);
  for (const std::complex<double>& m : orbit.multipliers) {
    fmt::print("             {:<+20.12e} {:<+20.12e} {:.12f}\n", m.real(), m.imag(), std::abs(m));
  }
  fmt::print("solve:       {}\n", summary.BriefReport());
}

nlohmann::json OrbitJson(const System& system, const PeriodicOrbit& orbit,
                         const OrbitSummary& summary, double min_speed) {
  nlohmann::json j;
  j["kind"] = "sticking";
  j["stop"] = orbit.stop + 1;  // 1-based, as in the system file and --stop
  j["q"] = orbit.q;
  j["releases"] = orbit.releases;
  j["omega"] = orbit.omega;
  j["stable"] = orbit.stable;
  j["residual"] = orbit.residual;
  j["iterations"] = summary.iterations;
  std::vector<double> stick_phases, release_phases, stuck_durations;
  for (const StuckPhase& stuck : orbit.stuck) {
    stick_phases.push_back(stuck.stick_phase);
    release_phases.push_back(stuck.release_phase);
    stuck_durations.push_back(stuck.Duration());
  }
  j["stick_phases"] = stick_phases;
  j["release_phases"] = release_phases;
  j["stuck_durations"] = stuck_durations;
  j["min_speed"] = min_speed;
  j["chatter"] = nlohmann::json::array();
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    nlohmann::json impacts = nlohmann::json::array();
    for (const OrbitImpact& i : FastImpacts(orbit, k, min_speed)) {
      impacts.push_back(
          {{"t", i.t}, {"phase", i.phase}, {"velocity", i.velocity}, {"stop", i.stop + 1}});
    }
    j["chatter"].push_back({{"stop", orbit.stuck[k].stop + 1},
                            {"impacts", orbit.stuck[k].impacts},
                            {"accumulation", orbit.stuck[k].stick},
                            {"contact_force", orbit.stuck[k].contact_force},
                            {"fast_impacts", impacts}});
  }
  j["multipliers"] = nlohmann::json::array();
  for (const std::complex<double>& m : orbit.multipliers) {
    j["multipliers"].push_back({m.real(), m.imag()});
  }
  j["state"] = std::vector<double>(orbit.eta.begin(), orbit.eta.end());
  j["system"] = nlohmann::json::parse(SystemToJson(system));
  return j;
}

}  // namespace

void ReportStickingOrbit(const System& system, const PeriodicOrbit& orbit,
                         const OrbitSummary& summary, double min_speed, bool check_jacobian,
                         AtomicOutputFile* json, const std::string& json_path,
                         const SystemOptions& source) {
  Print(system, orbit, summary, min_speed);
  nlohmann::json j = OrbitJson(system, orbit, summary, min_speed);
  j["provenance"] =
      MakeProvenance(source, system, fmt::format("orbit --sticking --q {}", orbit.q)).Json();
  if (check_jacobian) {
    StickingMapOptions map;
    map.stop = orbit.stop;
    const Eigen::MatrixXd fd =
        FiniteDifferenceJacobian(StickingMap(system, map), orbit.eta, orbit.releases);
    if (fd.size() == 0) {
      throw std::runtime_error(
          "the finite-difference Jacobian cannot be formed here: a perturbed map does not stick");
    }
    const double difference = (orbit.jacobian - fd).cwiseAbs().maxCoeff();
    const double relative = difference / std::max(1.0, orbit.jacobian.cwiseAbs().maxCoeff());
    fmt::print(
        "check:       analytic vs finite-difference Jacobian: largest difference {:.3e} "
        "({:.3e} relative to its largest entry)\n",
        difference, relative);
    j["jacobian_check"] = {{"max_difference", difference}, {"max_relative_difference", relative}};
  }
  if (json) {
    json->Write(j.dump(2) + "\n");
    json->Commit();
    fmt::print("wrote:       {}\n", json_path);
  }
}

}  // namespace impactkit::cli
