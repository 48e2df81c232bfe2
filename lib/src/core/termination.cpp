#include "impactkit/core/termination.hpp"

namespace impactkit {
namespace {

struct TerminationText {
  const char* name;
  const char* description;
};

TerminationText TextOf(Termination termination) {
  switch (termination) {
    case Termination::kConverged:
      return {"converged", "converged"};
    case Termination::kNoConvergence:
      return {"no_convergence", "no convergence"};
    case Termination::kFailure:
      return {"failure", "failure"};
    case Termination::kCompleted:
      return {"completed", "completed"};
    case Termination::kStopped:
      return {"stopped", "stopped on request"};
    case Termination::kEventLimit:
      return {"event_limit", "event limit reached"};
    case Termination::kWorkLimit:
      return {"work_limit", "work bound reached: too many events in one forcing period"};
    case Termination::kStalled:
      return {"stalled", "stalled: events repeat at one instant"};
    case Termination::kNoImpact:
      return {"no_impact", "lost impact (no further impact)"};
    case Termination::kGrazing:
      return {"grazing", "grazing impact (speed ~ 0)"};
    case Termination::kSticking:
      return {"sticking",
              "chatter into sticking (impacts accumulate at the stop, the mass pressed into it)"};
    case Termination::kOtherStop:
      return {"other_stop", "the last impact or release is at another stop than the section's"};
    case Termination::kNotReleased:
      return {"not_released", "not a release (the stop still pushes on the mass: Fs > 0)"};
    case Termination::kNoChatter:
      return {"no_chatter", "impacts without a chatter sequence accumulating"};
    case Termination::kNoSticking:
      return {"no_sticking", "the chatter ends with Fs <= 0: the mass is not held (no sticking)"};
    case Termination::kNoRelease:
      return {"no_release", "no release: the mass stays stuck"};
    case Termination::kMetWhileHeld:
      return {"met_while_held",
              "a mass reaches its stop while another stop holds a mass (the release map follows "
              "one held stop at a time)"};
    case Termination::kEarlyRelease:
      return {"early_release", "the contact force touches 0 inside a stuck phase"};
    case Termination::kParameterBound:
      return {"parameter_bound", "reached an end of the parameter's range"};
    case Termination::kBranchPoint:
      return {"branch_point", "met the branch of a shorter orbit traversed several times"};
    case Termination::kMaxPoints:
      return {"max_points", "a bound on points, branches or depth reached"};
    case Termination::kCorrectorFailed:
      return {"corrector_failed", "no convergence even with the smallest step"};
    case Termination::kClosed:
      return {"closed", "the curve closed on its start"};
  }
  return {"unknown", "unknown"};
}

}  // namespace

std::string ToString(Termination termination) { return TextOf(termination).name; }

std::string Describe(Termination termination) { return TextOf(termination).description; }

}  // namespace impactkit
