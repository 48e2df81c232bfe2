#pragma once
/// \file common/progress.hpp
/// A progress line for long simulations, drawn on stderr and rewritten in
/// place. Only for a person watching: silent when stderr is not a terminal
/// (pipes, logs, tests) and for runs that finish within a second.

#include <chrono>
#include <string>

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

/// The same line for work counted in steps of unknown number (points of a
/// continued curve): the caller says what to show.
class StepProgress {
 public:
  StepProgress();
  /// Erases the line.
  ~StepProgress();
  StepProgress(const StepProgress&) = delete;
  StepProgress& operator=(const StepProgress&) = delete;

  /// One more step; `text` (made only when drawn) is shown after "impactkit: ".
  template <typename Text>
  void Step(const Text& text) {
    if (Due()) Draw(text());
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool Due();
  void Draw(const std::string& text);

  const bool enabled_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_drawn_{};
  bool drawn_ = false;
};

}  // namespace impactkit::cli
