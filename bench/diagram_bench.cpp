/// The connected diagram of the paper's range, Ω from 0.4 to 2.3, with the
/// library's defaults (SweptDiagramOptions: a 481-value sweep refined five
/// times where the motion changes or has no period) beside the 2401-value
/// uniform sweep's (no refinement: `impactkit diagram --from 0.4 --to 2.3
/// --sweep-values 2401 --refine 1`), both in this process on the same
/// threads: CPU seconds of each (the process's, all threads), split into
/// the sweep with its seeds and the network, and what each finds — the
/// families P(p,q) it traces and the special points it locates (kind and
/// parameter to 1e-6) — with every difference listed.
///
///   ./build/bench/diagram_bench [threads]      (default 2)

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "cpu_time.hpp"
#include "impactkit/analysis/swept_diagram.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

struct Run {
  SweptDiagram swept;
  double cpu = 0.0;          ///< CPU seconds of the whole run
  double network_cpu = 0.0;  ///< of which after the first branch point was reported
};

/// The run's CPU time, and when its diagram stage began.
Run Measure(const SweptDiagramOptions& options) {
  Run run;
  const double start = CpuSeconds();
  double network_start = -1.0;
  const RunControl control([&](const Progress& progress) {
    if (network_start < 0 && progress.stage == "diagram") network_start = CpuSeconds();
  });
  run.swept = TraceSweptDiagram(PaperSystem(0.4), {}, options, control);
  const double end = CpuSeconds();
  run.cpu = end - start;
  run.network_cpu = network_start < 0 ? 0.0 : end - network_start;
  return run;
}

SweptDiagramOptions PaperRange(int threads) {
  SweptDiagramOptions options;
  options.diagram.continuation.from = 0.4;
  options.diagram.continuation.to = 2.3;
  options.diagram.threads = options.sweep.threads = threads;
  return options;
}

std::string Family(const Branch& b) {
  return b.section == OrbitSection::kRelease ? fmt::format("P(inf,{}) {}r", b.q, b.releases)
                                             : fmt::format("P({},{})", b.p, b.q);
}

/// A special point's kind as a located feature: a period doubling and the
/// branch point where its doubled branch lands are one node, named by
/// whichever branch located it first.
std::string Kind(const DiagramNode& node) {
  return node.special == SpecialPointType::kBranchPoint ? "period_doubling" : node.Name();
}

bool Special(const DiagramNode& node) { return node.kind == DiagramNodeKind::kSpecialPoint; }

/// Two special points are one: the same kind, parameters within 1e-6.
bool SameNode(const DiagramNode& a, const DiagramNode& b) {
  return Kind(a) == Kind(b) && std::abs(a.parameter - b.parameter) < 1e-6;
}

std::set<std::string> Families(const Diagram& d) {
  std::set<std::string> families;
  for (const DiagramBranch& b : d.branches) families.insert(Family(b.branch));
  return families;
}

/// Prints the families and special points `found` has and `other` has
/// not; returns how many. Where a branch ends otherwise (the corrector
/// failing, a bound) is not compared: it is where tracing gave up, not a
/// point of the diagram.
int Differences(const Diagram& found, const Diagram& other, const std::string& only_in) {
  int count = 0;
  const std::set<std::string> theirs = Families(other);
  for (const std::string& family : Families(found)) {
    if (theirs.count(family)) continue;
    fmt::print("  family only in {}: {}\n", only_in, family);
    ++count;
  }
  for (const DiagramNode& n : found.nodes) {
    if (!Special(n)) continue;
    const bool shared =
        std::any_of(other.nodes.begin(), other.nodes.end(),
                    [&](const DiagramNode& o) { return Special(o) && SameNode(n, o); });
    if (shared) continue;
    fmt::print("  special point only in {}: {} at {:.9f} on P({},{})\n", only_in, n.Name(),
               n.parameter, n.p, n.q);
    ++count;
  }
  return count;
}

int SpecialNodes(const Diagram& d) {
  return static_cast<int>(std::count_if(d.nodes.begin(), d.nodes.end(), Special));
}

void Row(const std::string& name, const Run& run) {
  const SweptDiagram& s = run.swept;
  fmt::print("| {} | {} ({} refined) | {} | {} | {} | {} | {:.2f} | {:.2f} | {:.2f} |\n", name,
             s.sweep.points.size(), s.refined_values, s.seeds.size(), s.diagram.branches.size(),
             SpecialNodes(s.diagram),
             s.diagram.termination == Termination::kCompleted ? "yes" : s.diagram.message,
             run.cpu - run.network_cpu, run.network_cpu, run.cpu);
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const SweptDiagramOptions defaults = PaperRange(threads);
  SweptDiagramOptions uniform = PaperRange(threads);
  uniform.sweep.steps = 2401;
  uniform.refine.factor = 1;
  const Run fine = Measure(uniform);
  const Run recipe = Measure(defaults);
  fmt::print("Ω 0.4 to 2.3, {} threads; CPU seconds of this process\n\n", threads);
  fmt::print(
      "| run | sweep values | seeds | branches | special points | complete | sweep + seeds CPU "
      "s | network CPU s | total CPU s |\n|---|---|---|---|---|---|---|---|---|\n");
  Row("2401 uniform values", fine);
  Row("defaults (481, refined x5)", recipe);
  fmt::print("\nCPU ratio defaults / 2401 values: {:.3f} (target <= 0.333)\n",
             recipe.cpu / fine.cpu);
  fmt::print("differences:\n");
  const int missing = Differences(fine.swept.diagram, recipe.swept.diagram, "the 2401-value run");
  const int extra = Differences(recipe.swept.diagram, fine.swept.diagram, "the defaults' run");
  fmt::print("{} found by the 2401-value run only, {} by the defaults' only\n", missing, extra);
  const bool p46 =
      std::any_of(recipe.swept.diagram.branches.begin(), recipe.swept.diagram.branches.end(),
                  [](const DiagramBranch& b) { return b.branch.p == 4 && b.branch.q == 6; });
  fmt::print("the defaults' run traces P(4,6): {}\n", p46 ? "yes" : "no");
  return 0;
}
