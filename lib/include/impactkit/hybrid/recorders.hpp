#pragma once
/// \file recorders.hpp
/// Observers that record what users ask of a simulation. Each records
/// everything it is shown: run the transient without them.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "impactkit/hybrid/record_log.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit {

/// Forwards every call to several observers, in order.
class ObserverList : public Observer {
 public:
  void Add(Observer& observer) { observers_.push_back(&observer); }
  void OnSegment(const Segment& segment) override;
  void OnImpact(const Impact& impact) override;
  void OnChatter(const ChatterEnd& chatter) override;
  void OnLanding(const Landing& landing) override;
  void OnRelease(const Release& release) override;
  bool ShouldStop() const override;

 private:
  std::vector<Observer*> observers_;
};

/// What a sample is: a point of the time grid, or an event's state.
enum class SampleKind {
  kGrid,          ///< at t_first + k dt
  kBeforeImpact,  ///< at an impact, the speed before it (x_c = xs, v_c > 0)
  kAfterImpact,   ///< at the same instant, the speed after it (v_c = -r v before)
  kStick,         ///< sticking begins (x_c = xs, v_c = 0)
  kRelease,       ///< the contact mass leaves the stop
};

/// "grid", "impact_before", "impact_after", "stick", "release".
const char* ToString(SampleKind kind);

/// One sample of the motion.
struct Sample {
  double t = 0.0;
  Eigen::VectorXd x;
  Eigen::VectorXd v;
  bool stuck = false;
  SampleKind kind = SampleKind::kGrid;
};

/// A recorded sample (record_log.hpp): Sample's fields, the vectors mapped.
struct SampleView {
  double t;
  Eigen::Map<const Eigen::VectorXd> x;
  Eigen::Map<const Eigen::VectorXd> v;
  bool stuck;
  SampleKind kind;
  Sample Owned() const { return Sample{t, x, v, stuck, kind}; }
};

template <>
struct RecordLayout<Sample> {
  struct Scalars {
    double t;
    bool stuck;
    SampleKind kind;
  };
  using View = SampleView;
  static constexpr int kVectors = 2;
  static Scalars ScalarsOf(const Sample& s) { return {s.t, s.stuck, s.kind}; }
  static std::array<const Eigen::VectorXd*, 2> VectorsOf(const Sample& s) { return {&s.x, &s.v}; }
  static View MakeView(const Scalars& s, const double* vectors, Eigen::Index n) {
    return {s.t, {vectors, n}, {vectors + n, n}, s.stuck, s.kind};
  }
};

/// Samples stored flat (record_log.hpp).
using SampleLog = RecordLog<Sample>;

/// A recorded impact (record_log.hpp): Impact's fields, the vectors mapped.
struct ImpactView {
  double t;
  int stop;
  double phase;
  double velocity;
  Eigen::Map<const Eigen::VectorXd> x;
  Eigen::Map<const Eigen::VectorXd> v;
  Eigen::Map<const Eigen::VectorXd> v_after;
  Impact Owned() const { return Impact{t, stop, phase, velocity, x, v, v_after}; }
};

template <>
struct RecordLayout<Impact> {
  struct Scalars {
    double t;
    int stop;
    double phase;
    double velocity;
  };
  using View = ImpactView;
  static constexpr int kVectors = 3;
  static Scalars ScalarsOf(const Impact& i) { return {i.t, i.stop, i.phase, i.velocity}; }
  static std::array<const Eigen::VectorXd*, 3> VectorsOf(const Impact& i) {
    return {&i.x, &i.v, &i.v_after};
  }
  static View MakeView(const Scalars& s, const double* vectors, Eigen::Index n) {
    return {s.t, s.stop, s.phase, s.velocity, {vectors, n}, {vectors + n, n}, {vectors + 2 * n, n}};
  }
};

/// Impacts stored flat (record_log.hpp).
using ImpactLog = RecordLog<Impact>;

/// Samples at t = t_first + k dt (k = 0, 1, ...) that fall inside segments
/// and, with `events`, every event from t_first on as samples of its own,
/// in time order: each impact twice (the state before and after it, at one
/// instant), the start of sticking and the release. A curve through the
/// samples then reaches the stop at every impact and jumps in velocity there
/// instead of drawing a slope between two grid points.
class TimeSeriesRecorder : public Observer {
 public:
  TimeSeriesRecorder(double t_first, double dt, bool events = false);
  void OnSegment(const Segment& segment) override;
  void OnImpact(const Impact& impact) override;
  const SampleLog& Samples() const { return samples_; }
  /// Room for `samples` samples (RecordLog::reserve).
  void Reserve(std::size_t samples) { samples_.reserve(samples); }

 private:
  /// The sticking or release, if any, that the segment's first instant is.
  void AddEventAtBegin(const Segment& segment);
  /// The segment's state at t, recorded.
  void AddState(const Segment& segment, double t, SampleKind kind);

  double t_first_;
  double dt_;
  bool events_;
  long next_ = 0;
  std::optional<SegmentMode> last_mode_;
  Sample scratch_;  ///< the sample being recorded (its vectors' storage reused)
  SampleLog samples_;
};

/// Every impact.
class ImpactRecorder : public Observer {
 public:
  void OnImpact(const Impact& impact) override { impacts_.push_back(impact); }
  const ImpactLog& Impacts() const { return impacts_; }
  /// Room for `impacts` impacts (RecordLog::reserve).
  void Reserve(std::size_t impacts) { impacts_.reserve(impacts); }

 private:
  ImpactLog impacts_;
};

/// The state once per forcing period, at t = k T (forcing phase 0).
class StroboscopicRecorder : public Observer {
 public:
  explicit StroboscopicRecorder(double period) : sampler_(0.0, period) {}
  void OnSegment(const Segment& segment) override { sampler_.OnSegment(segment); }
  const SampleLog& Points() const { return sampler_.Samples(); }
  /// Room for `points` points (RecordLog::reserve).
  void Reserve(std::size_t points) { sampler_.Reserve(points); }

 private:
  TimeSeriesRecorder sampler_;
};

/// Max and min of every x_i over one forcing period [k T, (k+1) T).
struct PeriodExtrema {
  long period = 0;  ///< k
  Eigen::VectorXd max;
  Eigen::VectorXd min;
};

/// Exact per-period extrema of every x_i: in each segment the interior
/// extrema are the zeros of v_i, found like events (events.hpp).
class ExtremaRecorder : public Observer {
 public:
  explicit ExtremaRecorder(double period) : period_(period) {}
  void OnSegment(const Segment& segment) override;
  /// Periods seen whole (the first and last may be partial and are left out).
  std::vector<PeriodExtrema> CompletePeriods() const;

 private:
  void Include(long period, int i, double value);
  double period_;
  int max_dof_ = 0;
  double first_time_ = 0.0;
  double last_time_ = 0.0;
  bool any_ = false;
  std::vector<PeriodExtrema> periods_;
};

/// The times at which chatter sequences ended at the stop (what
/// DetectPeriod needs to call a motion sticking).
class ChatterRecorder : public Observer {
 public:
  void OnChatter(const ChatterEnd& chatter) override { end_times_.push_back(chatter.t_end); }
  const std::vector<double>& EndTimes() const { return end_times_; }

 private:
  std::vector<double> end_times_;
};

/// An interval during which the contact mass is at the stop (after chatter).
struct StickingInterval {
  double begin = 0.0;
  double end = 0.0;
};

/// Sticking intervals, from the impact that starts a completed chatter
/// sequence (its accumulated tail is simulated as held at the stop) or the
/// impact with r = 0, to release. An interval still open at the end of the
/// run ends there. TotalTime() equals SimulationSummary::stuck_time.
class StickingRecorder : public Observer {
 public:
  void OnSegment(const Segment& segment) override;
  const std::vector<StickingInterval>& Intervals() const { return intervals_; }
  double TotalTime() const;

 private:
  std::vector<StickingInterval> intervals_;
  bool open_ = false;
};

}  // namespace impactkit
