#include "simulate/summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "impactkit/io/system_file.hpp"

namespace impactkit::cli {
namespace {

using Json = nlohmann::ordered_json;

/// "no impacts", "1 impact", "3 impacts".
std::string Count(long n, const std::string& noun) {
  if (n == 0) return "no " + noun + "s";
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

/// The fewest recorded periods that let DetectPeriod search up to its max_q.
long PeriodsForFullSearch() { return 2L * PeriodOptions{}.max_q; }

std::string ImpactLine(const SimulateResult& result) {
  const ImpactLog& impacts = result.recorders.steady.Impacts();
  if (impacts.empty()) return "none";
  double slowest = INFINITY, fastest = 0.0;
  for (const ImpactView impact : impacts) {
    slowest = std::min(slowest, impact.velocity);
    fastest = std::max(fastest, impact.velocity);
  }
  return fmt::format("{} ({:.6g} per forcing period), speed {:.6g} to {:.6g}", impacts.size(),
                     result.analysis.impacts_per_period, slowest, fastest);
}

std::string WrittenFiles(const SimulateRequest& request) {
  std::vector<std::string> files;
  for (const auto* path : {&request.series, &request.impacts, &request.plot, &request.json}) {
    if (!path->empty()) files.push_back(path->string());
  }
  return files.empty() ? "nothing (ask with --series, --impacts, --plot, --json)"
                       : fmt::format("{}", fmt::join(files, ", "));
}

std::vector<double> ToVector(const Eigen::VectorXd& v) { return {v.begin(), v.end()}; }

Json StateJson(const HybridState& state) {
  return {
      {"t", state.t}, {"x", ToVector(state.x)}, {"v", ToVector(state.v)}, {"stuck", state.Stuck()}};
}

Json RunJson(const SimulateResult& result) {
  const SimulateRequest& request = result.request;
  Json run = {{"transient_periods", request.transient},
              {"periods", request.periods},
              {"samples_per_period", request.samples_per_period},
              {"chatter", ToString(request.chatter)}};
  if (request.chatter == ChatterMethod::kThreshold) {
    run["chatter_threshold"] = SimulationOptionsOf(request).chatter_threshold;
  }
  run["initial_state"] = StateJson(result.initial_state);
  return run;
}

Json MotionJson(const WindowAnalysis& analysis) {
  const MotionPeriod& motion = analysis.motion;
  Json json = {{"label", MotionLabel(analysis)},
               {"description", DescribeMotion(analysis)},
               {"periodic", motion.periodic},
               {"searched_q", analysis.searched_q}};
  if (motion.periodic) {
    // The schema of every output and of Python (the library's GridCell):
    // p = 0 when the motion sticks (its impacts before accumulation are no
    // period; `sticking` and the label say P(inf,q)).
    json["p"] = motion.sticking ? 0 : motion.p;
    json["q"] = motion.q;
    json["sticking"] = motion.sticking;
    json["mismatch"] = motion.mismatch;
  }
  return json;
}

}  // namespace

std::string MotionLabel(const WindowAnalysis& analysis) {
  return analysis.motion.periodic ? analysis.motion.ToString()
                                  : fmt::format("no period up to q = {}", analysis.searched_q);
}

std::string DescribeMotion(const WindowAnalysis& analysis) {
  const MotionPeriod& motion = analysis.motion;
  if (motion.periodic && motion.sticking) {
    return fmt::format("{} sticking (chatter ends at the stop; repeats every {})",
                       motion.ToString(), Count(motion.q, "forcing period"));
  }
  if (motion.periodic) {
    return fmt::format("{} ({} in {})", motion.ToString(), Count(motion.p, "impact"),
                       Count(motion.q, "forcing period"));
  }
  if (analysis.searched_q == 0) return "undetermined (record at least 2 forcing periods)";
  // Either the transient has not died out yet or the period is long (or
  // there is none: chaos); say how to tell.
  std::string hint = "a longer --transient lets transients decay";
  if (analysis.searched_q < PeriodOptions{}.max_q) {
    hint += fmt::format("; --periods {} looks up to q = {}", PeriodsForFullSearch(),
                        PeriodOptions{}.max_q);
  }
  return fmt::format("{} in the recorded window ({})", MotionLabel(analysis), hint);
}

std::string SummaryText(const SimulateResult& result) {
  const Window& window = result.window;
  const WindowAnalysis& analysis = result.analysis;
  std::string text;
  auto line = [&](const char* key, const std::string& value) {
    text += fmt::format("{:<10}{}\n", key, value);
  };
  line("system:", DescribeSystem(result.system));
  line("window:", fmt::format("t = {:.6g} to {:.6g} (forcing periods {} to {}, T = {:.6g})",
                              window.begin, window.end, window.first_period,
                              window.first_period + window.periods, window.period));
  line("impacts:", ImpactLine(result));
  // A cut chatter sequence did not end at its accumulation point: say so
  // where there were any (docs/theory.md §4).
  const std::string cuts =
      analysis.chatter_cuts > 0
          ? fmt::format(" ({} cut at a short bounce without accumulating: elastic chatter)",
                        analysis.chatter_cuts)
          : "";
  line("sticking:", fmt::format("{:.3g}% of the window, {} chatter sequence{}{}",
                                100.0 * analysis.sticking_fraction, analysis.chatter_sequences,
                                analysis.chatter_sequences == 1 ? "" : "s", cuts));
  line("motion:", DescribeMotion(analysis));
  line("run time:", fmt::format("{:.3g} s", result.seconds));
  line("wrote:", WrittenFiles(result.request));
  return text;
}

std::string SummaryJson(const SimulateResult& result, const Provenance& provenance) {
  const ImpactLog& impacts = result.recorders.steady.Impacts();
  const Window& window = result.window;
  Json json = {{"provenance", provenance.Json()}};
  json["system"] = Json::parse(SystemToJson(result.system));
  json["run"] = RunJson(result);
  json["window"] = {{"t_begin", window.begin},
                    {"t_end", window.end},
                    {"forcing_period", window.period},
                    {"first_period", window.first_period},
                    {"periods", window.periods}};
  json["impacts"] = {{"count", impacts.size()},
                     {"per_forcing_period", result.analysis.impacts_per_period}};
  json["sticking_fraction"] = result.analysis.sticking_fraction;
  json["chatter_sequences"] = result.analysis.chatter_sequences;
  json["chatter_cuts"] = result.analysis.chatter_cuts;
  json["motion"] = MotionJson(result.analysis);
  json["final_state"] = StateJson(result.final_state);
  json["seconds"] = result.seconds;
  return json.dump(2);
}

}  // namespace impactkit::cli
