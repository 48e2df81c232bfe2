#pragma once
/// \file common/progress.hpp
/// A progress line for long simulations, drawn on stderr and rewritten in
/// place. Only for a person watching: silent when stderr is not a terminal
/// (pipes, logs, tests) and for runs that finish within a second.

#include <chrono>
#include <string>

#include "impactkit/core/run_control.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit::cli {

class ProgressLine : public Observer {
 public:
  /// `label` says which stage runs ("transient"); the run covers
  /// [t_begin, t_end], shown in forcing periods of length `period`.
  ProgressLine(std::string label, double t_begin, double t_end, double period);
  /// Erases the line, so that what is printed next starts clean.
  ~ProgressLine() override;
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  void OnSegment(const Segment& segment) override;

 private:
  using Clock = std::chrono::steady_clock;

  const bool enabled_;
  const std::string label_;
  const double t_begin_;
  const double t_end_;
  const double period_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_drawn_{};
  bool drawn_ = false;
};

/// The same line for a library run (sweep, branch, curve, diagram): its
/// RunControl reports here. "sweep of omega 35% (840 of 2401 values)",
/// "branch: 314 points, omega = 1.2345", "diagram: 3 branches done, ...".
class RunProgress {
 public:
  /// The names of the parameters the run's points carry.
  explicit RunProgress(std::string parameter, std::string parameter2 = "");
  /// Erases the line.
  ~RunProgress();
  RunProgress(const RunProgress&) = delete;
  RunProgress& operator=(const RunProgress&) = delete;

  /// What to pass the library's driver.
  const RunControl& Control() const { return control_; }

 private:
  using Clock = std::chrono::steady_clock;
  void Draw(const Progress& progress);
  std::string Text(const Progress& progress) const;

  const bool enabled_;
  const std::string parameter_, parameter2_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_drawn_{};
  bool drawn_ = false;
  RunControl control_;
};

}  // namespace impactkit::cli
