#include "impactkit/io/class_colors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace impactkit {
namespace {

struct FixedColor {
  MotionKind kind;
  int p;  ///< 0 for sticking and for the kinds without a period
  int q;
  const char* color;
};

/// Kelly's colours of maximum contrast and a few of Tol's, assigned to the
/// classes in order of how often the paper's maps hold them.
constexpr std::array<FixedColor, 21> kFixed = {{
    {MotionKind::kPeriodic, 1, 1, "#0067a5"},     {MotionKind::kPeriodic, 1, 2, "#e68fac"},
    {MotionKind::kSticking, 0, 1, "#875692"},     {MotionKind::kPeriodic, 2, 1, "#008856"},
    {MotionKind::kPeriodic, 2, 2, "#f3c300"},     {MotionKind::kPeriodic, 3, 1, "#a1caf1"},
    {MotionKind::kPeriodic, 4, 1, "#be0032"},     {MotionKind::kPeriodic, 3, 2, "#f38400"},
    {MotionKind::kPeriodic, 4, 4, "#c2b280"},     {MotionKind::kPeriodic, 5, 1, "#00a6a6"},
    {MotionKind::kPeriodic, 6, 1, "#8db600"},     {MotionKind::kPeriodic, 7, 1, "#882d17"},
    {MotionKind::kPeriodic, 2, 4, "#f99379"},     {MotionKind::kPeriodic, 3, 3, "#2b3d26"},
    {MotionKind::kPeriodic, 4, 2, "#b3446c"},     {MotionKind::kSticking, 0, 2, "#654522"},
    {MotionKind::kPeriodic, 2, 3, "#ff4fd8"},     {MotionKind::kPeriodic, 8, 1, "#3a3aff"},
    {MotionKind::kNonImpacting, 0, 0, "#f2f2f2"}, {MotionKind::kChaotic, 0, 0, "#000000"},
    {MotionKind::kUnresolved, 0, 0, "#707070"},
}};

std::string Hex(double r, double g, double b) {
  auto channel = [](double c) {
    return static_cast<int>(std::lround(255.0 * std::clamp(c, 0.0, 1.0)));
  };
  return fmt::format("#{:02x}{:02x}{:02x}", channel(r), channel(g), channel(b));
}

/// A colour of hue `hue` in [0, 6) (HSL's sectors), chroma 0.6, lightness
/// `light`.
std::string FromHue(double hue, double light) {
  const double chroma = 0.6, x = chroma * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0));
  const std::array<std::array<double, 3>, 6> rgb = {{{chroma, x, 0},
                                                     {x, chroma, 0},
                                                     {0, chroma, x},
                                                     {0, x, chroma},
                                                     {x, 0, chroma},
                                                     {chroma, 0, x}}};
  const auto& c = rgb[static_cast<int>(hue) % 6];
  const double m = light - chroma / 2;
  return Hex(c[0] + m, c[1] + m, c[2] + m);
}

/// The channels of "#rrggbb" in [0, 1].
std::array<double, 3> Channels(const std::string& color) {
  std::array<double, 3> c{};
  for (int i = 0; i < 3; ++i) c[i] = std::stoi(color.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
  return c;
}

/// CIELAB (D65) of "#rrggbb": distances in it are differences as the eye
/// sees them (about 2.3 is just noticeable).
std::array<double, 3> Lab(const std::string& color) {
  std::array<double, 3> linear = Channels(color);
  for (double& c : linear) c = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  const double x = (0.4124 * linear[0] + 0.3576 * linear[1] + 0.1805 * linear[2]) / 0.95047;
  const double y = 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2];
  const double z = (0.0193 * linear[0] + 0.1192 * linear[1] + 0.9505 * linear[2]) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

/// Whether `color` is at least `distance` CIELAB units from every fixed
/// colour.
bool ApartFromFixed(const std::string& color, double distance) {
  const std::array<double, 3> a = Lab(color);
  return std::all_of(kFixed.begin(), kFixed.end(), [&](const FixedColor& f) {
    const std::array<double, 3> b = Lab(f.color);
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) >= distance;
  });
}

/// The colour of a period without a fixed one: its hue a golden angle from
/// that of the next p at the same q (p counts on through the q's, a sticking
/// P(∞,q) as p = 0), so that a cascade P(n,1), P(n+1,1), ... never has two
/// near ones alike, in three lightnesses in turn; moved on along the
/// golden-angle sequence while it is within 15 CIELAB units of a fixed
/// colour, so that no rare period passes for a common one.
std::string GeneratedColor(MotionKind kind, int p, int q) {
  constexpr long kPerQ = 1009;  // more than any p an orbit can have (apps: 1000)
  constexpr std::array<double, 3> kLightness = {0.38, 0.55, 0.72};
  const long start = kPerQ * q + (kind == MotionKind::kSticking ? 0 : p);
  for (long index = start;; index += kPerQ * 64) {
    const double hue = std::fmod(0.618033988749895 * static_cast<double>(index), 1.0) * 6.0;
    const std::string color = FromHue(hue, kLightness[index % 3]);
    if (ApartFromFixed(color, 15.0)) return color;
  }
}

/// `color` mixed with black (odd copies) or white (even copies), a third
/// of the way per step: a shade of the same hue, told apart in a legend.
std::string Shaded(const std::string& color, int copy) {
  const double toward = copy % 2 == 1 ? 0.0 : 1.0;
  const double weight = std::min(0.8, 0.33 * ((copy + 1) / 2));
  std::array<double, 3> c = Channels(color);
  for (double& channel : c) channel += weight * (toward - channel);
  return Hex(c[0], c[1], c[2]);
}

}  // namespace

std::string ClassColor(MotionKind kind, int p, int q, int copy) {
  const bool periodic = kind == MotionKind::kPeriodic, sticking = kind == MotionKind::kSticking;
  const int key_p = periodic ? p : 0, key_q = periodic || sticking ? q : 0;
  const auto fixed = std::find_if(kFixed.begin(), kFixed.end(), [&](const FixedColor& f) {
    return f.kind == kind && f.p == key_p && f.q == key_q;
  });
  const std::string color =
      fixed != kFixed.end() ? fixed->color : GeneratedColor(kind, key_p, key_q);
  return copy > 0 ? Shaded(color, copy) : color;
}

}  // namespace impactkit
