#include "continuation/curve_tests.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace impactkit::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// A resonance 1:1 or 1:2 has a double multiplier ±1; the eigensolver
/// splits a Jordan pair by ~sqrt(machine epsilon) only, far below this.
constexpr double kDoubleMultiplier = 1e-3;
/// A cusp: the tangent's parameter part (of a unit tangent in X) vanishes
/// there; a sharp turn of the curve keeps it well above this.
constexpr double kCuspTangent = 1e-3;

/// The value of the test function of `type` at a curve point.
template <SpecialPointType type>
double TestValue(const CurvePoint& point, const CurvePoint&) {
  return point.test_values[TestIndex(type)];
}
constexpr auto Fold = TestValue<SpecialPointType::kFold>;
constexpr auto Flip = TestValue<SpecialPointType::kPeriodDoubling>;
constexpr auto Torus = TestValue<SpecialPointType::kNeimarkSacker>;

/// A grazing curve's GrazingLimit(±1): which curve leaves at its zero.
template <int index>
double GrazingLimit(const CurvePoint& point, const CurvePoint&) {
  return point.grazing_limits[index];
}
constexpr auto FoldLeaves = GrazingLimit<0>;
constexpr auto FlipLeaves = GrazingLimit<1>;

/// The critical pair's e^{iθ}: the multiplier with θ in (0, π) nearest the
/// unit circle; none when every multiplier is real.
std::optional<std::complex<double>> CriticalPair(const CurvePoint& point) {
  std::optional<std::complex<double>> best;
  for (const std::complex<double>& l : point.orbit.multipliers) {
    if (!(l.imag() > 0)) continue;
    if (!best || std::abs(std::abs(l) - 1.0) < std::abs(std::abs(*best) - 1.0)) best = l;
  }
  return best;
}

/// cos θ − cos(2π/3) and cos θ: zero at the 1:3 and 1:4 resonances.
double Third(const CurvePoint& point, const CurvePoint&) {
  const auto l = CriticalPair(point);
  return l ? std::cos(std::arg(*l)) + 0.5 : kNaN;
}
double Quarter(const CurvePoint& point, const CurvePoint&) {
  const auto l = CriticalPair(point);
  return l ? std::cos(std::arg(*l)) : kNaN;
}

/// The tangent's (μ1, μ2) part projected on the reference's: it changes
/// sign where the curve's projection reverses, at a cusp.
double CuspTest(const CurvePoint& point, const CurvePoint& reference) {
  const Eigen::Vector2d here = point.tangent.tail(2), there = reference.tangent.tail(2);
  return there.norm() > 0 ? here.dot(there.normalized()) : kNaN;
}

int MultipliersNear(const CurvePoint& point, double target) {
  int count = 0;
  for (const std::complex<double>& l : point.orbit.multipliers) {
    if (std::abs(l - target) < kDoubleMultiplier) ++count;
  }
  return count;
}

bool Any(const CurvePoint&) { return true; }
bool DoublePlusOne(const CurvePoint& point) { return MultipliersNear(point, 1.0) >= 2; }
bool DoubleMinusOne(const CurvePoint& point) { return MultipliersNear(point, -1.0) >= 2; }
bool OnUnitCircle(const CurvePoint& point) {
  const auto l = CriticalPair(point);
  const TestFunction& torus = *TestFunctionOf(SpecialPointType::kNeimarkSacker);
  return l && torus.distance(*l) <= torus.max_distance;
}
bool Cusp(const CurvePoint& point) { return point.tangent.tail(2).norm() < kCuspTangent; }

}  // namespace

std::vector<SecondTest> SecondTests(SpecialPointType type) {
  switch (type) {
    case SpecialPointType::kFold:
      return {{Codim2Type::kFoldFlip, Flip, Any},
              {Codim2Type::kResonance11, Torus, DoublePlusOne},
              {Codim2Type::kCusp, CuspTest, Cusp}};
    case SpecialPointType::kPeriodDoubling:
      return {{Codim2Type::kFoldFlip, Fold, Any},
              {Codim2Type::kResonance12, Torus, DoubleMinusOne}};
    case SpecialPointType::kNeimarkSacker:
      return {{Codim2Type::kResonance11, Fold, Any},
              {Codim2Type::kResonance12, Flip, Any},
              {Codim2Type::kResonance13, Third, OnUnitCircle},
              {Codim2Type::kResonance14, Quarter, OnUnitCircle}};
    default:
      return {{Codim2Type::kFoldGrazing, Fold, Any},
              {Codim2Type::kPeriodDoublingGrazing, Flip, Any},
              {Codim2Type::kNeimarkSackerGrazing, Torus, OnUnitCircle},
              {Codim2Type::kResonantGrazingFold, FoldLeaves, Any},
              {Codim2Type::kResonantGrazingPeriodDoubling, FlipLeaves, Any}};
  }
}

Codim2Type GrazingMeeting(SpecialPointType type) {
  switch (type) {
    case SpecialPointType::kFold:
      return Codim2Type::kFoldGrazing;
    case SpecialPointType::kPeriodDoubling:
      return Codim2Type::kPeriodDoublingGrazing;
    case SpecialPointType::kNeimarkSacker:
      return Codim2Type::kNeimarkSackerGrazing;
    default:
      return Codim2Type::kDoubleGrazing;
  }
}

std::optional<double> PointMonitor(const CurvePoint& point, Monitor monitor) {
  if (point.orbit.multipliers.size() == 0) return std::nullopt;
  return LinearMonitor(point.orbit, monitor, point.defining.size() == 2);
}

}  // namespace impactkit::detail
