#include "impactkit/continuation/test_functions.hpp"

#include <cmath>
#include <limits>

namespace impactkit {
namespace {

double FoldTest(const Eigen::MatrixXd& dp, const Eigen::VectorXcd&) {
  return (dp - Eigen::MatrixXd::Identity(dp.rows(), dp.cols())).determinant();
}

double PeriodDoublingTest(const Eigen::MatrixXd& dp, const Eigen::VectorXcd&) {
  return (dp + Eigen::MatrixXd::Identity(dp.rows(), dp.cols())).determinant();
}

/// Π_{i<j} (λ_i λ_j - 1): zero when two multipliers have product 1, which
/// for a complex pair means |λ| = 1. Real for a real matrix (the factors
/// come in conjugate pairs); the rounding in the imaginary part is dropped.
double NeimarkSackerTest(const Eigen::MatrixXd&, const Eigen::VectorXcd& lambda) {
  std::complex<double> product = 1.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    for (Eigen::Index j = i + 1; j < lambda.size(); ++j) product *= lambda(i) * lambda(j) - 1.0;
  }
  return product.real();
}

constexpr double kAny = std::numeric_limits<double>::infinity();

/// det(D P ∓ I) also changes sign where a multiplier passes through
/// infinity rather than ±1: an impact of a long orbit slowing to a graze
/// makes D P's saltation terms (1/v) blow up. A located zero is a fold or a
/// period doubling only with a multiplier this close to ±1. A genuine one,
/// bracketed or solved directly (continuation.cpp), lands within ~1e-9 (the
/// rounding of a long orbit's D P); a pole leaves the nearest multiplier
/// anywhere.
constexpr double kRealCrossing = 1e-7;

constexpr std::array<TestFunction, kBifurcationTestCount> kTests = {{
    {SpecialPointType::kFold, FoldTest, [](std::complex<double> l) { return std::abs(l - 1.0); },
     kRealCrossing, 1.0, false},
    {SpecialPointType::kPeriodDoubling, PeriodDoublingTest,
     [](std::complex<double> l) { return std::abs(l + 1.0); }, kRealCrossing, -1.0, true},
    {SpecialPointType::kNeimarkSacker, NeimarkSackerTest,
     [](std::complex<double> l) { return l.imag() > 0 ? std::abs(std::abs(l) - 1.0) : kAny; }, 1e-4,
     std::nullopt, false},
}};

constexpr std::array<std::pair<SpecialPointType, std::string_view>, 10> kNames = {{
    {SpecialPointType::kFold, "fold"},
    {SpecialPointType::kPeriodDoubling, "period_doubling"},
    {SpecialPointType::kNeimarkSacker, "neimark_sacker"},
    {SpecialPointType::kGrazing, "grazing"},
    {SpecialPointType::kSticking, "sticking"},
    {SpecialPointType::kBranchPoint, "branch_point"},
    {SpecialPointType::kPitchfork, "pitchfork"},
    {SpecialPointType::kNoSticking, "no_sticking"},
    {SpecialPointType::kEarlyRelease, "early_release"},
    {SpecialPointType::kUserTest, "user_test"},
}};

}  // namespace

std::string ToString(SpecialPointType type) {
  for (const auto& [known, name] : kNames) {
    if (known == type) return std::string(name);
  }
  return "unknown";
}

std::optional<SpecialPointType> SpecialPointTypeFromName(std::string_view name) {
  for (const auto& [type, known] : kNames) {
    if (known == name) return type;
  }
  return std::nullopt;
}

const std::array<TestFunction, kBifurcationTestCount>& BifurcationTests() { return kTests; }

int TestIndex(SpecialPointType type) {
  for (std::size_t i = 0; i < kTests.size(); ++i) {
    if (kTests[i].type == type) return static_cast<int>(i);
  }
  return -1;
}

const TestFunction* TestFunctionOf(SpecialPointType type) {
  const int index = TestIndex(type);
  return index < 0 ? nullptr : &kTests[index];
}

std::array<double, kBifurcationTestCount> EvaluateBifurcationTests(
    const Eigen::MatrixXd& jacobian, const Eigen::VectorXcd& multipliers) {
  std::array<double, kBifurcationTestCount> values;
  for (std::size_t i = 0; i < kTests.size(); ++i)
    values[i] = kTests[i].value(jacobian, multipliers);
  return values;
}

}  // namespace impactkit
