/// `impactkit continue`: pseudo-arclength continuation of a P(p, q) branch in
/// one parameter, its special points, and optionally the branches that
/// start at them (impactkit/continuation.hpp does the work).

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "impactkit/continuation.hpp"
#include "impactkit/csv.hpp"
#include "impactkit/output_file.hpp"
#include "impactkit/system_file.hpp"
#include "orbit_seed.hpp"
#include "plot.hpp"
#include "system_options.hpp"

namespace impactkit::cli {
namespace {

struct ContinueRequest {
  SystemOptions system;
  OrbitSeedOptions seed;
  std::string parameter = "omega";
  std::optional<double> from, to, start;
  double step = 0.01, min_step = 1e-7, max_step = 0.02;
  int max_points = 10000;
  bool switch_period_doubling = false;
  bool follow_grazing = false;
  std::string out, json, plot;
};

/// A progress line on stderr while a person watches (silent otherwise).
class BranchProgress {
 public:
  explicit BranchProgress(std::string parameter)
      : enabled_(::isatty(STDERR_FILENO) == 1), parameter_(std::move(parameter)) {}
  ~BranchProgress() {
    if (drawn_) fmt::print(stderr, "\r\033[K");
  }
  BranchProgress(const BranchProgress&) = delete;
  BranchProgress& operator=(const BranchProgress&) = delete;

  void operator()(const std::string& label, const BranchPoint& point) {
    ++points_;
    const auto now = std::chrono::steady_clock::now();
    if (!enabled_ || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    fmt::print(stderr, "\r\033[Kcontinue {}: {} points, {} = {:.8g}", label, points_, parameter_,
               point.parameter);
  }

 private:
  const bool enabled_;
  const std::string parameter_;
  int points_ = 0;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

/// A traced branch and where it came from.
struct TracedBranch {
  std::string label;   ///< "main", "pd1", "graze1", ...
  std::string origin;  ///< how it was started
  Branch branch;
};

ContinuationOptions MakeOptions(const ContinueRequest& request, const OrbitOptions& orbit) {
  ContinuationOptions options;
  options.parameter = request.parameter;
  options.lower = std::min(*request.from, *request.to);
  options.upper = std::max(*request.from, *request.to);
  options.direction = request.start ? ContinuationDirection::kBoth
                      : *request.to > *request.from ? ContinuationDirection::kIncreasing
                                                    : ContinuationDirection::kDecreasing;
  options.initial_step = request.step;
  options.min_step = request.min_step;
  options.max_step = request.max_step;
  options.max_points = request.max_points;
  options.orbit = orbit;
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  return options;
}

/// The branches born at the main branch's special points, as asked.
std::vector<TracedBranch> SwitchBranches(const ContinueRequest& request, const System& system,
                                         const TracedBranch& main,
                                         const ContinuationOptions& options,
                                         BranchProgress& progress) {
  std::vector<TracedBranch> born;
  const std::string& name = options.parameter;
  for (const SpecialPoint& special : main.branch.special_points) {
    const bool pd = special.type == SpecialPointType::kPeriodDoubling;
    const bool graze =
        special.type == SpecialPointType::kGrazing || special.type == SpecialPointType::kSticking;
    if (pd && request.switch_period_doubling) {
      const std::optional<BranchStart> start =
          DoubledBranchStart(system, main.branch, special, options);
      if (!start) continue;
      ContinuationOptions doubled = options;
      doubled.orbit.p *= 2;
      doubled.orbit.q *= 2;
      doubled.direction = ContinuationDirection::kIncreasing;
      const std::string label = fmt::format("pd{}", born.size() + 1);
      born.push_back({label, "from the " + special.Describe(name),
                      ContinueBranch(*start, doubled, [&](const BranchPoint& p) { progress(label, p); })});
    }
    if (graze && request.follow_grazing) {
      for (const GrazingSeed& seed : SeedsAtGrazing(system, main.branch, special, options)) {
        PeriodicOrbit orbit;
        if (FindOrbit(seed.system, seed.eta, seed.orbit, &orbit).termination !=
            OrbitTermination::kConverged) {
          continue;
        }
        ContinuationOptions next = options;
        next.orbit = seed.orbit;
        next.direction = ContinuationDirection::kBoth;
        const std::string label = fmt::format("graze{}", born.size() + 1);
        born.push_back({label, "seeded at the " + special.Describe(name),
                        ContinueBranch({seed.system, orbit, {}}, next,
                                       [&](const BranchPoint& p) { progress(label, p); })});
        break;  // the seeds on both sides lead to one branch, followed both ways
      }
    }
  }
  return born;
}

std::vector<std::string> Columns(const Branch& branch) {
  std::vector<std::string> columns = {branch.parameter, "arclength"};
  for (int i = 1; i <= branch.p; ++i) columns.push_back(fmt::format("phase{}", i));
  for (int i = 1; i <= branch.p; ++i) columns.push_back(fmt::format("v{}", i));
  columns.push_back("range_xN");
  const Eigen::Index multipliers = branch.points.front().orbit.multipliers.size();
  for (Eigen::Index i = 1; i <= multipliers; ++i) columns.push_back(fmt::format("mod{}", i));
  for (const char* name : {"stable", "clearance", "depth", "special"}) columns.push_back(name);
  return columns;
}

/// Special-point codes of the CSV's `special` column (0: an ordinary point).
double SpecialCode(const Branch& branch, const BranchPoint& point) {
  for (const SpecialPoint& s : branch.special_points) {
    if (s.point.arclength == point.arclength) return 1.0 + static_cast<int>(s.type);
  }
  return 0.0;
}

void WriteCsv(const std::string& path, const std::string& provenance, const Branch& branch) {
  CsvWriter csv(path, provenance, Columns(branch));
  for (const BranchPoint& point : branch.points) {
    const PeriodicOrbit& orbit = point.orbit;
    std::vector<double> row = {point.parameter, point.arclength};
    for (const OrbitImpact& i : orbit.impacts) row.push_back(i.phase);
    for (const OrbitImpact& i : orbit.impacts) row.push_back(i.velocity);
    row.push_back(orbit.contacts.Range());
    for (const std::complex<double>& m : orbit.multipliers) row.push_back(std::abs(m));
    row.push_back(orbit.stable ? 1.0 : 0.0);
    // No interior maximum: the clearance is the whole way down to the
    // lowest point, reported as the range (never NaN in a table).
    row.push_back(orbit.contacts.clearance.value_or(orbit.contacts.Range()));
    row.push_back(std::min(orbit.contacts.slowest_depth, 1e300));
    row.push_back(SpecialCode(branch, point));
    csv.WriteRow(row);
  }
  csv.Commit();
}

/// FILE.csv for the main branch, FILE.<label>.csv for the others.
std::string BranchPath(const std::string& path, const std::string& label) {
  if (label == "main") return path;
  const std::size_t dot = path.rfind('.');
  const bool has_extension = dot != std::string::npos && path.find('/', dot) == std::string::npos;
  return has_extension ? path.substr(0, dot) + "." + label + path.substr(dot)
                       : path + "." + label;
}

nlohmann::json SpecialJson(const SpecialPoint& s, const std::string& parameter) {
  nlohmann::json j = {{"type", ToString(s.type)},
                      {"param", s.point.parameter},
                      {"parameter", parameter},
                      {"description", s.Describe(parameter)},
                      {"monitor", s.monitor},
                      {"eta", std::vector<double>(s.point.orbit.eta.data(),
                                                  s.point.orbit.eta.data() + s.point.orbit.eta.size())}};
  if (s.type == SpecialPointType::kGrazing || s.type == SpecialPointType::kSticking) {
    j["vanishing_impact"] = s.vanishing_impact < 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(s.vanishing_impact + 1);
  } else {
    j["multiplier"] = {s.multiplier.real(), s.multiplier.imag()};
  }
  j["impacts"] = nlohmann::json::array();
  for (const OrbitImpact& i : s.point.orbit.impacts) {
    j["impacts"].push_back({{"phase", i.phase}, {"v", i.velocity}});
  }
  return j;
}

nlohmann::json BranchJson(const TracedBranch& traced) {
  const Branch& b = traced.branch;
  nlohmann::json j = {{"label", traced.label},       {"origin", traced.origin},
                      {"p", b.p},                    {"q", b.q},
                      {"points", b.points.size()},   {"end_reason", ToString(b.end)},
                      {"end_message", b.end_message}, {"seconds", b.seconds}};
  if (b.begin) {
    j["begin_reason"] = ToString(*b.begin);
    j["begin_message"] = b.begin_message;
  }
  j["param_range"] = {b.points.front().parameter, b.points.back().parameter};
  j["special_points"] = nlohmann::json::array();
  for (const SpecialPoint& s : b.special_points) j["special_points"].push_back(SpecialJson(s, b.parameter));
  return j;
}

std::string ContinueJson(const System& system, const std::vector<TracedBranch>& branches,
                         const std::string& provenance) {
  nlohmann::json j = BranchJson(branches.front());
  j["command"] = provenance;
  j["branches"] = nlohmann::json::array();
  for (const TracedBranch& b : branches) j["branches"].push_back(BranchJson(b));
  j["system"] = nlohmann::json::parse(SystemToJson(system));
  return j.dump(2) + "\n";
}

/// The branch as impact velocity against the parameter: stable stretches
/// solid, unstable dashed, special points marked.
LineChart BranchChart(const std::vector<TracedBranch>& branches) {
  static const char* kPalette[] = {"#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf"};
  LineChart chart;
  chart.title = "Continued branches: impact velocities";
  chart.x_label = branches.front().branch.parameter;
  chart.y_label = "impact velocity";
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const Branch& b = branches[k].branch;
    const std::string color = kPalette[k % 5];
    for (int i = 0; i < b.p; ++i) {
      // One curve per stretch of equal stability, so that the pieces join.
      std::size_t from = 0;
      while (from + 1 < b.points.size()) {
        std::size_t to = from + 1;
        while (to + 1 < b.points.size() && b.points[to].orbit.stable == b.points[from].orbit.stable) ++to;
        Curve curve;
        curve.color = color;
        curve.dashed = !b.points[from].orbit.stable;
        for (std::size_t n = from; n <= to; ++n) {
          curve.x.push_back(b.points[n].parameter);
          curve.y.push_back(b.points[n].orbit.impacts[i].velocity);
        }
        if (from == 0 && i == 0) curve.title = fmt::format("P({},{}) {}", b.p, b.q, branches[k].label);
        chart.curves.push_back(std::move(curve));
        from = to;
      }
    }
    for (const SpecialPoint& s : b.special_points) {
      Curve mark;
      mark.points = true;
      mark.color = "#d62728";
      for (const OrbitImpact& i : s.point.orbit.impacts) {
        mark.x.push_back(s.point.parameter);
        mark.y.push_back(i.velocity);
      }
      chart.curves.push_back(std::move(mark));
    }
  }
  return chart;
}

void PrintBranch(const TracedBranch& traced) {
  const Branch& b = traced.branch;
  fmt::print("branch {}:  P({},{}) {}, {} points, {} from {:.10g} to {:.10g} ({:.3g} s)\n",
             traced.label, b.p, b.q, traced.origin, b.points.size(), b.parameter,
             b.points.front().parameter, b.points.back().parameter, b.seconds);
  if (b.begin) fmt::print("  begins: {} ({})\n", ToString(*b.begin), b.begin_message);
  for (const SpecialPoint& s : b.special_points) fmt::print("  {}\n", s.Describe(b.parameter));
  fmt::print("  ends:   {} ({})\n", ToString(b.end), b.end_message);
}

System StartSystem(const ContinueRequest& request) {
  if (*request.from == *request.to) {
    throw InvalidInput(fmt::format("--from and --to must differ (both {})", *request.from));
  }
  System system = ResolveSystem(request.system);
  GetParameter(system, request.parameter);  // an unknown name fails here, naming the choices
  MakeOptions(request, OrbitOptions{});     // and bad bounds or steps before any work
  const double lower = std::min(*request.from, *request.to);
  const double upper = std::max(*request.from, *request.to);
  if (request.start && !(*request.start >= lower && *request.start <= upper)) {
    throw InvalidInput(fmt::format("--start {} is not between --from and --to", *request.start));
  }
  SetParameter(system, request.parameter, request.start.value_or(*request.from));
  Validate(system);
  return system;
}

std::string Provenance(const ContinueRequest& request, const System& system) {
  return fmt::format("continue --param {} --from {} --to {}{} {}", request.parameter,
                     *request.from, *request.to,
                     request.start ? fmt::format(" --start {}", *request.start) : "",
                     ParameterList(system));
}

void RunContinue(const ContinueRequest& request) {
  const System system = StartSystem(request);
  std::optional<AtomicOutputFile> json;  // created first: a bad path fails before the work
  if (!request.json.empty()) json.emplace(request.json);
  if (!request.plot.empty()) RequireGnuplot();
  OrbitOptions orbit_options;
  const PeriodicOrbit start = FindStartOrbit(system, request.seed, &orbit_options);
  const ContinuationOptions options = MakeOptions(request, orbit_options);
  fmt::print("system:     {}\n", DescribeSystem(system));
  fmt::print("start:      P({},{}) at {} = {}, {}\n", start.p, start.q, request.parameter,
             GetParameter(system, request.parameter), start.stable ? "stable" : "unstable");
  std::vector<TracedBranch> branches;
  {
    BranchProgress progress(request.parameter);
    branches.push_back({"main", "from the start", ContinueBranch({system, start, {}}, options,
                                                                 [&](const BranchPoint& p) {
                                                                   progress("main", p);
                                                                 })});
    std::vector<TracedBranch> born = SwitchBranches(request, system, branches.front(), options, progress);
    branches.insert(branches.end(), born.begin(), born.end());
  }
  for (const TracedBranch& b : branches) PrintBranch(b);
  const std::string provenance = Provenance(request, system);
  if (!request.out.empty()) {
    for (const TracedBranch& b : branches) {
      WriteCsv(BranchPath(request.out, b.label), provenance, b.branch);
      fmt::print("wrote:      {}\n", BranchPath(request.out, b.label));
    }
  }
  if (json) {
    json->Write(ContinueJson(system, branches, "impactkit " + provenance));
    json->Commit();
    fmt::print("wrote:      {}\n", request.json);
  }
  if (!request.plot.empty()) {
    AtomicOutputFile png(request.plot);
    png.Write(RenderPng(BranchChart(branches)));
    png.Commit();
    fmt::print("wrote:      {}\n", request.plot);
  }
}

}  // namespace

void AddContinueCommand(CLI::App& app) {
  auto request = std::make_shared<ContinueRequest>();
  CLI::App* command = app.add_subcommand(
      "continue",
      "Follow a periodic orbit P(p,q) as a parameter moves (pseudo-arclength continuation, "
      "through folds), locating folds, period doublings, Neimark-Sacker points, and the "
      "grazing or sticking point where the branch ends. The start orbit is found at --from "
      "(or --start, then followed both ways) as `impactkit orbit` finds it.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Continuation";
  command->add_option("--param", request->parameter, "Parameter to vary: omega, xs, r, A1.., m, k, c")
      ->capture_default_str()
      ->group(group);
  command->add_option("--from", request->from, "Start value (and one bound) of the parameter")
      ->required()
      ->group(group);
  command->add_option("--to", request->to, "The other bound: the branch first heads there")
      ->required()
      ->group(group);
  command->add_option("--start", request->start,
                      "Start value between --from and --to; the branch is then followed both ways")
      ->group(group);
  command->add_option("--step", request->step, "Initial arclength step in (eta, parameter)")
      ->capture_default_str()
      ->group(group);
  command->add_option("--min-step", request->min_step, "Smallest step before giving up")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-step", request->max_step, "Largest step")
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-points", request->max_points, "Points per direction at most")
      ->capture_default_str()
      ->group(group);
  command->add_flag("--switch-pd", request->switch_period_doubling,
                    "At each period doubling, also follow the period-doubled branch P(2p,2q)")
      ->group(group);
  command->add_flag("--follow-grazing", request->follow_grazing,
                    "At a grazing end, also follow the orbit with one impact more or fewer, "
                    "where one is found")
      ->group(group);
  AddOrbitSeedOptions(*command, request->seed, "Start orbit");
  command->add_option("--out", request->out,
                      "CSV, one row per point: parameter, arclength, phase1.., v1.., range_xN, "
                      "mod1.. (multiplier moduli), stable, clearance, depth, special (0 none, "
                      "1 fold, 2 period doubling, 3 Neimark-Sacker, 4 grazing, 5 sticking); "
                      "other branches go to FILE.<label>.csv")
      ->type_name("FILE.csv")
      ->group("Output");
  command->add_option("--json", request->json,
                      "JSON: special_points [{type, param, ...}], end_reason, and every branch")
      ->type_name("FILE.json")
      ->group("Output");
  command->add_option("--plot", request->plot,
                      "PNG: impact velocities against the parameter, stable solid, unstable "
                      "dashed, special points marked (needs gnuplot)")
      ->type_name("FILE.png")
      ->group("Output");
  command->callback([request] { RunContinue(*request); });
}

}  // namespace impactkit::cli
