#include "common/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
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

RunProgress::RunProgress(std::string parameter, std::string parameter2)
    : enabled_(::isatty(STDERR_FILENO) == 1),
      parameter_(std::move(parameter)),
      parameter2_(std::move(parameter2)),
      control_([this](const Progress& progress) { Draw(progress); }) {}

RunProgress::~RunProgress() {
  if (drawn_) fmt::print(stderr, "\r\033[K");
}

void RunProgress::Draw(const Progress& progress) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  const bool last = progress.total > 0 && progress.done == progress.total;
  if (now - start_ < kQuietPeriod || (now - last_drawn_ < kRedrawInterval && !last)) return;
  fmt::print(stderr, "\r\033[Kimpactkit: {}", Text(progress));
  last_drawn_ = now;
  drawn_ = true;
}

std::string RunProgress::Text(const Progress& progress) const {
  std::string text =
      progress.total > 0
          ? fmt::format("{} of {} {:3.0f}% ({} of {} values)", progress.stage, parameter_,
                        100.0 * static_cast<double>(progress.done) / progress.total, progress.done,
                        progress.total)
          : fmt::format("{}: {} {}", progress.stage, progress.done,
                        progress.stage == "diagram" ? "branches done" : "points");
  if (std::isfinite(progress.parameter)) {
    text += fmt::format(", {} = {:.8g}", parameter_, progress.parameter);
  }
  if (std::isfinite(progress.parameter2)) {
    text += fmt::format(", {} = {:.8g}", parameter2_, progress.parameter2);
  }
  return text;
}

}  // namespace impactkit::cli
