// The branch network (diagram.hpp): starts taken breadth first, each traced
// unless its orbit lies on a branch traced already, and the branches born
// at each traced branch's special points queued as the next generation.

#include "impactkit/continuation/diagram.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "continuation/diagram_builder.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {
namespace {

/// A branch to trace: where it starts, which way, and where it came from.
struct PendingStart {
  BranchStart start;
  ContinuationDirection direction = ContinuationDirection::kBoth;
  OrbitOptions orbit;  ///< p and q of the start
  std::string origin;
  int depth = 0;
  int parent = -1;
  /// A pitchfork's start: the branch it crosses, which its orbit lies within
  /// the same-branch tolerance of so near the crossing (not compared with).
  int crosses = -1;
};

/// What a branch's orbits are: their section, and their map's events
/// (impacts or releases) in q forcing periods.
struct Family {
  OrbitSection section = OrbitSection::kImpact;
  int k = 1;
  int q = 1;
  bool operator==(const Family&) const = default;
};

Family FamilyOf(const Branch& branch) {
  return {branch.section, branch.section == OrbitSection::kRelease ? branch.releases : branch.p,
          branch.q};
}

/// What identifies an orbit on its branch whichever event its η starts
/// from: its first k impact speeds, or its k stuck durations, sorted.
std::vector<double> Signature(const PeriodicOrbit& orbit, int k) {
  std::vector<double> values;
  for (int i = 0; i < k; ++i) {
    values.push_back(orbit.Sticks() ? orbit.stuck[i].Duration() : orbit.impacts[i].velocity);
  }
  std::sort(values.begin(), values.end());
  return values;
}

/// The start's family, an impacting start reduced to its primitive period
/// (a P(2,2) that is P(1,1) twice is P(1,1)), as ContinueBranch will
/// follow it.
Family StartFamily(const PendingStart& pending) {
  const PeriodicOrbit& orbit = pending.start.orbit;
  if (orbit.Sticks()) return {OrbitSection::kRelease, orbit.releases, orbit.q};
  const ImpactMap map(pending.start.system, pending.orbit.map);
  const OrbitPeriod period = PrimitivePeriod(map, orbit.eta, pending.orbit.p, pending.orbit.q);
  return {OrbitSection::kImpact, period.p, period.q};
}

/// Whether the orbit (of family `family`, signature `signature`, at μ)
/// lies on `branch`: the same family, and a signature within `tolerance` of
/// the branch's, linearly interpolated between two consecutive points that
/// bracket μ (through a fold, either sheet).
bool OnBranch(const Branch& branch, Family family, double mu, const std::vector<double>& signature,
              double tolerance) {
  if (FamilyOf(branch) != family) return false;
  const double scale = tolerance * (1.0 + signature.back());
  for (std::size_t k = 0; k < branch.points.size(); ++k) {
    const BranchPoint& a = branch.points[k];
    const BranchPoint& b = branch.points[std::min(k + 1, branch.points.size() - 1)];
    const double lo = std::min(a.parameter, b.parameter), hi = std::max(a.parameter, b.parameter);
    if (mu < lo - scale || mu > hi + scale) continue;
    const double w =
        hi > lo ? std::clamp((mu - a.parameter) / (b.parameter - a.parameter), 0.0, 1.0) : 0.0;
    const std::vector<double> sa = Signature(a.orbit, family.k);
    const std::vector<double> sb = Signature(b.orbit, family.k);
    bool close = true;
    for (int i = 0; i < family.k && close; ++i) {
      close = std::abs((1 - w) * sa[i] + w * sb[i] - signature[i]) <= scale;
    }
    if (close) return true;
  }
  return false;
}

}  // namespace

bool CoveredBy(const Branch& branch, const Branch& other, double tolerance) {
  const Family family = FamilyOf(branch);
  if (branch.points.empty() || FamilyOf(other) != family) return false;
  return std::all_of(branch.points.begin(), branch.points.end(), [&](const BranchPoint& point) {
    return OnBranch(other, family, point.parameter, Signature(point.orbit, family.k), tolerance);
  });
}

namespace {

class NetworkTracer {
 public:
  NetworkTracer(System system, const DiagramOptions& options, const RunControl& control)
      : system_(std::move(system)),
        options_(options),
        control_(control),
        builder_(&diagram_, options) {
    diagram_.parameter = options.continuation.parameter;
    diagram_.termination = Termination::kCompleted;
  }

  Diagram Run(const std::vector<DiagramSeed>& seeds) {
    std::vector<PendingStart> generation;
    for (std::size_t k = 0; k < seeds.size(); ++k) {
      OrbitOptions orbit = options_.continuation.orbit;
      if (!seeds[k].orbit.Sticks()) {  // a sticking family is its start's
        orbit.p = seeds[k].orbit.p;
        orbit.q = seeds[k].orbit.q;
        orbit.map.stop = seeds[k].orbit.stop;
      }
      generation.push_back(
          {{seeds[k].system, seeds[k].orbit, {}},
           seeds[k].direction,
           orbit,
           seeds[k].origin.empty() ? fmt::format("seed {}", k + 1) : seeds[k].origin,
           0,
           -1});
    }
    while (!generation.empty() && !control_.Cancelled()) {
      std::vector<PendingStart> next;
      for (int index : TraceGeneration(Untraced(std::move(generation)))) {
        const std::vector<PendingStart> born = Switch(index);
        next.insert(next.end(), born.begin(), born.end());
      }
      generation = std::move(next);
    }
    if (control_.Cancelled()) Incomplete(Termination::kStopped, Describe(Termination::kStopped));
    return std::move(diagram_);
  }

 private:
  /// Whether the start's orbit lies on a branch in diagram_.
  bool Traced(const PendingStart& pending) const {
    const Family family = StartFamily(pending);
    const double mu = GetParameter(pending.start.system, diagram_.parameter);
    const std::vector<double> signature = Signature(pending.start.orbit, family.k);
    for (std::size_t k = 0; k < diagram_.branches.size(); ++k) {
      if (static_cast<int>(k) == pending.crosses) continue;
      if (OnBranch(diagram_.branches[k].branch, family, mu, signature,
                   options_.same_branch_tolerance)) {
        return true;
      }
    }
    return false;
  }

  /// The starts not on a traced branch.
  std::vector<PendingStart> Untraced(std::vector<PendingStart> starts) {
    std::vector<PendingStart> kept;
    for (PendingStart& s : starts) {
      if (Traced(s)) {
        ++diagram_.duplicate_starts;
      } else {
        kept.push_back(std::move(s));
      }
    }
    return kept;
  }

  /// Where a start of a generation is: waiting for the earlier starts of
  /// its family, being traced, traced, or dropped (on one of their branches).
  enum class StartState { kWaiting, kRunning, kTraced, kDropped };

  /// What a worker does next with a generation's starts.
  struct NextStart {
    enum { kTrace, kWait, kDone } action = kDone;
    std::size_t index = 0;  ///< the start to trace (kTrace)
  };

  /// The first waiting start whose family's earlier starts are all decided,
  /// dropping on the way each whose orbit an earlier branch of its family
  /// holds. A start lies only on branches of its own family, so deciding
  /// the starts of one family in order drops exactly those an in-order
  /// trace would, and no worker traces one of them: the branches traced do
  /// not depend on the threads, and families are traced at once.
  NextStart Decide(const std::vector<PendingStart>& starts, const std::vector<Family>& families,
                   const std::vector<Branch>& traced, const std::vector<std::exception_ptr>& errors,
                   std::vector<StartState>* states) const {
    bool busy = false;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      busy = busy || (*states)[k] == StartState::kRunning;
      if ((*states)[k] != StartState::kWaiting) continue;
      bool decided = true, held = false;
      for (std::size_t j = 0; j < k && decided; ++j) {
        if (families[j] != families[k]) continue;
        decided = (*states)[j] == StartState::kTraced || (*states)[j] == StartState::kDropped;
        held = held || ((*states)[j] == StartState::kTraced && !errors[j] &&
                        Holds(traced[j], starts[k], families[k]));
      }
      if (!decided) {
        busy = true;
        continue;
      }
      (*states)[k] = held ? StartState::kDropped : StartState::kRunning;
      if (!held) return {NextStart::kTrace, k};
    }
    return {busy ? NextStart::kWait : NextStart::kDone, 0};
  }

  /// Whether `branch` holds the start's orbit.
  bool Holds(const Branch& branch, const PendingStart& pending, Family family) const {
    return OnBranch(branch, family, GetParameter(pending.start.system, diagram_.parameter),
                    Signature(pending.start.orbit, family.k), options_.same_branch_tolerance);
  }

  /// Traces the starts (on up to options.threads threads), each unless an
  /// earlier start's branch of the generation holds it (Decide), and adds
  /// the branches in start order. Returns the indices of the added branches.
  std::vector<int> TraceGeneration(const std::vector<PendingStart>& starts) {
    if (!starts.empty() && static_cast<int>(diagram_.branches.size()) >= options_.max_branches) {
      Incomplete(Termination::kMaxPoints,
                 fmt::format("max_branches ({}) reached", options_.max_branches));
      return {};  // not traced at all: none of them could be kept
    }
    std::vector<Family> families;
    for (const PendingStart& pending : starts) families.push_back(StartFamily(pending));
    std::vector<Branch> traced(starts.size());
    std::vector<std::exception_ptr> errors(starts.size());
    std::vector<StartState> states(starts.size(), StartState::kWaiting);
    std::mutex mutex;
    std::condition_variable decided;
    auto work = [&] {
      std::unique_lock<std::mutex> lock(mutex);
      for (;;) {
        const NextStart next = Decide(starts, families, traced, errors, &states);
        if (next.action == NextStart::kDone) {
          decided.notify_all();  // a drop may have left the others nothing to wait for
          return;
        }
        if (next.action == NextStart::kWait) {
          decided.wait(lock);
          continue;
        }
        lock.unlock();
        Trace(starts[next.index], &traced[next.index], &errors[next.index]);
        lock.lock();
        states[next.index] = StartState::kTraced;
        decided.notify_all();
      }
    };
    std::vector<std::thread> workers;
    const int threads = std::min<int>(options_.threads, static_cast<int>(starts.size()));
    for (int t = 1; t < threads; ++t) workers.emplace_back(work);
    work();
    for (std::thread& t : workers) t.join();
    for (std::size_t k = 0; k < starts.size(); ++k) {
      if (!errors[k]) continue;
      // A caller's seed that ContinueBranch refuses is the caller's error;
      // a start found by switching that it refuses is a switch that failed.
      if (starts[k].depth == 0) std::rethrow_exception(errors[k]);
      try {
        std::rethrow_exception(errors[k]);
      } catch (const InvalidInput&) {
        ++diagram_.failed_starts;
      }
    }

    std::vector<int> added;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      if (states[k] == StartState::kDropped) ++diagram_.duplicate_starts;
      if (errors[k] || states[k] == StartState::kDropped) continue;
      if (static_cast<int>(diagram_.branches.size()) >= options_.max_branches) {
        Incomplete(Termination::kMaxPoints,
                   fmt::format("max_branches ({}) reached", options_.max_branches));
        break;
      }
      diagram_.branches.push_back(
          {std::move(traced[k]), starts[k].origin, starts[k].depth, starts[k].parent});
      added.push_back(static_cast<int>(diagram_.branches.size()) - 1);
    }
    return added;
  }

  /// Follows one start's branch into *branch. An exception may not leave a
  /// worker thread (it would terminate the program): kept in *error, and
  /// rethrown or counted after the join.
  void Trace(const PendingStart& pending, Branch* branch, std::exception_ptr* error) const {
    ContinuationOptions options = options_.continuation;
    options.orbit = pending.orbit;
    options.direction = pending.direction;
    try {
      const RunControl branch_control(
          [&](const Progress& point) {
            control_.Report({.stage = "diagram",
                             .done = static_cast<std::int64_t>(diagram_.branches.size()),
                             .parameter = point.parameter});
          },
          control_);
      *branch = ContinueBranch(pending.start, options, branch_control);
    } catch (...) {
      *error = std::current_exception();
    }
  }

  /// Records the first reason the network is cut short.
  void Incomplete(Termination termination, const std::string& why) {
    if (diagram_.termination != Termination::kCompleted) return;
    diagram_.termination = termination;
    diagram_.message = why;
  }

  /// Adds branch `index` to the graph and returns the starts born at its
  /// special points.
  std::vector<PendingStart> Switch(int index) {
    const std::vector<int> nodes = builder_.AddBranch(index);
    const DiagramBranch& traced = diagram_.branches[index];
    const Branch& branch = traced.branch;
    std::vector<PendingStart> born;
    if (traced.depth >= options_.max_depth) {
      if (!branch.special_points.empty()) {
        Incomplete(Termination::kMaxPoints,
                   fmt::format("max_depth ({}) reached", options_.max_depth));
      }
      return born;
    }
    const System& system = system_;
    for (std::size_t k = 0; k < branch.special_points.size(); ++k) {
      const SpecialPoint& s = branch.special_points[k];
      const std::string where = s.Describe(branch.parameter);
      auto add = [&](BranchStart start, ContinuationDirection direction, int p, int q,
                     const std::string& how) {
        // A special point located just past a bound (grazings are
        // approached from the branch side) may seed outside the range.
        const double mu = GetParameter(start.system, diagram_.parameter);
        if (mu < options_.continuation.Lower() || mu > options_.continuation.Upper()) return;
        OrbitOptions orbit = options_.continuation.orbit;
        if (!start.orbit.Sticks()) {  // a sticking family is its start's
          orbit.p = p;
          orbit.q = q;
          orbit.map.stop = start.orbit.stop;
        }
        born.push_back(
            {std::move(start), direction, orbit, how + where, traced.depth + 1, nodes[k]});
      };
      if (s.type == SpecialPointType::kPeriodDoubling && options_.switch_period_doubling) {
        ContinuationOptions options = options_.continuation;
        options.orbit.p = branch.p;
        options.orbit.q = branch.q;
        if (std::optional<BranchStart> start = DoubledBranchStart(system, branch, s, options)) {
          add(std::move(*start), ContinuationDirection::kIncreasing, 2 * branch.p, 2 * branch.q,
              "doubled at the ");
        } else {
          ++diagram_.failed_starts;
        }
      }
      if (s.type == SpecialPointType::kPitchfork && options_.switch_pitchforks) {
        ContinuationOptions options = options_.continuation;
        options.orbit.p = branch.p;
        options.orbit.q = branch.q;
        // Both halves: in a symmetric system, the two mirror images.
        for (double offset : {1e-3, -1e-3}) {
          if (std::optional<BranchStart> start =
                  PitchforkBranchStart(system, branch, s, options, offset)) {
            const std::size_t before = born.size();
            add(std::move(*start), ContinuationDirection::kIncreasing, branch.p, branch.q,
                "crossing at the ");
            if (born.size() > before) born.back().crosses = index;
          } else {
            ++diagram_.failed_starts;
          }
        }
      }
      // Seeds past a grazing are orbits with an impact more or fewer.
      const bool graze =
          s.type == SpecialPointType::kGrazing || s.type == SpecialPointType::kSticking;
      if (graze && options_.switch_grazing) {
        ContinuationOptions options = options_.continuation;
        options.orbit.p = branch.p;
        options.orbit.q = branch.q;
        // Both sides: which side the orbit with an impact more or fewer
        // lives on depends on the grazing; a side holding none fails to
        // converge or converges onto a traced branch.
        const std::vector<GrazingSeed> near = SeedsAtGrazing(system, branch, s, options);
        const std::vector<GrazingSeed> nearer = SeedsAtGrazing(system, branch, s, options, 1e-4);
        for (std::size_t side = 0; side < near.size(); ++side) {
          PeriodicOrbit orbit;
          // Newton's basin beside a grazing is narrow (the map is a square
          // root there): a side whose seed misses it is tried once nearer.
          const GrazingSeed* seed = &near[side];
          bool found = FindOrbit(seed->system, seed->eta, seed->orbit, &orbit).termination ==
                       Termination::kConverged;
          if (!found && side < nearer.size()) {
            seed = &nearer[side];
            found = FindOrbit(seed->system, seed->eta, seed->orbit, &orbit).termination ==
                    Termination::kConverged;
          }
          if (!found) {
            ++diagram_.failed_starts;
            continue;
          }
          add({seed->system, orbit, {}}, ContinuationDirection::kBoth, seed->orbit.p, seed->orbit.q,
              "seeded at the ");
        }
      }
      if (s.type == SpecialPointType::kBranchPoint && options_.switch_branch_points) {
        // The orbit here repeats itself: ContinueBranch follows it as the
        // shorter orbit, whose branch this one meets.
        System at = system;
        SetParameter(at, branch.parameter, s.point.parameter);
        add({at, s.point.orbit, {}}, ContinuationDirection::kBoth, branch.p, branch.q,
            "the shorter orbit at the ");
      }
    }
    return born;
  }

  /// The seeds' system: every branch's at some parameter value (switching
  /// sets the value it needs).
  const System system_;
  const DiagramOptions& options_;
  const RunControl& control_;
  Diagram diagram_;
  detail::DiagramBuilder builder_;
};

}  // namespace

bool DiagramOptions::IsValid(std::string* error) const {
  auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (max_depth < 0) return fail(fmt::format("max_depth must be >= 0, got {}", max_depth));
  if (max_branches < 1) return fail(fmt::format("max_branches must be >= 1, got {}", max_branches));
  if (threads < 1) return fail(fmt::format("threads must be >= 1, got {}", threads));
  for (double tolerance : {node_tolerance, node_range_tolerance, same_branch_tolerance}) {
    if (!(tolerance > 0 && tolerance < 1)) {
      return fail(fmt::format("the diagram's tolerances must be in (0, 1), got {}", tolerance));
    }
  }
  return continuation.IsValid(error);
}

Diagram TraceDiagram(const std::vector<DiagramSeed>& seeds, const DiagramOptions& options,
                     const RunControl& control) {
  const auto clock_start = std::chrono::steady_clock::now();
  std::string error;
  Require(options.IsValid(&error), error);
  Require(!seeds.empty(), "TraceDiagram needs at least one seed");
  for (const DiagramSeed& seed : seeds) {
    Require(seed.system.Dof() == seeds.front().system.Dof(),
            "the seeds of one diagram must be orbits of one system");
  }
  Diagram diagram = NetworkTracer(seeds.front().system, options, control).Run(seeds);
  diagram.iterations = static_cast<int>(diagram.branches.size());
  diagram.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return diagram;
}

}  // namespace impactkit
