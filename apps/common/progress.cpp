#include "common/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

#include "impactkit/dynamics/segment.hpp"

namespace impactkit::cli {
namespace {

constexpr auto kQuietPeriod = std::chrono::seconds(1);  ///< no line for shorter runs
constexpr auto kRedrawInterval = std::chrono::milliseconds(200);

}  // namespace

ProgressLine::ProgressLine(std::string label, double t_begin, double t_end, double period)
    : enabled_(::isatty(STDERR_FILENO) == 1 && t_end > t_begin),
      label_(std::move(label)),
      t_begin_(t_begin),
      t_end_(t_end),
      period_(period) {}

ProgressLine::~ProgressLine() {
  if (drawn_) fmt::print(stderr, "\r\033[K");
}

void ProgressLine::OnSegment(const Segment& segment) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  if (now - start_ < kQuietPeriod || now - last_drawn_ < kRedrawInterval) return;
  const double fraction = (segment.End() - t_begin_) / (t_end_ - t_begin_);
  fmt::print(stderr, "\r\033[Kimpactkit: {} {:3.0f}% (forcing period {:.0f} of {:.0f})", label_,
             100.0 * fraction, segment.End() / period_, t_end_ / period_);
  last_drawn_ = now;
  drawn_ = true;
}

StepProgress::StepProgress() : enabled_(::isatty(STDERR_FILENO) == 1) {}

StepProgress::~StepProgress() {
  if (drawn_) fmt::print(stderr, "\r\033[K");
}

bool StepProgress::Due() {
  if (!enabled_) return false;
  const Clock::time_point now = Clock::now();
  return now - start_ >= kQuietPeriod && now - last_drawn_ >= kRedrawInterval;
}

void StepProgress::Draw(const std::string& text) {
  fmt::print(stderr, "\r\033[Kimpactkit: {}", text);
  last_drawn_ = Clock::now();
  drawn_ = true;
}

}  // namespace impactkit::cli
