#pragma once
/// \file run_control.hpp
/// Progress reports and cancellation for the library's long runs — sweeps,
/// branches, curves, diagrams — in one object the caller passes last:
/// `Result Run(problem, options, control)`.

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <string_view>

namespace impactkit {

/// How far a run is, after each unit of its work.
struct Progress {
  /// What runs: "sweep" (units: parameter values), "branch" or "curve"
  /// (points), "diagram" (branches finished).
  std::string_view stage;
  std::int64_t done = 0;
  /// Units the run is asked for; 0 when not known ahead (a branch's points).
  std::int64_t total = 0;
  /// Where the run is: the parameter value of its latest point (NaN for a
  /// sweep, whose values finish out of order), and a curve's second
  /// parameter (NaN otherwise).
  double parameter = std::numeric_limits<double>::quiet_NaN();
  double parameter2 = std::numeric_limits<double>::quiet_NaN();
};

/// Reports are serialised (never concurrent) but may come from any worker
/// thread. Cancel() may be called from any thread, the progress callback
/// included; the run then stops at its next unit (a sweep: at the end of the
/// chunks running) and returns what it has, its termination kStopped.
class RunControl {
 public:
  using ProgressCallback = std::function<void(const Progress&)>;

  RunControl() = default;
  explicit RunControl(ProgressCallback on_progress) : on_progress_(std::move(on_progress)) {}
  /// A control for a run inside another (a diagram's branches): it reports
  /// to `on_progress` and is cancelled when `outer` is.
  RunControl(ProgressCallback on_progress, const RunControl& outer)
      : on_progress_(std::move(on_progress)), outer_(&outer) {}
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  void Report(const Progress& progress) const {
    if (!on_progress_) return;
    const std::lock_guard<std::mutex> lock(report_mutex_);
    on_progress_(progress);
  }
  void Cancel() const { cancelled_ = true; }
  bool Cancelled() const { return cancelled_ || (outer_ != nullptr && outer_->Cancelled()); }

 private:
  ProgressCallback on_progress_;
  const RunControl* outer_ = nullptr;
  mutable std::mutex report_mutex_;
  mutable std::atomic<bool> cancelled_{false};
};

}  // namespace impactkit
