/// `impactkit sweep`: a brute-force bifurcation diagram over any named
/// parameter (impactkit/sweep.hpp does the work), written as CSV and PNG.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "common/limits.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/system_options.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/io/output_set.hpp"
#include "sweep/chart.hpp"

namespace impactkit::cli {
namespace {

struct SweepRequest {
  SystemOptions system;
  std::string param = "omega";
  double from = 0.0;
  double to = 0.0;
  int steps = 0;
  int transient = 500;
  int record = 100;
  std::string start = "previous";
  std::string direction = "up";
  std::vector<double> x0, v0;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  int chunk = SweepOptions{}.chunk_values;
  int warmup = SweepOptions{}.warmup_values;
  int max_q = PeriodOptions{}.max_q;
  std::string out, summary, plot;
};

/// Values done of K on stderr, rewritten in place; like ProgressLine
/// (common/progress.hpp), only on a terminal and only after the first second.
class SweepProgressLine {
 public:
  explicit SweepProgressLine(std::string parameter)
      : enabled_(::isatty(STDERR_FILENO) == 1), parameter_(std::move(parameter)) {}
  ~SweepProgressLine() {
    if (drawn_) fmt::print(stderr, "\r\033[K");
  }
  SweepProgressLine(const SweepProgressLine&) = delete;
  SweepProgressLine& operator=(const SweepProgressLine&) = delete;

  void Update(int done, int total) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    if (now - start_ < std::chrono::seconds(1) ||
        (now - last_drawn_ < std::chrono::milliseconds(200) && done < total)) {
      return;
    }
    fmt::print(stderr, "\r\033[Kimpactkit: sweep of {} {:3.0f}% ({} of {} values)", parameter_,
               100.0 * done / total, done, total);
    last_drawn_ = now;
    drawn_ = true;
  }

 private:
  using Clock = std::chrono::steady_clock;
  const bool enabled_;
  const std::string parameter_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_drawn_{};
  bool drawn_ = false;
};

/// The flags as library options; flag names in the messages.
SweepOptions OptionsOf(const SweepRequest& request, const System& system) {
  if (request.steps < 1)
    throw InvalidInput(fmt::format("--steps must be >= 1, got {}", request.steps));
  if (request.steps > 1 && request.from == request.to) {
    throw InvalidInput(
        fmt::format("--from and --to are both {}: {} steps need a range (or --steps 1)",
                    request.from, request.steps));
  }
  if (request.transient < 0) {
    throw InvalidInput(fmt::format("--transient must be >= 0, got {}", request.transient));
  }
  if (request.record < 1)
    throw InvalidInput(fmt::format("--record must be >= 1, got {}", request.record));
  if (request.threads < 1) {
    throw InvalidInput(fmt::format("--threads must be >= 1, got {}", request.threads));
  }
  if (request.chunk < 0)
    throw InvalidInput(fmt::format("--chunk must be >= 0, got {}", request.chunk));
  if (request.warmup < 0) {
    throw InvalidInput(fmt::format("--warmup must be >= 0, got {}", request.warmup));
  }
  if (request.max_q < 1)
    throw InvalidInput(fmt::format("--max-q must be >= 1, got {}", request.max_q));
  GetParameter(system, request.param);  // "unknown parameter 'x'; allowed: ..."
  RequireNotSet(request.system, request.param, "--param", "--from and --to");
  SweepOptions options;
  options.parameter = request.param;
  options.from = request.from;
  options.to = request.to;
  options.steps = request.steps;
  options.transient_periods = request.transient;
  options.recorded_periods = request.record;
  options.start = request.start == "fixed" ? SweepStart::kFixed : SweepStart::kPrevious;
  options.direction = request.direction == "down" ? SweepDirection::kDown : SweepDirection::kUp;
  options.threads = request.threads;
  options.chunk_values = request.chunk;
  options.warmup_values = request.warmup;
  options.classify.period.max_q = request.max_q;
  if (!request.x0.empty() || !request.v0.empty()) {
    HybridState state = RestState(system);
    auto fill = [&](const std::vector<double>& given, Eigen::VectorXd& target, const char* flag) {
      if (given.empty()) return;
      if (static_cast<int>(given.size()) != system.Dof()) {
        throw InvalidInput(fmt::format("{} needs {} values (one per mass), got {}", flag,
                                       system.Dof(), given.size()));
      }
      target = Eigen::Map<const Eigen::VectorXd>(given.data(), system.Dof());
    };
    fill(request.x0, state.x, "--x0");
    fill(request.v0, state.v, "--v0");
    options.fixed_state = state;
  }
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  return options;
}

/// The first line of every output: all that decides the result (the thread
/// count does not).
std::string Provenance(const SweepRequest& request, const System& system,
                       const SweepOptions& options) {
  std::string text = "sweep";
  if (!request.system.file.empty()) text += " system=" + request.system.file;
  text += fmt::format(
      " {} param={} from={} to={} steps={} transient={} record={} start={} direction={} "
      "max_q={}",
      ParameterList(system), options.parameter, options.from, options.to, options.steps,
      options.transient_periods, options.recorded_periods, ToString(options.start),
      ToString(options.direction), options.classify.period.max_q);
  if (!request.x0.empty()) text += fmt::format(" x0={}", fmt::join(request.x0, ","));
  if (!request.v0.empty()) text += fmt::format(" v0={}", fmt::join(request.v0, ","));
  if (options.start == SweepStart::kPrevious) {
    text += fmt::format(
        " chunk={} warmup={} (each value from the previous one's final state; every chunk of "
        "{} values from the fixed state through the transients of the {} values before it)",
        options.chunk_values, options.warmup_values, options.chunk_values, options.warmup_values);
  } else {
    text += " (each value from the fixed state)";
  }
  return text;
}

/// A number as the CSV files write it: shortest round-trip form; an
/// undefined value (NaN here) is an empty field — gnuplot and pandas read it
/// as missing, and no NaN reaches a file.
std::string Number(double value) { return std::isnan(value) ? "" : fmt::format("{}", value); }

std::string SummaryRow(const SweepPoint& point) {
  const Classification& c = point.classification;
  const MotionPeriod& m = c.period;
  std::string p, q;  // empty: no period
  if (m.periodic && c.kind != MotionKind::kUnresolved && c.kind != MotionKind::kChaotic) {
    p = c.kind == MotionKind::kSticking ? "inf" : std::to_string(m.p);
    q = std::to_string(m.q);
  }
  auto extreme = [](const std::vector<double>& values, bool largest) {
    if (values.empty()) return std::nan("");
    return largest ? *std::max_element(values.begin(), values.end())
                   : *std::min_element(values.begin(), values.end());
  };
  double v_min = std::nan(""), v_max = std::nan("");
  for (const SweepImpact& i : point.impacts) {
    v_min = std::isnan(v_min) ? i.velocity : std::min(v_min, i.velocity);
    v_max = std::isnan(v_max) ? i.velocity : std::max(v_max, i.velocity);
  }
  const double lyapunov =
      c.lyapunov_computed && c.lyapunov.valid ? c.lyapunov.largest : std::nan("");
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", Number(point.value),
                     ToString(c.kind), p, q, Number(extreme(point.range_contact, true)),
                     Number(extreme(point.range_first, true)),
                     Number(extreme(point.range_contact, false)),
                     Number(extreme(point.range_first, false)), point.impacts.size(), Number(v_min),
                     Number(v_max), Number(lyapunov), point.restarted ? 1 : 0);
}

void RunSweepCommand(const SweepRequest& request) {
  const System system = ResolveSystem(request.system);
  const SweepOptions options = OptionsOf(request, system);
  const std::string provenance = Provenance(request, system, options);
  // Outputs are opened before the work, so that a bad path or a missing
  // gnuplot fails at once, not after a long sweep.
  if (!request.plot.empty()) RequireGnuplot();
  OutputSet outputs;
  CsvWriter* out = nullptr;
  if (!request.out.empty()) {
    out = &outputs.AddCsv(request.out, provenance,
                          std::vector<std::string>{"param", "t", "phase", "v"});
  }
  AtomicOutputFile* summary = AddIfAsked(outputs, request.summary);
  AtomicOutputFile* plot = AddIfAsked(outputs, request.plot);

  SweepResult result;
  {
    SweepProgressLine progress(options.parameter);
    result = RunSweep(system, options,
                      [&progress](int done, int total) { progress.Update(done, total); });
  }

  fmt::print("system:  {}\n", DescribeSystem(system));
  fmt::print(
      "sweep:   {} from {} to {} in {} values, {}, {} transient + {} recorded periods, "
      "start {}, {} threads\n",
      options.parameter, options.from, options.to, options.steps, ToString(options.direction),
      options.transient_periods, options.recorded_periods, ToString(options.start),
      options.threads);
  fmt::print("result:  {}\n", result.BriefReport());
  if (out) {
    for (const SweepPoint& point : result.points) {
      for (const SweepImpact& i : point.impacts) {
        const double row[] = {point.value, i.t, i.phase, i.velocity};
        out->WriteRow(row);
      }
    }
  }
  if (summary) {
    summary->Write(fmt::format("# impactkit {}\n", provenance));
    summary->Write(
        "param,kind,p,q,range_xN,range_x1,range_xN_min,range_x1_min,impacts,v_min,v_max,"
        "lyapunov,restarted\n");
    for (const SweepPoint& point : result.points) summary->Write(SummaryRow(point));
  }
  if (plot) plot->Write(RenderStackedPng(SweepCharts(system, options, result), 1000, 900));
  // Committed last: a failure above leaves no partial set of files.
  outputs.Commit();
  for (const std::string* path : {&request.out, &request.summary, &request.plot}) {
    if (!path->empty()) fmt::print("wrote:   {}\n", *path);
  }
}

}  // namespace

void AddSweepCommand(CLI::App& app) {
  auto request = std::make_shared<SweepRequest>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Brute-force bifurcation diagram: step one named parameter through evenly spaced values, "
      "simulate each to steady state (from the previous value's final state by default), record "
      "every impact and the per-period max - min of the contact mass and of x1, and classify the "
      "motion (periodic P(p,q), sticking P(inf,q), chaotic, non_impacting, or unresolved). "
      "Results are identical for any --threads.");
  AddSystemOptions(*command, request->system);
  const std::string group = "Sweep";
  command
      ->add_option("--param", request->param, "Parameter to sweep: omega, xs, r, A1..AN, m, k, c")
      ->type_name("NAME")
      ->capture_default_str()
      ->group(group);
  command->add_option("--from", request->from, "One end of the range")
      ->type_name("A")
      ->required()
      ->group(group);
  command->add_option("--to", request->to, "The other end of the range")
      ->type_name("B")
      ->required()
      ->group(group);
  command->add_option("--steps", request->steps, "Number of values K, both ends included")
      ->type_name("K")
      ->check(AtMost(kMaxSteps, "values"))
      ->required()
      ->group(group);
  command->add_option("--transient", request->transient, "Forcing periods discarded at each value")
      ->type_name("P")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--record", request->record, "Forcing periods recorded at each value")
      ->type_name("P")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command
      ->add_option("--start", request->start,
                   "'previous': each value from the previous value's final state; 'fixed': each "
                   "from the fixed state (--x0/--v0, default rest)")
      ->check(CLI::IsMember({"previous", "fixed"}))
      ->capture_default_str()
      ->group(group);
  command->add_option("--direction", request->direction, "'up' or 'down' through the range")
      ->check(CLI::IsMember({"up", "down"}))
      ->capture_default_str()
      ->group(group);
  command->add_option("--x0", request->x0, "Fixed state positions x1,...,xN (default 0)")
      ->type_name("X1,...,XN")
      ->delimiter(',')
      ->group(group);
  command->add_option("--v0", request->v0, "Fixed state velocities v1,...,vN (default 0)")
      ->type_name("V1,...,VN")
      ->delimiter(',')
      ->group(group);
  command->add_option("--threads", request->threads, "Worker threads (default: all cores)")
      ->type_name("N")
      ->check(AtMost(kMaxThreads, "threads"))
      ->group(group);
  command
      ->add_option("--chunk", request->chunk,
                   "With --start previous: values per independently computed chunk (0: one "
                   "chunk, strictly sequential); part of the result, unlike --threads")
      ->type_name("N")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group(group);
  command
      ->add_option("--warmup", request->warmup,
                   "With --start previous: values before each chunk whose transients it runs "
                   "first, from the fixed state")
      ->type_name("N")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group(group);
  command->add_option("--max-q", request->max_q, "Longest period searched, in forcing periods")
      ->type_name("Q")
      ->check(AtMost(kMaxOrbitPeriod, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  const std::string output = "Output (each written only if asked for, and only whole)";
  command
      ->add_option("--out", request->out,
                   "Every recorded impact: columns param,t,phase,v (t from the start of "
                   "that value's run, phase = t mod T, v the impact speed)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--summary", request->summary,
                   "One row per value: param,kind,p,q,range_xN,range_x1,range_xN_min,"
                   "range_x1_min,impacts,v_min,v_max,lyapunov,restarted (range_*: largest and "
                   "smallest per-period max - min; p = inf when sticking; empty where undefined)")
      ->type_name("FILE.csv")
      ->check(OutputPath())
      ->group(output);
  command
      ->add_option("--plot", request->plot,
                   "PNG of the paper's Fig. 3: max - min of the contact mass per period, and "
                   "impact velocity, against the parameter (needs gnuplot)")
      ->type_name("FILE.png")
      ->check(OutputPath())
      ->group(output);
  command->callback([request] { RunSweepCommand(*request); });
}

}  // namespace impactkit::cli
