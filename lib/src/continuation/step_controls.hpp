#pragma once
/// \file step_controls.hpp
/// The checks every pseudo-arclength driver (branches, two-parameter curves)
/// makes of its step controls, in one place so their messages agree.

#include <optional>
#include <string>

namespace impactkit {

/// What is wrong with the step controls, or nothing: 0 < min_step <=
/// initial_step <= max_step (finite), max_points >= 2, corrector_iterations
/// >= 1, max_correction in (0, 1].
std::optional<std::string> StepControlProblem(double min_step, double initial_step, double max_step,
                                              int max_points, int corrector_iterations,
                                              double max_correction);

}  // namespace impactkit
