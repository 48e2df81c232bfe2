// impactkit.continue_branch, Branch and SpecialPoint:
// continuation/continuation.hpp.
#include "impactkit/continuation/continuation.hpp"

#include <fmt/format.h>
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>

#include "bindings.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/io/branch_output.hpp"
#include "option_sets.hpp"

namespace impactkit::python {
namespace {

ContinuationDirection DirectionFromName(const std::string& name) {
  if (name == "increasing") return ContinuationDirection::kIncreasing;
  if (name == "decreasing") return ContinuationDirection::kDecreasing;
  if (name == "both") return ContinuationDirection::kBoth;
  throw InvalidInput("direction must be 'increasing', 'decreasing' or 'both', got '" + name + "'");
}

std::string DirectionName(ContinuationDirection direction) {
  switch (direction) {
    case ContinuationDirection::kIncreasing:
      return "increasing";
    case ContinuationDirection::kDecreasing:
      return "decreasing";
    case ContinuationDirection::kBoth:
      return "both";
  }
  return "increasing";  // not reached: every direction has its name above
}

ContinuationOptions MakeOptions(const std::string& parameter, double from, double to,
                                const std::string& direction, double initial_step, double min_step,
                                double max_step, int max_points, bool locate_bifurcations) {
  ContinuationOptions options;
  options.parameter = parameter;
  options.from = from;
  options.to = to;
  options.direction = DirectionFromName(direction);
  options.initial_step = initial_step;
  options.min_step = min_step;
  options.max_step = max_step;
  options.max_points = max_points;
  options.locate_bifurcations = locate_bifurcations;
  return options;
}

Branch ContinueFromStart(const BranchStart& start, const std::string& parameter, double from,
                         double to, const std::string& direction, double initial_step,
                         double min_step, double max_step, int max_points, bool locate_bifurcations,
                         const std::optional<py::dict>& user_tests, const py::object& progress) {
  ContinuationOptions options = MakeOptions(parameter, from, to, direction, initial_step, min_step,
                                            max_step, max_points, locate_bifurcations);
  options.user_tests = UserTestsFrom(user_tests);
  if (!start.orbit.Sticks()) {  // a sticking family is its start's
    options.orbit.p = start.orbit.p;
    options.orbit.q = start.orbit.q;
  }
  const InterruptibleRun run(progress);
  return WithoutGil([&] {
    Branch branch = ContinueBranch(start, options, run);
    PredictGrazings(start.system, &branch);
    return branch;
  });
}

Branch ContinueFromOrbit(const System& system, const PeriodicOrbit& orbit,
                         const std::string& parameter, double from, double to,
                         const std::string& direction, double initial_step, double min_step,
                         double max_step, int max_points, bool locate_bifurcations,
                         const std::optional<py::dict>& user_tests, const py::object& progress) {
  return ContinueFromStart({system, orbit, {}}, parameter, from, to, direction, initial_step,
                           min_step, max_step, max_points, locate_bifurcations, user_tests,
                           progress);
}

/// The library's switching functions need only the orbit and corrector
/// options of the branch (its defaults here) and the branch's own p, q and
/// parameter.
ContinuationOptions SwitchingOptions(const Branch& branch) {
  ContinuationOptions options;
  options.parameter = branch.parameter;
  if (branch.section == OrbitSection::kImpact) {
    options.orbit.p = branch.p;
    options.orbit.q = branch.q;
  }
  return options;
}

std::optional<BranchStart> DoubledStart(const System& system, const Branch& branch,
                                        const SpecialPoint& pd, double offset) {
  Require(pd.type == SpecialPointType::kPeriodDoubling,
          "doubled_branch_start needs a period_doubling point, got " + ToString(pd.type));
  return WithoutGil(
      [&] { return DoubledBranchStart(system, branch, pd, SwitchingOptions(branch), offset); });
}

std::vector<GrazingSeed> GrazingSeeds(const System& system, const Branch& branch,
                                      const SpecialPoint& graze, double offset) {
  Require(graze.type == SpecialPointType::kGrazing || graze.type == SpecialPointType::kSticking,
          "seeds_at_grazing needs a grazing or sticking point, got " + ToString(graze.type));
  return WithoutGil(
      [&] { return SeedsAtGrazing(system, branch, graze, SwitchingOptions(branch), offset); });
}

/// impactkit.ContinuationOptions: the keywords of continue_branch (but the
/// start and user_tests), over ContinuationOptions.
void BindContinuationOptions(py::module_& module, const ContinuationOptions& defaults) {
  OptionSetBinding<ContinuationOptions>(defaults)
      .Field("parameter", &ContinuationOptions::parameter,
             "The continued parameter: a name of System.parameter_names().")
      .Required("from_", &ContinuationOptions::from,
                "One end of the parameter's range (either order): the branch stays within it "
                "and ends on reaching an end.")
      .Required("to", &ContinuationOptions::to, "The other end of the parameter's range.")
      .Converted(
          "direction", [](const ContinuationOptions& o) { return DirectionName(o.direction); },
          [](ContinuationOptions& o, const std::string& name) {
            o.direction = DirectionFromName(name);
          },
          "Initial sense of the parameter from the start: 'increasing', 'decreasing', or "
          "'both' (follows the branch both ways).")
      .Field("initial_step", &ContinuationOptions::initial_step,
             "Arclength step in (eta, parameter) space: the first.")
      .Field("min_step", &ContinuationOptions::min_step,
             "Arclength step in (eta, parameter) space: the floor.")
      .Field("max_step", &ContinuationOptions::max_step,
             "Arclength step in (eta, parameter) space: the ceiling.")
      .Field("max_points", &ContinuationOptions::max_points, "Points at most, per direction.")
      .Field("locate_bifurcations", &ContinuationOptions::locate_bifurcations,
             "Locate fold, period doubling and Neimark-Sacker points (grazing and sticking are "
             "always watched: they end the branch).")
      .Bind(module, "ContinuationOptions",
            "The keywords of impactkit.continue_branch (but the start and user_tests), with "
            "its defaults: the library's ContinuationOptions "
            "(continuation/continuation.hpp). from_ and to have none: "
            "impactkit.continue_branch(system, orbit, **impactkit.ContinuationOptions(from_=1.5, "
            "to=1.8)) passes a set.");
}

}  // namespace

void BindContinuation(py::module_& module) {
  py::class_<SpecialPoint>(module, "SpecialPoint",
                           "A located fold, period doubling, Neimark-Sacker, grazing, sticking "
                           "or branch point of a branch, or the end of a sticking family.")
      .def_property_readonly(
          "type", [](const SpecialPoint& s) { return ToString(s.type); },
          "'fold', 'period_doubling', 'neimark_sacker', 'grazing', 'sticking', "
          "'branch_point', 'pitchfork', 'user_test', or of a sticking family 'no_sticking' or "
          "'early_release'.")
      .def_readonly("user_test", &SpecialPoint::user_test,
                    "A user test's zero: the test's name (its key in user_tests).")
      .def_readonly("parameter", &SpecialPoint::parameter, "The parameter value there.")
      .def_readonly("multiplier", &SpecialPoint::multiplier,
                    "The critical multiplier (fold, period doubling, Neimark-Sacker).")
      .def_property_readonly(
          "multipliers", [](const SpecialPoint& s) { return s.point.orbit.multipliers; },
          "All multipliers of the orbit at the located point.")
      .def_property_readonly(
          "eigenvector", [](const SpecialPoint& s) { return s.eigenvector; },
          "Period doubling: the real eigenvector of D P for -1 (else empty).")
      .def_readonly("monitor", &SpecialPoint::monitor,
                    "The test function, or the clearance/depth for grazing and sticking.")
      .def_readonly("vanishing_impact", &SpecialPoint::vanishing_impact,
                    "Grazing/sticking: which impact vanishes (-1 for a new contact).")
      .def_property_readonly(
          "orbit", [](const SpecialPoint& s) { return s.point.orbit; },
          "The orbit at the located point.")
      .def_property_readonly(
          "normal_form", [](const SpecialPoint& s) { return NormalFormDict(s.normal_form); },
          "A grazing's discontinuity-map normal form and, once predicted, what the motion does "
          "past it (its 'prediction'): the dict files carry under 'normal_form' "
          "(docs/continuation.md, 'What a grazing will do'); None for other points.")
      .def_readonly("normal_form_note", &SpecialPoint::normal_form_note,
                    "Why a grazing has no normal form, when it has none.")
      .def("describe", &SpecialPoint::Describe, py::arg("parameter_name"),
           "One line, as the command line prints it.")
      .def("__repr__", [](const SpecialPoint& s) {
        return "impactkit.SpecialPoint(" + ToString(s.type) +
               ", parameter=" + py::repr(py::float_(s.parameter)).cast<std::string>() + ")";
      });

  py::class_<UnlocatedZero>(module, "UnlocatedZero",
                            "A step of a branch over which a fold or period-doubling test "
                            "changed sign and the locator could not account for it: a fold or "
                            "period doubling may lie in the step, missing from special_points.")
      .def_property_readonly(
          "type", [](const UnlocatedZero& u) { return ToString(u.type); },
          "The test that changed sign: 'fold' or 'period_doubling'.")
      .def_property_readonly(
          "values",
          [](const UnlocatedZero& u) {
            return std::pair{u.from, u.to};
          },
          "The parameter at the step's two ends, in order along the branch.")
      .def("describe", &UnlocatedZero::Describe, py::arg("parameter_name"),
           "One line, as the command line prints it.")
      .def("__repr__", [](const UnlocatedZero& u) {
        return "impactkit.UnlocatedZero(" + ToString(u.type) +
               ", values=" + py::repr(py::make_tuple(u.from, u.to)).cast<std::string>() + ")";
      });

  py::class_<Branch>(module, "Branch",
                     "A branch of P(p, q) orbits, or of sticking orbits P(inf, q): its points "
                     "in order, as arrays, and its special points.")
      .def_readonly("parameter", &Branch::parameter, "The continued parameter's name.")
      .def_property_readonly(
          "section", [](const Branch& b) { return ToString(b.section); },
          "'impact' (P(p, q) orbits) or 'release' (sticking orbits).")
      .def_readonly("p", &Branch::p,
                    "Impacts per orbit (of the orbit followed: a start that is a shorter orbit "
                    "traversed several times is followed as that orbit); 0 for sticking orbits.")
      .def_readonly("q", &Branch::q, "Forcing periods per orbit.")
      .def_readonly("releases", &Branch::releases,
                    "Sticking phases per orbit (0 for impacting orbits).")
      .def_property_readonly(
          "values",
          [](const Branch& b) {
            return Column<double>(b.points, [](const BranchPoint& p) { return p.parameter; });
          },
          "The parameter at each point, shape (n,).")
      .def_property_readonly(
          "arclength",
          [](const Branch& b) {
            return Column<double>(b.points, [](const BranchPoint& p) { return p.arclength; });
          },
          "Signed arclength from the start, shape (n,).")
      .def_property_readonly(
          "eta",
          [](const Branch& b) {
            const auto n = static_cast<py::ssize_t>(b.points.size());
            const py::ssize_t size = n == 0 ? 0 : b.points.front().orbit.eta.size();
            std::vector<double> eta;
            for (const BranchPoint& p : b.points)
              eta.insert(eta.end(), p.orbit.eta.begin(), p.orbit.eta.end());
            return MoveToArray<double, 2>(std::move(eta), {n, size});
          },
          "The fixed point at each point, shape (n, 2N) (sticking orbits: (n, 2N - 1)).")
      .def_property_readonly(
          "multipliers",
          [](const Branch& b) {
            const auto n = static_cast<py::ssize_t>(b.points.size());
            const py::ssize_t size = n == 0 ? 0 : b.points.front().orbit.multipliers.size();
            std::vector<std::complex<double>> m;
            for (const BranchPoint& p : b.points) {
              m.insert(m.end(), p.orbit.multipliers.begin(), p.orbit.multipliers.end());
            }
            return MoveToArray<std::complex<double>, 2>(std::move(m), {n, size});
          },
          "The multipliers at each point (complex), shape (n, 2N).")
      .def_property_readonly(
          "stable",
          [](const Branch& b) {
            py::array_t<bool> stable(static_cast<py::ssize_t>(b.points.size()));
            for (std::size_t i = 0; i < b.points.size(); ++i) {
              stable.mutable_at(static_cast<py::ssize_t>(i)) = b.points[i].orbit.stable;
            }
            return stable;
          },
          "Stability at each point, shape (n,) bool.")
      .def_property_readonly(
          "orbits",
          [](const Branch& b) {
            py::list orbits;
            for (const BranchPoint& p : b.points) orbits.append(py::cast(p.orbit));
            return orbits;
          },
          "The orbit at each point (a list of Orbit).")
      .def_readonly("special_points", &Branch::special_points, "In order along the branch.")
      .def_readonly("unlocated", &Branch::unlocated,
                    "Steps whose fold or period-doubling sign change was not located (a list of "
                    "UnlocatedZero, in order along the branch; usually empty).")
      .def_property_readonly(
          "end", [](const Branch& b) { return ToString(b.end); },
          "Why the last point is the last: 'parameter_bound', 'grazing', 'sticking', "
          "'branch_point', 'max_points', 'corrector_failed', or for sticking orbits "
          "'no_sticking' or 'early_release'.")
      .def_readonly("end_message", &Branch::end_message, "The end in words.")
      .def_property_readonly(
          "begin",
          [](const Branch& b) -> std::optional<std::string> {
            if (!b.begin) return std::nullopt;
            return ToString(*b.begin);
          },
          "With direction='both': why the first point is the first (else None).")
      .def_readonly("begin_message", &Branch::begin_message,
                    "With direction='both': the beginning in words.")
      .def_readonly("seconds", &Branch::seconds, "Wall time.")
      .def(
          "to_json", [](const Branch& b) { return BranchJson(b, "main", "continue_branch"); },
          "The branch as JSON text: the object `impactkit continue --json` writes for each "
          "branch (io/branch_output.hpp; label 'main').")
      .def(
          "write_csv",
          [](const Branch& b, const std::filesystem::path& path) {
            CsvWriter csv(path,
                          fmt::format("impactkit {} (Python): continue_branch in {}",
                                      IMPACTKIT_VERSION, b.parameter),
                          BranchColumns(b));
            WriteBranchRows(csv, b);
            csv.Commit();
          },
          py::arg("path"),
          "Writes the branch as `impactkit continue --out` does: one row per point, the same "
          "columns (docs/cli.md), the provenance as comment lines after the header.")
      .def("__len__", [](const Branch& b) { return b.points.size(); })
      .def("__repr__", [](const Branch& b) {
        return "impactkit.Branch(" + FamilyName(b) + " in " + b.parameter + ", " +
               std::to_string(b.points.size()) + " points, " +
               std::to_string(b.special_points.size()) + " special points, end " + ToString(b.end) +
               ")";
      });

  py::class_<BranchStart>(module, "BranchStart",
                          "Where a branch starts: a converged orbit of `system` and the initial "
                          "direction in (eta, parameter).")
      .def_readonly("system", &BranchStart::system)
      .def_readonly("orbit", &BranchStart::orbit)
      .def_property_readonly(
          "direction", [](const BranchStart& s) { return s.direction; },
          "Unit direction in (eta, parameter), size 2N + 1 (empty: from `direction`).");

  py::class_<GrazingSeed>(module, "GrazingSeed",
                          "A seed at a grazing point for the orbit with one impact more or "
                          "fewer: refine it with find_orbit(seed.system, p=seed.p, q=seed.q, "
                          "stop=seed.stop, seed=seed.eta) (a sticking family's with "
                          "releases=seed.releases instead of p).")
      .def_readonly("system", &GrazingSeed::system, "At the seed's parameter value.")
      .def_property_readonly(
          "p", [](const GrazingSeed& s) { return s.orbit.p; }, "Impacts per orbit (p +- 1).")
      .def_property_readonly(
          "q", [](const GrazingSeed& s) { return s.orbit.q; }, "Forcing periods per orbit.")
      .def_property_readonly(
          "releases", [](const GrazingSeed& s) { return s.orbit.releases; },
          "Sticking phases per orbit of a sticking family's seed (else 0).")
      .def_property_readonly(
          "stop", [](const GrazingSeed& s) { return s.orbit.SectionStop(); },
          "The stop (0-based) the seed state is at: find_orbit's stop.")
      .def_property_readonly(
          "eta", [](const GrazingSeed& s) { return s.eta; },
          "The seed state: an impact state, or a sticking family's release state.");

  const char* continue_doc =
      R"(Follows the branch of `orbit` (found for `system`), or from a BranchStart,
in a named parameter between from_ and to (either order; `from` is a Python keyword) by pseudo-arclength continuation,
locating folds, period doublings, Neimark-Sacker points, and ending at
grazing or sticking.

direction: 'increasing', 'decreasing' or 'both' (a BranchStart's own
direction, when it has one, takes precedence). user_tests: {name:
function(Orbit) -> float}, test functions of your own whose zeros are
located like the bifurcations' (special points 'user_test' with that name).
Returns a Branch. Raises ValueError for bad input, and what a user test
raises. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
progress: True draws a tqdm bar where tqdm is installed; a callable gets {stage,
done, total, parameter, parameter2} at each report.
Its keywords are impactkit.ContinuationOptions's (but user_tests):
`continue_branch(system, orbit, **impactkit.ContinuationOptions(...))` passes a set.)";
  // The defaults are the library's, as the command line's are: those of the
  // function's keywords and of ContinuationOptions, from the same struct.
  const ContinuationOptions kBranch;
  BindContinuationOptions(module, kBranch);
  module.def("continue_branch", &ContinueFromOrbit, py::arg("system"), py::arg("orbit"),
             py::kw_only(), py::arg("parameter") = kBranch.parameter, py::arg("from_"),
             py::arg("to"), py::arg("direction") = DirectionName(kBranch.direction),
             py::arg("initial_step") = kBranch.initial_step, py::arg("min_step") = kBranch.min_step,
             py::arg("max_step") = kBranch.max_step, py::arg("max_points") = kBranch.max_points,
             py::arg("locate_bifurcations") = kBranch.locate_bifurcations,
             py::arg("user_tests") = py::none(), py::arg("progress") = false, continue_doc);
  module.def("continue_branch", &ContinueFromStart, py::arg("start"), py::kw_only(),
             py::arg("parameter") = kBranch.parameter, py::arg("from_"), py::arg("to"),
             py::arg("direction") = DirectionName(kBranch.direction),
             py::arg("initial_step") = kBranch.initial_step, py::arg("min_step") = kBranch.min_step,
             py::arg("max_step") = kBranch.max_step, py::arg("max_points") = kBranch.max_points,
             py::arg("locate_bifurcations") = kBranch.locate_bifurcations,
             py::arg("user_tests") = py::none(), py::arg("progress") = false, continue_doc);
  module.def("doubled_branch_start", &DoubledStart, py::arg("system"), py::arg("branch"),
             py::arg("period_doubling"), py::kw_only(), py::arg("offset") = 1e-3,
             R"(A first point on the P(2p, 2q) branch born at a period doubling of
`branch` (continued for `system`), `offset` away along the flip eigenvector,
heading away from it: a BranchStart for continue_branch, or None when the
corrector does not reach a genuinely doubled orbit.)");
  module.def("seeds_at_grazing", &GrazingSeeds, py::arg("system"), py::arg("branch"),
             py::arg("grazing"), py::kw_only(), py::arg("offset") = 1e-3,
             R"(Seeds at a grazing (or sticking) point of `branch` for the orbits with one
impact more and one fewer, `offset` to either side in the parameter: a list
of GrazingSeed (empty when p would drop to 0).)");
}

}  // namespace impactkit::python
