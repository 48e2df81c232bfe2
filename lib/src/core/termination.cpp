#include "impactkit/core/termination.hpp"

namespace impactkit {

std::string ToString(Termination termination) {
  switch (termination) {
    case Termination::kConverged:
      return "converged";
    case Termination::kNoConvergence:
      return "no convergence";
    case Termination::kFailure:
      return "failure";
  }
  return "unknown";
}

}  // namespace impactkit
