/// `impactkit paper`: the paper's whole study on its system in one run —
/// modal data, resonance peaks, the orbits at its sample frequencies, the
/// continued branches with every located special point, and the brute-force
/// diagram's regimes — printed, and written (CSV, JSON, PNG) into one folder.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "common/branches.hpp"
#include "common/grid_flags.hpp"
#include "common/limits.hpp"
#include "common/orbit_seed.hpp"
#include "common/output.hpp"
#include "common/plot.hpp"
#include "common/progress.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "diagram/output.hpp"
#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/resonance.hpp"
#include "impactkit/analysis/swept_diagram.hpp"
#include "impactkit/io/grid_output.hpp"
#include "impactkit/io/output_set.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/modal.hpp"
#include "sweep/chart.hpp"

namespace impactkit::cli {
namespace {

struct PaperRequest {
  std::string out = "out/paper";
  bool quick = false;
  bool all_branches = false;  ///< a table for every branch, not only the seeds'
  int threads = 0;            ///< 0: all cores
};

/// Resolution of the run: the paper's, or a quick one for tests.
struct Resolution {
  int transient;     ///< forcing periods before an orbit is seeded
  int sweep_values;  ///< Fig. 3 sweep
  int sweep_transient;
  int sweep_record;
  int max_q;      ///< longest period the sweep's classification looks for
  int max_depth;  ///< switches from a seed's branch in the connected diagram
};

Resolution ResolutionFor(bool quick) {
  return quick ? Resolution{200, 121, 200, 20, 8, 1}
               : Resolution{500, 2401, 500, 100, 64, DiagramOptions{}.max_depth};
}

/// "[2/5] orbits at the paper's frequencies" on stderr, after what stdout
/// has so far.
void Stage(int k, const std::string& what) {
  std::fflush(stdout);
  fmt::print(stderr, "[{}/5] {}\n", k, what);
}

/// The output folder: every file is staged in one set and moved into place
/// at the end, so that a failure at any stage leaves no partial study.
struct Folder {
  std::filesystem::path path;
  Provenance provenance;  ///< of the run; each table adds what it holds
  OutputSet outputs;
  std::vector<std::string> written;        ///< names, in the order staged
  std::vector<std::string> branch_tables;  ///< of written, the branch CSVs
};

/// Stages `text` as folder/name.
void WriteFile(Folder& folder, const std::string& name, const std::string& text) {
  folder.outputs.AddFile(folder.path / name).Write(text);
  folder.written.push_back(name);
}

/// A table staged as folder/name, its header saying which part of the run
/// (`what`) it holds.
CsvWriter& AddTable(Folder& folder, const std::string& name, const std::string& what,
                    const std::vector<std::string>& columns) {
  folder.written.push_back(name);
  Provenance provenance = folder.provenance;
  provenance.run += "; " + what;
  return folder.outputs.AddCsv(folder.path / name, provenance.Text(), columns);
}

nlohmann::json ModalStage(const System& system) {
  const ModalData modal = ComputeModalData(system);
  nlohmann::json j = nlohmann::json::array();
  fmt::print("modal data:   mode   natural frequency   damping ratio   shape\n");
  for (Eigen::Index i = 0; i < modal.natural_frequencies.size(); ++i) {
    std::vector<double> shape(modal.mode_shapes.col(i).data(),
                              modal.mode_shapes.col(i).data() + modal.mode_shapes.rows());
    fmt::print("              {:<6} {:<19.9f} {:<15.9f} ({:.6f})\n", i + 1,
               modal.natural_frequencies(i), modal.damping_ratios(i), fmt::join(shape, ", "));
    j.push_back({{"frequency", modal.natural_frequencies(i)},
                 {"damping_ratio", modal.damping_ratios(i)},
                 {"shape", shape}});
  }
  return j;
}

nlohmann::json ResonanceStage(const System& system, Folder& folder) {
  const std::vector<ResonancePoint> curve = ResonanceCurve(system, 0.05, 2.5, 2451);
  nlohmann::json peaks = nlohmann::json::array();
  for (const ResonancePeak& peak : ResonancePeaks(system, curve)) {
    fmt::print("resonance:    x{} peaks at omega = {:.6f} (max - min {:.4f}, no stop)\n",
               peak.dof + 1, peak.omega, peak.range);
    peaks.push_back({{"dof", peak.dof + 1}, {"omega", peak.omega}, {"range", peak.range}});
  }
  LineChart chart;
  chart.title = "Fig. 2: non-impacting resonance curves";
  chart.x_label = ParameterLabel("omega");
  chart.y_from_zero = true;
  chart.y_label = "max - min displacement";
  for (int i = 0; i < system.Dof(); ++i) {
    Curve c;
    c.title = fmt::format("x{}", i + 1);
    c.dashed = i + 1 < system.Dof();
    for (const ResonancePoint& p : curve) {
      c.x.push_back(p.omega);
      c.y.push_back(p.range(i));
    }
    chart.curves.push_back(std::move(c));
  }
  WriteFile(folder, "fig2-resonance.png", RenderChart(chart, ImageFormat::kPng));
  return peaks;
}

/// The paper's sample frequencies (Fig. 4 and §3) and what is found there.
nlohmann::json OrbitStage(const System& paper, const Resolution& resolution) {
  nlohmann::json rows = nlohmann::json::array();
  for (double omega : {0.1, 0.2, 0.4, 0.6, 0.9, 1.2, 1.4, 1.65, 1.7, 2.0}) {
    System system = paper;
    system.omega = omega;
    const std::optional<OrbitSeed> seed = SeedFromSimulation(system, resolution.transient);
    nlohmann::json row = {{"omega", omega}};
    std::string line = seed ? seed->motion.ToString() : "non-impacting";
    if (seed && seed->motion.periodic && !seed->motion.sticking) {
      OrbitOptions options;
      options.p = static_cast<int>(seed->motion.p);
      options.q = seed->motion.q;
      options.map.stop = seed->stop;
      PeriodicOrbit orbit;
      if (FindOrbit(system, seed->eta, options, &orbit).termination == Termination::kConverged) {
        std::vector<double> v;
        for (const OrbitImpact& i : orbit.impacts) v.push_back(i.velocity);
        line = fmt::format("P({},{}) {}, max |multiplier| {:.4f}, impact speeds {:.6f}", orbit.p,
                           orbit.q, orbit.stable ? "stable" : "unstable",
                           std::abs(orbit.multipliers(0)), fmt::join(v, ", "));
        row["p"] = orbit.p;
        row["q"] = orbit.q;
        row["stable"] = orbit.stable;
        row["velocities"] = v;
        row["max_multiplier_modulus"] = std::abs(orbit.multipliers(0));
      }
    }
    row["motion"] = line;
    fmt::print("  omega = {:<5} {}\n", omega, line);
    rows.push_back(row);
  }
  return rows;
}

/// The connected diagram in omega over the sweep's range (§3 and Fig. 3),
/// seeded by the P(1,1), P(2,1) and P(1,2) orbits of §3 and by the sweep's
/// periodic windows: the branches, every special point, and the picture.
nlohmann::json DiagramStage(const System& paper, const Resolution& resolution, int threads,
                            const SweepOptions& sweep_options, SweepResult sweep, bool all_branches,
                            Folder& folder) {
  SweptDiagramOptions options;
  options.diagram.continuation.from = sweep_options.from;
  options.diagram.continuation.to = sweep_options.to;
  options.diagram.threads = threads;
  options.diagram.max_depth = resolution.max_depth;
  options.seeds.max_p = resolution.max_q;
  std::vector<DiagramSeed> seeds;
  for (double omega : {1.0, 0.6, 2.0}) {
    System system = paper;
    system.omega = omega;
    // The start as `impactkit orbit` finds it; a failure ends the job with
    // its reason rather than leave a branch out of the summary.
    StartOrbitRequest request;
    request.kind = StartOrbitKind::kImpacting;
    request.transient = resolution.transient;
    seeds.push_back({system, SolveStartOrbit(system, request).orbit,
                     fmt::format("the orbit at omega = {}", omega)});
  }
  SweptDiagram swept;
  swept.seeds = seeds;
  for (DiagramSeed& s : SeedsFromSweep(paper, sweep_options, sweep, options.seeds)) {
    swept.seeds.push_back(std::move(s));
  }
  {
    const RunProgress progress("omega");
    swept.diagram = TraceDiagram(swept.seeds, options.diagram, progress.Control());
  }
  PredictGrazings(paper, &swept.diagram);
  swept.sweep = std::move(sweep);
  PrintDiagram(swept.diagram);
  nlohmann::json j = nlohmann::json::array();
  const std::vector<TracedBranch> branches = LabelBranches(swept.diagram);
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const TracedBranch& b = branches[k];
    PrintBranch(b);
    j.push_back(BranchJson(b));
    // The paper's three branches (the first seeds) always; the others,
    // dozens of tables whose points diagram.json holds too, when asked.
    if (k >= seeds.size() && !all_branches) continue;
    const std::string csv = "branch-" + b.label + ".csv";
    WriteBranchRows(AddTable(folder, csv, "branch " + b.label, BranchColumns(b.branch)), b.branch);
    folder.branch_tables.push_back(csv);
  }
  WriteFile(folder, "diagram.json",
            nlohmann::json::parse(DiagramJson(swept.diagram)).dump(2) + "\n");
  WriteFile(folder, "diagram.png",
            RenderDiagram(DiagramFigure(swept, DiagramAxis::kImpactVelocity), ImageFormat::kPng));
  return j;
}

/// What a regime is: the kind, with p and q for periodic motions and q for
/// sticking ones (P(inf,q) whatever the impacts before the chatter ends).
std::string RegimeKey(const Classification& c) {
  switch (c.kind) {
    case MotionKind::kPeriodic:
      return fmt::format("P({},{})", c.period.p, c.period.q);
    case MotionKind::kSticking:
      return fmt::format("P(inf,{})", c.period.q);
    default:
      return ToString(c.kind);
  }
}

/// Consecutive values with the same motion, as ranges.
nlohmann::json Regimes(const SweepResult& sweep) {
  nlohmann::json regimes = nlohmann::json::array();
  std::size_t from = 0;
  for (std::size_t i = 1; i <= sweep.points.size(); ++i) {
    const std::string key = RegimeKey(sweep.points[from].classification);
    if (i < sweep.points.size() && RegimeKey(sweep.points[i].classification) == key) continue;
    regimes.push_back({{"from", sweep.points[from].value},
                       {"to", sweep.points[i - 1].value},
                       {"values", i - from},
                       {"kind", ToString(sweep.points[from].classification.kind)},
                       {"motion", key}});
    from = i;
  }
  return regimes;
}

void PrintRegimes(const nlohmann::json& regimes) {
  int short_runs = 0;
  for (const nlohmann::json& r : regimes) {
    if (r["values"].get<std::size_t>() < 3) {
      ++short_runs;
      continue;
    }
    fmt::print("  omega {:.4f} to {:.4f}  {}\n", r["from"].get<double>(), r["to"].get<double>(),
               r["motion"].get<std::string>());
  }
  if (short_runs > 0) fmt::print("  (and {} windows of one or two values)\n", short_runs);
}

SweepOptions PaperSweepOptions(const Resolution& resolution, int threads) {
  SweepOptions options;
  options.from = 0.1;
  options.to = 2.5;
  options.steps = resolution.sweep_values;
  options.transient_periods = resolution.sweep_transient;
  options.recorded_periods = resolution.sweep_record;
  options.classify.period.max_q = resolution.max_q;
  options.threads = threads;
  return options;
}

nlohmann::json SweepStage(const System& paper, const SweepOptions& options,
                          const SweepResult& sweep, Folder& folder) {
  fmt::print("  {}\n", sweep.BriefReport());
  const nlohmann::json regimes = Regimes(sweep);
  PrintRegimes(regimes);
  CsvWriter& csv = AddTable(folder, "fig3-sweep.csv", "the Fig. 3 sweep, omega 0.1 to 2.5",
                            {"omega", "range_xN_max", "impacts", "kind", "p", "q"});
  for (const SweepPoint& p : sweep.points) {
    const double range = p.range_contact.empty()
                             ? 0.0
                             : *std::max_element(p.range_contact.begin(), p.range_contact.end());
    const PeriodLabels period = LabelsOf(CellOf(0, p));
    csv.WriteRow(std::vector<double>{p.value, range, static_cast<double>(p.impacts.size())},
                 std::vector<std::string>{period.kind, period.p, period.q});
  }
  WriteFile(folder, "fig3-bifurcation.png",
            RenderStacked(SweepCharts(paper, options, sweep), 1000, 900, ImageFormat::kPng));
  return regimes;
}

/// What is where in the folder, a line per part of the study (every file
/// staged is on one of them).
void PrintWritten(const Folder& folder, std::size_t branches) {
  fmt::print("wrote into {}:\n", std::filesystem::absolute(folder.path).string());
  fmt::print(
      "  summary.json          everything printed above (modes, peaks, orbits, regimes, "
      "branches)\n");
  fmt::print("  fig2-resonance.png    Fig. 2, the resonance curves without the stop\n");
  fmt::print(
      "  fig3-bifurcation.png  Fig. 3, the brute-force diagram; fig3-sweep.csv, one row "
      "per value\n");
  fmt::print(
      "  diagram.png           the connected diagram; diagram.json, its {} branches' "
      "points and special points\n",
      branches);
  const std::size_t tables = folder.branch_tables.size();
  fmt::print("  branch-*.csv          {} branch table{}: {}{}\n", tables, tables == 1 ? "" : "s",
             fmt::join(folder.branch_tables, ", "),
             tables < branches ? " (every branch's with --all-branches)" : "");
}

void RunPaper(const PaperRequest& request) {
  if (request.threads < 0) throw InvalidInput("--threads must be >= 0 (0: all cores)");
  RequireGnuplot();
  const auto start = std::chrono::steady_clock::now();
  Folder folder;
  folder.path = request.out;
  std::error_code error;
  std::filesystem::create_directories(folder.path, error);
  if (error) {
    throw OutputError(
        fmt::format("cannot create the folder {}: {}", folder.path.string(), error.message()));
  }
  // Staged first: a folder that cannot be written fails before the work.
  AtomicOutputFile& summary_file = folder.outputs.AddFile(folder.path / "summary.json");
  const Resolution resolution = ResolutionFor(request.quick);
  const System paper = PaperSystem(1.0);
  folder.provenance =
      MakeProvenance(SystemOptions{}, paper,
                     fmt::format("paper --out {}{}", request.out, request.quick ? " --quick" : ""));
  nlohmann::json summary;
  summary["provenance"] = folder.provenance.Json();
  summary["system"] = nlohmann::json::parse(SystemToJson(paper));
  summary["quick"] = request.quick;

  fmt::print("system:       {} (Wagg & Bishop 2001)\n", DescribeSystem(paper));
  Stage(1, "modal data and resonance curves");
  summary["modes"] = ModalStage(paper);
  summary["resonance_peaks"] = ResonanceStage(paper, folder);
  Stage(2, "orbits at the paper's frequencies");
  fmt::print("orbits (from a simulation from rest, refined as fixed points of the impact map):\n");
  summary["orbits"] = OrbitStage(paper, resolution);
  const int threads = request.threads > 0
                          ? request.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  Stage(3, "brute-force bifurcation diagram (Fig. 3)");
  fmt::print("brute-force diagram, omega 0.1 to 2.5 ({} values):\n", resolution.sweep_values);
  const SweepOptions sweep_options = PaperSweepOptions(resolution, threads);
  SweepResult sweep;
  {
    const RunProgress progress("omega");
    sweep = RunSweep(paper, sweep_options, progress.Control());
  }
  summary["regimes"] = SweepStage(paper, sweep_options, sweep, folder);
  Stage(4, "connected bifurcation diagram");
  fmt::print(
      "branches (the connected diagram in omega, seeded at 1.0, 0.6, 2.0 and by the "
      "sweep):\n");
  summary["branches"] = DiagramStage(paper, resolution, threads, sweep_options, std::move(sweep),
                                     request.all_branches, folder);
  Stage(5, "summary");
  summary["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary_file.Write(summary.dump(2) + "\n");
  folder.written.push_back("summary.json");
  folder.outputs.Commit();
  PrintWritten(folder, summary["branches"].size());
  fmt::print("time:         {:.1f} s\n", summary["seconds"].get<double>());
}

}  // namespace

void AddPaperCommand(CLI::App& app) {
  auto request = std::make_shared<PaperRequest>();
  CLI::App* command = app.add_subcommand(
      "paper",
      "The paper's study on its system in one run: modal data, resonance peaks (Fig. 2), the "
      "orbits at its sample frequencies with their stability, the P(1,1), P(2,1) and P(1,2) "
      "branches continued in omega with the branches born at their period doublings and "
      "grazings, and the brute-force diagram (Fig. 3) with its regimes. Prints a summary and "
      "writes CSV, JSON and PNG files into one folder, and says what is where.");
  command->add_option("--out", request->out, "Output folder (created if missing)")
      ->check(OutputPath("folder"))
      ->capture_default_str();
  command->add_flag("--quick", request->quick,
                    "Reduced resolution (121 sweep values, short transients), for tests");
  command->add_flag("--all-branches", request->all_branches,
                    "A CSV table for every branch of the connected diagram (dozens; diagram.json "
                    "holds their points too), not only for the three seeded at the paper's "
                    "orbits");
  command->add_option("--threads", request->threads, "Threads of the sweep (0: all cores)")
      ->check(AtMost(kMaxThreads, "threads"))
      ->capture_default_str();
  command->callback([request] { RunPaper(*request); });
}

}  // namespace impactkit::cli
