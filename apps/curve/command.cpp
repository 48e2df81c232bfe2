/// `impactkit curve`: a fold, period-doubling, Neimark–Sacker or grazing
/// point of a P(p, q) branch followed in two parameters, with the
/// codimension-two points along the curve (impactkit/continuation/curve.hpp
/// does the work).

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "common/arclength_flags.hpp"
#include "common/limits.hpp"
#include "common/orbit_seed.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "curve/output.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"

namespace impactkit::cli {
namespace {

/// Without --from/--to the first parameter stays within this factor of its
/// start value: a plane a paper would show, and a finite box for the curve.
constexpr double kDefaultRangeFactor = 4.0;

struct CurveRequest {
  SystemOptions system;
  OrbitSeedOptions seed;
  std::string type;
  std::string parameter = "omega", parameter2;
  std::optional<double> from, to;
  double from2 = 0.0, to2 = 0.0;
  std::string start_json;
  int point = 1;
  double step = CurveOptions{}.initial_step, min_step = CurveOptions{}.min_step,
         max_step = CurveOptions{}.max_step;
  int max_points = CurveOptions{}.max_points;
  std::string out, json, plot;
};

/// The special point a curve can follow that `name` names, if any.
std::optional<SpecialPointType> FollowableType(const std::string& name) {
  const std::optional<SpecialPointType> type = SpecialPointTypeFromName(name);
  if (type && HasCurve(*type)) return type;
  return std::nullopt;
}

SpecialPointType CurveType(const std::string& name) {
  const std::optional<SpecialPointType> type = FollowableType(name);
  Require(type.has_value(),
          fmt::format("--type must be fold, period_doubling, neimark_sacker or grazing, got '{}'",
                      name));
  return *type;
}

/// Both parameters' bounds, checked against the system before any work.
CurveOptions MakeOptions(const CurveRequest& request, const System& system) {
  CurveOptions options;
  options.parameter = request.parameter;
  options.parameter2 = request.parameter2;
  const double mu1 = GetParameter(system, request.parameter);
  const double mu2 = GetParameter(system, request.parameter2);
  Require(request.from.has_value() == request.to.has_value(), "--from and --to go together");
  Require(request.from || mu1 > 0,
          fmt::format("{} = {} starts at or below 0: give its bounds with --from and --to",
                      request.parameter, mu1));
  const double from = request.from.value_or(mu1 / kDefaultRangeFactor);
  const double to = request.to.value_or(mu1 * kDefaultRangeFactor);
  options.from = from;
  options.to = to;
  options.from2 = request.from2;
  options.to2 = request.to2;
  RequireArclengthFlags(request.step, request.min_step, request.max_step, request.max_points);
  options.initial_step = request.step;
  options.min_step = request.min_step;
  options.max_step = request.max_step;
  options.max_points = request.max_points;
  std::string error;
  Require(options.IsValid(&error), error);
  Require(mu1 >= options.Lower() && mu1 <= options.Upper(),
          fmt::format("the start {} = {} is not between --from and --to", request.parameter, mu1));
  Require(
      mu2 >= options.Lower2() && mu2 <= options.Upper2(),
      fmt::format("the start {} = {} is not between --from2 and --to2", request.parameter2, mu2));
  for (const auto& [name, flag, bound] :
       {std::tuple{request.parameter, "--from", from}, std::tuple{request.parameter, "--to", to},
        std::tuple{request.parameter2, "--from2", request.from2},
        std::tuple{request.parameter2, "--to2", request.to2}}) {
    System at = system;
    SetParameter(at, name, bound);
    try {
      Validate(at);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{} {} = {} is not valid: {}", flag, name, bound, e.what()));
    }
  }
  return options;
}

/// The start found as the issue describes: the orbit at the system's
/// values, its branch in --param, the point of --type nearest.
CurveStart FindStart(const CurveRequest& request, const System& system, CurveOptions* options) {
  const SpecialPointType type = CurveType(request.type);
  const StartOrbit found =
      SolveStartOrbit(system, StartRequest(system, request.seed, {}, StartOrbitKind::kImpacting));
  const PeriodicOrbit& orbit = found.orbit;
  options->orbit = found.options;
  ContinuationOptions search;
  search.parameter = request.parameter;
  search.from = options->from;
  search.to = options->to;
  search.orbit = found.options;
  const std::optional<SpecialPoint> special = LocateSpecialPoint({system, orbit, {}}, search, type);
  Require(special.has_value(),
          fmt::format("the P({},{}) branch through the start has no {} point for {} in [{}, {}]",
                      orbit.p, orbit.q, request.type, request.parameter, search.Lower(),
                      search.Upper()));
  System at = system;
  SetParameter(at, request.parameter, special->parameter);
  if (special->type != SpecialPointType::kGrazing || special->vanishing_impact < 0) {
    return {at, *special};
  }
  if (orbit.p == 1) {
    fmt::print(
        "origin:     P({},{})'s impact vanishes at {} = {:.10g}: the curve is where the "
        "non-impacting response touches the stop\n",
        orbit.p, orbit.q, request.parameter, special->parameter);
    return {at, *special};
  }
  Branch branch;
  branch.parameter = request.parameter;
  branch.p = orbit.p;
  branch.q = orbit.q;
  const std::optional<CurveStart> reduced = ReducedGrazingStart(system, branch, *special, search);
  fmt::print(
      "origin:     impact {} of P({},{}) vanishes at {} = {:.10g}: the curve is that of "
      "P({},{}) grazing by a new contact\n",
      special->vanishing_impact + 1, orbit.p, orbit.q, request.parameter, special->parameter,
      orbit.p - 1, orbit.q);
  if (!reduced) {
    throw std::runtime_error(
        fmt::format("no P({},{}) orbit found at the vanishing impact at {} = "
                    "{:.10g}",
                    orbit.p - 1, orbit.q, request.parameter, special->parameter));
  }
  return *reduced;
}

/// The start as `impactkit continue --json` reported it: special point
/// `point` (1-based) of FILE's main branch, on FILE's system.
CurveStart StartFromJson(const CurveRequest& request, System* system, CurveOptions* options) {
  std::ifstream in(request.start_json);
  Require(in.good(), fmt::format("--start-json {}: cannot be read", request.start_json));
  nlohmann::json j;
  try {
    in >> j;
    Require(j.value("section", std::string("impact")) != "release",
            fmt::format("--start-json {}: a sticking family P(inf,q) (`continue --sticking`); "
                        "curve follows fold, period_doubling, neimark_sacker and grazing points "
                        "of orbits P(p,q)",
                        request.start_json));
    const nlohmann::json& s = j.at("special_points").at(request.point - 1);
    const std::string type = s.at("type").get<std::string>();
    Require(FollowableType(type).has_value(),
            fmt::format("--start-json: point {} is a {}; curve follows fold, period_doubling, "
                        "neimark_sacker and grazing points",
                        request.point, type));
    std::ostringstream text;
    text << j.at("system");
    *system = ParseSystem(text.str(), SystemFileFormat::kJson, request.start_json);
    Require(s.at("parameter").get<std::string>() == request.parameter,
            fmt::format("--start-json: point {} is on a branch in {}, not --param {}",
                        request.point, s.at("parameter").get<std::string>(), request.parameter));
    Require(request.type.empty() || s.at("type").get<std::string>() == request.type,
            fmt::format("--start-json: point {} is a {}, not --type {}", request.point,
                        s.at("type").get<std::string>(), request.type));
    SetParameter(*system, request.parameter, s.at("param").get<double>());
    const std::vector<double> eta = s.at("eta").get<std::vector<double>>();
    OrbitOptions orbit;
    orbit.p = j.at("p").get<int>();
    orbit.q = j.at("q").get<int>();
    *options = MakeOptions(request, *system);
    options->orbit = orbit;
    CurveStart start{*system, {}};
    start.special.type = CurveType(s.at("type").get<std::string>());
    start.special.parameter = s.at("param").get<double>();
    start.special.point.parameter = start.special.parameter;
    start.special.monitor = s.value("monitor", 0.0);
    if (s.contains("multiplier")) {
      const std::vector<double> l = s.at("multiplier").get<std::vector<double>>();
      Require(l.size() == 2, "--start-json: a multiplier is [re, im]");
      start.special.multiplier = {l[0], l[1]};
    }
    const bool vanishing = s.contains("vanishing_impact") && !s.at("vanishing_impact").is_null();
    Require(!vanishing || orbit.p == 1,
            "--start-json: a vanishing impact's curve starts from the orbit with one impact "
            "fewer: use --type grazing with that orbit (--p, --q) instead");
    if (vanishing) {
      // P(1,q)'s impact vanishes where the non-impacting response touches
      // the stop: the curve needs no orbit, only where it starts.
      start.special.vanishing_impact = s.at("vanishing_impact").get<int>() - 1;
      start.special.point.orbit.p = orbit.p;
      start.special.point.orbit.q = orbit.q;
      return start;
    }
    // η is at the stop `stop` names (1-based; files before several stops
    // have none: stop 1).
    ImpactMapOptions section;
    section.stop = s.value("stop", 1) - 1;
    Require(section.stop >= 0 && section.stop < system->StopCount(),
            fmt::format("--start-json: point {}'s stop {} is not one of the system's {} stops",
                        request.point, section.stop + 1, system->StopCount()));
    start.special.point.orbit = DescribeOrbit(
        ImpactMap(*system, section),
        Eigen::Map<const Eigen::VectorXd>(eta.data(), static_cast<Eigen::Index>(eta.size())),
        orbit.p, orbit.q);
    return start;
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(
        fmt::format("--start-json {}: not the JSON of `impactkit continue` with "
                    "a special point {} ({})",
                    request.start_json, request.point, e.what()));
  }
}

/// What produced the outputs: the system and every setting resolved.
Provenance ProvenanceOf(const CurveRequest& request, const System& system,
                        const CurveOptions& options, const CurveStart& start) {
  // With --start-json the system is the one that file holds.
  SystemOptions source = request.system;
  if (!request.start_json.empty()) source.file = request.start_json;
  return MakeProvenance(
      source, system,
      fmt::format("curve --type {} --param {} --param2 {} --from {} --to {} --from2 {} --to2 {} "
                  "--p {} --q {}",
                  ToString(start.special.type), request.parameter, request.parameter2,
                  options.Lower(), options.Upper(), request.from2, request.to2,
                  start.special.point.orbit.p, start.special.point.orbit.q));
}

void RunCurve(const CurveRequest& request) {
  Require(!request.start_json.empty() || !request.type.empty(),
          "--type is required (fold, period_doubling, neimark_sacker or grazing), unless "
          "--start-json names the point");
  const bool own_system = !request.system.file.empty() || !request.system.sets.empty() ||
                          request.system.omega || request.system.dof;
  Require(request.start_json.empty() || !own_system,
          "--start-json takes the system from its file: drop --system, --set, --omega and --dof");
  System system = request.start_json.empty() ? ResolveSystem(request.system) : System{};
  if (!request.plot.empty()) RequireGnuplot();
  // Created first: a bad path fails before the work.
  OutputSet outputs;
  AtomicOutputFile* out = AddIfAsked(outputs, request.out);
  AtomicOutputFile* json = AddIfAsked(outputs, request.json);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);
  CurveOptions options;
  CurveStart start;
  if (request.start_json.empty()) {
    options = MakeOptions(request, system);
    start = FindStart(request, system, &options);
  } else {
    start = StartFromJson(request, &system, &options);
  }
  fmt::print("system:     {}\n", DescribeSystem(system));
  fmt::print("start:      {}\n", start.special.Describe(request.parameter));
  if (start.special.normal_form) {
    const GrazingPrediction prediction = PredictGrazing(start.system, *start.special.normal_form);
    fmt::print("            {}\n            {}\n", start.special.normal_form->Describe(),
               prediction.Describe());
  }
  impactkit::Curve curve;
  {
    const RunProgress progress(request.parameter, request.parameter2);
    curve = ContinueCurve(start, options, progress.Control());
  }
  PredictGrazings(start.system, &curve);
  PrintCurve(curve);
  if (curve.points.size() < 2) {
    throw std::runtime_error(
        fmt::format("the curve could not be continued beyond its start: {}", curve.end_message));
  }
  const Provenance provenance = ProvenanceOf(request, system, options, start);
  const std::vector<impactkit::Curve> curves = {curve};
  if (out) WriteCurveRows(outputs.AddCsv(*out, provenance.Text(), CurveColumns(curve)), curve);
  if (json) {
    nlohmann::json document = nlohmann::json::parse(CurvesJson(curves, SystemToJson(system)));
    document["provenance"] = provenance.Json();
    json->Write(document.dump(2) + "\n");
  }
  if (plot) WriteChart(*plot, CurveChart(curves));
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.json, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:      {}\n", *path);
  }
}

}  // namespace

void AddCurveCommand(CLI::App& app) {
  auto request = std::make_shared<CurveRequest>();
  CLI::App* command = app.add_subcommand(
      "curve",
      "Follow a fold, period-doubling, Neimark-Sacker or grazing point of a periodic orbit "
      "P(p,q) in two parameters, locating the codimension-two points on the curve (fold-flip, "
      "cusp, strong resonances, a bifurcation meeting a grazing, sticking onset). The point is "
      "found on the branch in --param through the orbit at the system's values, as `impactkit "
      "continue` finds it, or read from `impactkit continue --json`.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Curve";
  command->add_option("--type", request->type, "fold, period_doubling, neimark_sacker or grazing")
      ->group(group);
  command->add_option("--param", request->parameter, "First parameter (the branch's)")
      ->capture_default_str()
      ->group(group);
  command->add_option("--param2", request->parameter2, "Second parameter")
      ->required()
      ->group(group);
  command
      ->add_option("--from", request->from,
                   "Bound of --param (default: a factor 4 either side of its start value)")
      ->group(group);
  command->add_option("--to", request->to, "The other bound of --param")->group(group);
  command->add_option("--from2", request->from2, "Bound of --param2")->required()->group(group);
  command->add_option("--to2", request->to2, "The other bound of --param2")
      ->required()
      ->group(group);
  command
      ->add_option("--start-json", request->start_json,
                   "Start from a special point of `impactkit continue --json FILE` (its system)")
      ->type_name("FILE.json")
      ->group(group);
  command->add_option("--point", request->point, "Which special point of --start-json (1 = first)")
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str()
      ->group(group);
  command->add_option("--step", request->step, "Initial arclength step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--min-step", request->min_step, "Smallest step before giving up")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-step", request->max_step, "Largest step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-points", request->max_points, "Points per direction at most")
      ->check(AtMost(kMaxBranchPoints, "points"))
      ->capture_default_str()
      ->group(group);
  AddOrbitSeedOptions(*command, request->seed, "Start orbit");
  command
      ->add_option("--out", request->out,
                   "CSV, one row per point: param, param2, arclength, mod1.. (multiplier "
                   "moduli), outside (multipliers outside the unit circle), codim2 (its type, "
                   "at a codimension-two point)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_option("--json", request->json,
                   "JSON: curves [{type, p, q, params, points, end_reason}] and codim2_points "
                   "(docs/curves-json.md)")
      ->type_name("FILE.json")
      ->check(OutputPath())
      ->group("Output");
  command
      ->add_option("--plot", request->plot,
                   "Figure: the curve in the parameter plane, codimension-two points marked (needs "
                   "gnuplot)")
      ->type_name("FILE.{png,pdf,svg}")
      ->check(OutputPath())
      ->check(FigurePath())
      ->group("Output");
  command->callback([request] { RunCurve(*request); });
}

}  // namespace impactkit::cli
