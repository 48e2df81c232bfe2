#include "impactkit/hybrid/recorders.hpp"

#include <cmath>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/segment.hpp"

namespace impactkit {

void ObserverList::OnSegment(const Segment& segment) {
  for (Observer* o : observers_) o->OnSegment(segment);
}
void ObserverList::OnImpact(const Impact& impact) {
  for (Observer* o : observers_) o->OnImpact(impact);
}
void ObserverList::OnChatter(const ChatterEnd& chatter) {
  for (Observer* o : observers_) o->OnChatter(chatter);
}
void ObserverList::OnLanding(const Landing& landing) {
  for (Observer* o : observers_) o->OnLanding(landing);
}
void ObserverList::OnRelease(const Release& release) {
  for (Observer* o : observers_) o->OnRelease(release);
}
bool ObserverList::ShouldStop() const {
  for (const Observer* o : observers_) {
    if (o->ShouldStop()) return true;
  }
  return false;
}

const char* ToString(SampleKind kind) {
  switch (kind) {
    case SampleKind::kGrid:
      return "grid";
    case SampleKind::kBeforeImpact:
      return "impact_before";
    case SampleKind::kAfterImpact:
      return "impact_after";
    case SampleKind::kStick:
      return "stick";
    case SampleKind::kRelease:
      return "release";
  }
  return "grid";
}

TimeSeriesRecorder::TimeSeriesRecorder(double t_first, double dt, bool events)
    : t_first_(t_first), dt_(dt), events_(events) {
  if (!(dt > 0 && std::isfinite(dt))) throw InvalidInput("the sampling interval must be > 0");
}

void TimeSeriesRecorder::OnImpact(const Impact& impact) {
  if (!events_ || impact.t < t_first_) return;
  // Through the scratch sample, whose vectors keep their storage.
  scratch_.t = impact.t;
  scratch_.stuck = false;
  scratch_.x = impact.x;
  scratch_.v = impact.v;
  scratch_.kind = SampleKind::kBeforeImpact;
  samples_.push_back(scratch_);
  scratch_.v = impact.v_after;
  scratch_.kind = SampleKind::kAfterImpact;
  samples_.push_back(scratch_);
}

void TimeSeriesRecorder::AddState(const Segment& segment, double t, SampleKind kind) {
  scratch_.t = t;
  scratch_.stuck = segment.Stuck();
  scratch_.kind = kind;
  segment.StateAt(t, &scratch_.x, &scratch_.v);
  samples_.push_back(scratch_);
}

void TimeSeriesRecorder::AddEventAtBegin(const Segment& segment) {
  const SegmentMode mode = segment.Mode();
  // The first segment seen begins no event: it is where recording starts.
  const bool stick =
      mode == SegmentMode::kStuck && last_mode_ && *last_mode_ != SegmentMode::kStuck;
  const bool release = mode != SegmentMode::kStuck && last_mode_ == SegmentMode::kStuck;
  last_mode_ = mode;
  if (!(stick || release) || segment.Begin() < t_first_) return;
  AddState(segment, segment.Begin(), stick ? SampleKind::kStick : SampleKind::kRelease);
}

void TimeSeriesRecorder::OnSegment(const Segment& segment) {
  if (events_) AddEventAtBegin(segment);
  // A grid time that equals Begin() up to rounding belongs to this segment
  // (evaluating the closed form a few ulps outside it is harmless).
  const long first_inside = static_cast<long>(std::ceil((segment.Begin() - t_first_) / dt_ - 1e-9));
  next_ = std::max(next_, first_inside);
  for (double t = t_first_ + next_ * dt_; t <= segment.End(); t = t_first_ + (++next_) * dt_) {
    AddState(segment, t, SampleKind::kGrid);
  }
}

void ExtremaRecorder::Include(long period, int i, double value) {
  if (periods_.empty()) {
    periods_.push_back(PeriodExtrema{period, Eigen::VectorXd::Constant(max_dof_, -INFINITY),
                                     Eigen::VectorXd::Constant(max_dof_, INFINITY)});
  }
  const long first = periods_.front().period;
  if (period < first) return;  // before the first segment: cannot happen
  while (periods_.back().period < period) {
    periods_.push_back(PeriodExtrema{periods_.back().period + 1,
                                     Eigen::VectorXd::Constant(max_dof_, -INFINITY),
                                     Eigen::VectorXd::Constant(max_dof_, INFINITY)});
  }
  PeriodExtrema& e = periods_[period - first];
  e.max(i) = std::max(e.max(i), value);
  e.min(i) = std::min(e.min(i), value);
}

void ExtremaRecorder::OnSegment(const Segment& segment) {
  Eigen::VectorXd x, v;
  segment.StateAt(segment.Begin(), &x, &v);
  max_dof_ = static_cast<int>(x.size());
  if (!any_) first_time_ = segment.Begin();
  any_ = true;
  last_time_ = segment.End();
  const EventOptions options{1e-12, period_};
  for (int i = 0; i < max_dof_; ++i) {
    const Signal position = segment.Position(i);
    std::vector<double> times =
        SignChanges(position.Derivative(), segment.Begin(), segment.End(), options);
    times.push_back(segment.Begin());
    times.push_back(segment.End());
    for (double t : times)
      Include(static_cast<long>(std::floor(t / period_)), i, position.Value(t));
    // A period boundary inside the segment closes one period and opens the next.
    for (long k = static_cast<long>(std::ceil(segment.Begin() / period_));
         k * period_ <= segment.End(); ++k) {
      const double value = position.Value(k * period_);
      Include(k - 1, i, value);
      Include(k, i, value);
    }
  }
}

std::vector<PeriodExtrema> ExtremaRecorder::CompletePeriods() const {
  std::vector<PeriodExtrema> complete;
  for (const PeriodExtrema& e : periods_) {
    if (e.period * period_ >= first_time_ - 1e-9 * period_ &&
        (e.period + 1) * period_ <= last_time_ + 1e-9 * period_) {
      complete.push_back(e);
    }
  }
  return complete;
}

void StickingRecorder::OnSegment(const Segment& segment) {
  if (!segment.Stuck()) {
    open_ = false;
    return;
  }
  if (open_ && intervals_.back().end == segment.Begin()) {
    intervals_.back().end = segment.End();
  } else {
    intervals_.push_back(StickingInterval{segment.Begin(), segment.End()});
    open_ = true;
  }
}

double StickingRecorder::TotalTime() const {
  double total = 0.0;
  for (const StickingInterval& i : intervals_) total += i.end - i.begin;
  return total;
}

}  // namespace impactkit
