#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/model/modal.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/model/system.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using namespace impactkit;

TEST_CASE("paper system: modal data of Sec. 3", "[model]") {
  const ModalData d = ComputeModalData(PaperSystem());
  // Closed form for E = [[2,-1],[-1,1]]: λ = (3 ∓ √5)/2, ω = √λ.
  const double l1 = (3.0 - std::sqrt(5.0)) / 2.0, l2 = (3.0 + std::sqrt(5.0)) / 2.0;
  CHECK_THAT(d.eigenvalues(0), WithinRel(l1, 1e-12));
  CHECK_THAT(d.eigenvalues(1), WithinRel(l2, 1e-12));
  CHECK_THAT(d.natural_frequencies(0), WithinRel(std::sqrt(l1), 1e-12));
  CHECK_THAT(d.natural_frequencies(1), WithinRel(std::sqrt(l2), 1e-12));
  // The paper's printed values (3 digits) and ζ_j = (c/2) sqrt(λ_j / (k m)).
  CHECK_THAT(d.eigenvalues(0), WithinAbs(0.382, 5e-4));
  CHECK_THAT(d.natural_frequencies(1), WithinAbs(1.618, 5e-4));
  CHECK_THAT(d.mode_shapes(0, 0), WithinAbs(0.526, 5e-4));
  CHECK_THAT(d.mode_shapes(1, 0), WithinAbs(0.851, 5e-4));
  CHECK_THAT(d.mode_shapes(0, 1), WithinAbs(-0.851, 5e-4));
  CHECK_THAT(d.mode_shapes(1, 1), WithinAbs(0.526, 5e-4));
  CHECK_THAT(d.damping_ratios(0), WithinRel(0.05 * std::sqrt(l1), 1e-12));
  CHECK_THAT(d.damping_ratios(1), WithinRel(0.05 * std::sqrt(l2), 1e-12));
  CHECK(d.proportional);
}

TEST_CASE("uniform chain matrices", "[model]") {
  const System s = UniformChain({3, 2.0, 5.0, 0.3}, Eigen::Vector3d(1, 0, 0), 1.2, 0.2, 0.5);
  Eigen::Matrix3d e;
  e << 2, -1, 0, -1, 2, -1, 0, -1, 1;
  CHECK(s.mass.isApprox(2.0 * Eigen::Matrix3d::Identity()));
  CHECK(s.stiffness.isApprox(5.0 * e));
  CHECK(s.damping.isApprox(0.3 * e));
  CHECK(s.stops[0].dof == 2);
}

TEST_CASE("named parameters round-trip and rebuild the chain", "[model]") {
  System s = PaperSystem();
  for (const auto& name : ParameterNames(s)) {
    const double value = GetParameter(s, name) + (name == "n" ? 1.0 : 0.125);
    SetParameter(s, name, value);
    CHECK(GetParameter(s, name) == value);
  }
  CHECK(s.Dof() == 3);
  CHECK(s.forcing.size() == 3);
  CHECK(s.stiffness(0, 0) == 2.0 * s.chain->stiffness);
}

namespace {
void CheckRejected(const System& s, const std::string& fragment) {
  try {
    Validate(s);
    FAIL("accepted a system that should be rejected: " << fragment);
  } catch (const InvalidInput& e) {
    CHECK_THAT(e.what(), Contains(fragment));
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
}
}  // namespace

TEST_CASE("validation names the bad parameter and the allowed range", "[model]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  System s = PaperSystem();
  SECTION("non-positive mass") {
    SetParameter(s, "m", 0.0);
    CheckRejected(s, "m (mass) must be finite and > 0");
  }
  SECTION("restitution outside [0, 1]") {
    SetParameter(s, "r", 1.5);
    CheckRejected(s, "r (coefficient of restitution) must be in [0, 1]");
  }
  SECTION("NaN") {
    SetParameter(s, "A1", nan);
    CheckRejected(s, "A (forcing) has a NaN");
  }
  SECTION("infinite omega") {
    SetParameter(s, "omega", std::numeric_limits<double>::infinity());
    CheckRejected(s, "omega (forcing frequency) must be finite and > 0");
  }
  SECTION("wrong vector length") {
    s.forcing = Eigen::Vector3d(1, 2, 3);
    CheckRejected(s, "A (forcing) must have N = 2 entries, got 3");
  }
  SECTION("non-symmetric matrix") {
    s.stiffness(0, 1) = 0.0;
    CheckRejected(s, "K (stiffness matrix) must be symmetric");
  }
  SECTION("undamped system forced at resonance") {
    SetParameter(s, "c", 0.0);
    SetParameter(s, "omega", std::sqrt((3.0 - std::sqrt(5.0)) / 2.0));
    CheckRejected(s, "no bounded steady response");
  }
  SECTION("undamped stuck subsystem forced at its resonance") {
    // Mass 2 held: x1'' + 2 x1 = ..., natural frequency sqrt(2).
    SetParameter(s, "c", 0.0);
    SetParameter(s, "omega", std::sqrt(2.0));
    CheckRejected(s, "stuck subsystem (mass 2 held at the stop): undamped mode");
  }
}

TEST_CASE("scales are validated before any computing, naming the parameter", "[model]") {
  // The issue's inputs: each used to fail later with "the initial state has
  // a NaN", "repeated (defective) eigenvalue", a hang, or inf in a series.
  System s = PaperSystem();
  SECTION("m = 1e308") {
    SetParameter(s, "m", 1e308);
    CheckRejected(s, "m (mass) must be within 1e-150 … 1e+150 in magnitude, got 1e+308");
  }
  SECTION("m = 1e-308") {
    SetParameter(s, "m", 1e-308);
    CheckRejected(s, "m (mass) must be within 1e-150 … 1e+150 in magnitude, got 1e-308");
  }
  SECTION("k = 1e-308") {
    SetParameter(s, "k", 1e-308);
    CheckRejected(s, "k (stiffness) must be within");
  }
  SECTION("A2 = 1e308") {
    SetParameter(s, "A2", 1e308);
    CheckRejected(s, "every entry of A (forcing) must be at most 1e+150 in magnitude, got 1e+308");
  }
  SECTION("omega = 1e-300 and 5e-324") {
    SetParameter(s, "omega", 1e-300);
    CheckRejected(s, "omega (forcing frequency) must be within 1e-150 … 1e+150");
    SetParameter(s, "omega", 5e-324);
    CheckRejected(s, "omega (forcing frequency) must be within 1e-150 … 1e+150");
  }
  SECTION("omega far below the fastest mode") {
    // The paper's fastest mode: ω² = (3 + √5)/2, ω = 1.618...
    SetParameter(s, "omega", 1e-8);
    CheckRejected(s,
                  "omega = 1e-08 is too slow for this system: one forcing period spans 1.62e+08 "
                  "periods of its fastest mode");
    SetParameter(s, "omega", 1.7e-6);  // just inside: 1.618 / 1e6 = 1.618e-6
    CHECK_NOTHROW(Validate(s));
  }
  SECTION("natural frequencies spread beyond 1e5") {
    s = GeneralSystem(Eigen::Vector2d(1.0, 1.0).asDiagonal(), Eigen::Matrix2d::Zero(),
                      Eigen::Vector2d(1.0, 1e11).asDiagonal(), Eigen::Vector2d(0.5, 0.0), 1.0, 0.1,
                      0.7);
    CheckRejected(s,
                  "give natural frequencies from 1 to 316228, a ratio of 3.16e+05; at most 1e+05");
  }
  SECTION("a forced response beyond 1e150") {
    SetParameter(s, "A1", 1e149);
    SetParameter(s, "c", 1e-3);
    SetParameter(s, "omega", std::sqrt((3.0 - std::sqrt(5.0)) / 2.0));  // at resonance
    CheckRejected(s, "A (forcing) gives a forced response of amplitude");
  }
  SECTION("an undamped mode forced within 1e-16 … 1e-8 of its frequency") {
    // The hang (Ω = 0.6180339887505129, c = 0). Its amplification
    // ω² / |ω² − Ω²| is closed form: refused above 1e6 (relative distance
    // below ~5e-7), accepted below.
    SetParameter(s, "c", 0.0);
    const double omega1 = std::sqrt((3.0 - std::sqrt(5.0)) / 2.0);
    for (const double offset : {1e-16, 1e-12, 1e-8, 1e-7}) {
      INFO("offset " << offset);
      SetParameter(s, "omega", omega1 * (1 + offset));
      CHECK_THROWS_AS(Validate(s), InvalidInput);
    }
    SetParameter(s, "omega", omega1 * (1 + 1e-6));  // amplification 1 / (2e-6) = 5e5
    CHECK_NOTHROW(Validate(s));
    SetParameter(s, "omega", omega1 * (1 + 1e-7));
    CheckRejected(s, "so near resonance that it amplifies the forcing 5e+06 times (at most 1e+06)");
  }
  SECTION("more than 1000 masses in general matrices") {
    const int n = kMaxDegreesOfFreedom + 1;
    s = GeneralSystem(Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Zero(n, n),
                      Eigen::MatrixXd::Identity(n, n), Eigen::VectorXd::Zero(n), 1.5, 0.1, 0.7);
    CheckRejected(s, "the system has N = 1001 masses; at most 1000");
  }
  SECTION("tiny entries that only underflow are fine") {
    SetParameter(s, "A2", 1e-300);
    SetParameter(s, "c", 1e-200);
    SetParameter(s, "xs", 1e-300);
    CHECK_NOTHROW(Validate(s));
  }
}

TEST_CASE("undamped but forced off resonance, or resonance of an unforced mode, is fine",
          "[model]") {
  System s = PaperSystem(0.9);
  SetParameter(s, "c", 0.0);
  CHECK_NOTHROW(Validate(s));
}

TEST_CASE("initial state checks", "[model]") {
  const System s = PaperSystem();
  HybridState state = RestState(s);
  CHECK_NOTHROW(ValidateState(s, state));
  state.x(1) = 0.5;
  CHECK_THROWS_WITH(ValidateState(s, state), Contains("beyond the stop"));
  state = RestState(s);
  state.v.resize(3);
  CHECK_THROWS_WITH(ValidateState(s, state), Contains("2 velocities"));
  state = RestState(s);
  state.v(0) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(ValidateState(s, state), Contains("NaN"));
}

TEST_CASE("the parameter table names every parameter once, with its meaning", "[model]") {
  const System chain = PaperSystem();
  const System general =
      GeneralSystem(chain.mass, chain.damping, chain.stiffness, chain.forcing, 1.0, 0.1, 0.7);
  CHECK(ParameterNames(chain) ==
        std::vector<std::string>{"omega", "xs", "r", "A1", "A2", "m", "k", "c", "n"});
  CHECK(ParameterNames(general) == std::vector<std::string>{"omega", "xs", "r", "A1", "A2"});
  for (const ParameterSpec& spec : ParameterTable()) {
    CHECK_FALSE(spec.meaning.empty());
    CHECK_FALSE(spec.range.empty());
    CHECK((spec.get == nullptr) == (spec.set == nullptr));
  }
  REQUIRE(FindParameter(chain, "A2") != nullptr);
  CHECK(FindParameter(chain, "A2")->name == "A");
  CHECK(FindParameter(chain, "A3") == nullptr);
  CHECK(FindParameter(general, "m") == nullptr);
  CHECK_THROWS_WITH(GetParameter(general, "m"), Contains("unknown parameter 'm'"));
}

TEST_CASE("the forcing phase is fmod's exact remainder, at every scale of t", "[model]") {
  // System::Phase takes t - floor(t/T) T by one fused multiply-add and falls
  // back on fmod where t/T rounds across an integer: both exact, so the two
  // must agree bit for bit, including at multiples of T and just beside them.
  std::mt19937_64 random(7);
  for (const double omega : {0.6, 1.4, 1.75, std::numbers::pi, 0.1}) {
    System system = PaperSystem(omega);
    const double period = system.ForcingPeriod();
    std::uniform_real_distribution<double> exponent(-3.0, 7.0);
    for (int i = 0; i < 20000; ++i) {
      double t = std::pow(10.0, exponent(random));
      if (i % 4 == 1) t = std::round(t / period) * period;  // on a multiple of T
      if (i % 4 == 2) t = std::nextafter(std::round(t / period) * period, 0.0);
      if (i % 4 == 3) t = -t;
      const double remainder = std::fmod(t, period);
      const double expected = remainder < 0 ? remainder + period : remainder;
      REQUIRE(system.Phase(t) == expected);
    }
  }
}

TEST_CASE("a parameter resolved once gets and sets what its name does", "[model]") {
  // Every name of a three-mass chain with a second stop: the resolved
  // parameter reads the value GetParameter reads, and setting it changes
  // exactly what SetParameter would.
  System system = UniformChain({3, 1.0, 1.0, 0.1}, Eigen::Vector3d(0.5, 0.0, 0.25), 1.2, 0.1, 0.7);
  system.stops.push_back({0, StopSide::kLower, -0.3, 0.6});
  const auto same = [](const System& a, const System& b) {
    return a.mass == b.mass && a.damping == b.damping && a.stiffness == b.stiffness &&
           a.forcing == b.forcing && a.omega == b.omega && a.stops == b.stops;
  };
  for (const std::string& name : ParameterNames(system)) {
    INFO(name);
    const NamedParameter parameter(system, name);
    CHECK(parameter.Name() == name);
    CHECK(parameter.Get(system) == GetParameter(system, name));
    const double value = name == "n" ? 2.0 : GetParameter(system, name) * 0.75 + 0.0625;
    System by_name = system, resolved = system;
    SetParameter(by_name, name, value);
    parameter.Set(resolved, value);
    CHECK(same(by_name, resolved));
  }
  CHECK_THROWS_WITH(NamedParameter(system, "A4"), Contains("unknown parameter 'A4'"));
  // Resolved while the chain had three masses: A3 is gone once n is 2.
  const NamedParameter a3(system, "A3");
  SetParameter(system, "n", 2);
  CHECK_THROWS_WITH(a3.Set(system, 1.0), Contains("A3: the system has 2 masses"));
}
