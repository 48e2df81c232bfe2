#include "impactkit/model/system.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <numbers>

#include "dynamics/subsystem.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "model/stuck_subsystem.hpp"

namespace impactkit {
namespace {

void RequireFinite(const Eigen::MatrixXd& m, const std::string& name) {
  Require(m.allFinite(), name + " has a NaN or infinite entry; all entries must be finite");
}

void RequireSquare(const Eigen::MatrixXd& m, int n, const std::string& name) {
  Require(m.rows() == n && m.cols() == n,
          fmt::format("{} must be {} x {} (N = {}), got {} x {}", name, n, n, n,
                      static_cast<int>(m.rows()), static_cast<int>(m.cols())));
  RequireFinite(m, name);
  const double scale = m.cwiseAbs().maxCoeff();
  Require((m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale, name + " must be symmetric");
}

/// Smallest eigenvalue of a symmetric matrix.
double SmallestEigenvalue(const Eigen::MatrixXd& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .minCoeff();
}

void ValidateChain(const ChainParameters& chain) {
  Require(chain.dof >= 1, fmt::format("n (number of masses) must be >= 1, got {}", chain.dof));
  Require(std::isfinite(chain.mass) && chain.mass > 0,
          fmt::format("m (mass) must be finite and > 0, got {}", chain.mass));
  Require(std::isfinite(chain.stiffness) && chain.stiffness > 0,
          fmt::format("k (stiffness) must be finite and > 0, got {}", chain.stiffness));
  Require(std::isfinite(chain.damping) && chain.damping >= 0,
          fmt::format("c (damping) must be finite and >= 0, got {}", chain.damping));
}

void ValidateMatrices(const System& s) {
  const int n = s.Dof();
  Require(n >= 1, "the system needs at least one mass (N >= 1)");
  RequireSquare(s.mass, n, "M (mass matrix)");
  RequireSquare(s.damping, n, "C (damping matrix)");
  RequireSquare(s.stiffness, n, "K (stiffness matrix)");
  const double m_scale = s.mass.cwiseAbs().maxCoeff();
  Require(m_scale > 0 && SmallestEigenvalue(s.mass) > 1e-12 * m_scale,
          "M (mass matrix) must be positive definite (every mass > 0)");
  const double k_scale = s.stiffness.cwiseAbs().maxCoeff();
  Require(k_scale > 0 && SmallestEigenvalue(s.stiffness) > 1e-12 * k_scale,
          "K (stiffness matrix) must be positive definite (every mass tied by a spring)");
  const double c_scale = s.damping.cwiseAbs().maxCoeff();
  Require(c_scale == 0 || SmallestEigenvalue(s.damping) >= -1e-12 * c_scale,
          "C (damping matrix) must be positive semi-definite (no negative damping)");
}

void ValidateScalars(const System& s) {
  const int n = s.Dof();
  Require(s.forcing.size() == n, fmt::format("A (forcing) must have N = {} entries, got {}", n,
                                             static_cast<int>(s.forcing.size())));
  Require(s.forcing.allFinite(), "A (forcing) has a NaN or infinite entry");
  Require(std::isfinite(s.omega) && s.omega > 0,
          fmt::format("omega (forcing frequency) must be finite and > 0, got {}", s.omega));
  Require(std::isfinite(s.stop), fmt::format("xs (stop position) must be finite, got {}", s.stop));
  Require(std::isfinite(s.restitution) && s.restitution >= 0 && s.restitution <= 1,
          fmt::format("r (coefficient of restitution) must be in [0, 1], got {}", s.restitution));
  Require(s.contact_dof >= 0 && s.contact_dof < n,
          fmt::format("contact DOF must be in [1, {}], got {}", n, s.contact_dof + 1));
}

/// The subsystem that moves while the contact mass sticks must have a
/// bounded steady response too.
void ValidateStuckSubsystem(const System& s) {
  const detail::StuckSubsystem stuck = detail::StuckSubsystemOf(s);
  try {
    LinearFlow(stuck.mass, stuck.damping, stuck.stiffness, stuck.forcing, stuck.constant_force,
               s.omega);
  } catch (const InvalidInput& e) {
    throw InvalidInput(detail::StuckSubsystemError(s, e.what()));
  }
}

}  // namespace

double System::ForcingPeriod() const { return 2.0 * std::numbers::pi / omega; }

double System::Phase(double t) const {
  const double period = ForcingPeriod();
  const double phase = std::fmod(t, period);
  return phase < 0 ? phase + period : phase;
}

Eigen::MatrixXd ChainCouplingMatrix(int dof) {
  Eigen::MatrixXd e = Eigen::MatrixXd::Zero(dof, dof);
  for (int i = 0; i < dof; ++i) {
    e(i, i) = (i + 1 < dof) ? 2.0 : 1.0;
    if (i + 1 < dof) e(i, i + 1) = e(i + 1, i) = -1.0;
  }
  return e;
}

System UniformChain(const ChainParameters& chain, const Eigen::VectorXd& forcing, double omega,
                    double stop, double restitution) {
  // Values are checked by Validate(); only the shape is needed to build.
  Require(chain.dof >= 1, fmt::format("n (number of masses) must be >= 1, got {}", chain.dof));
  const Eigen::MatrixXd e = ChainCouplingMatrix(chain.dof);
  System s =
      GeneralSystem(chain.mass * Eigen::MatrixXd::Identity(chain.dof, chain.dof), chain.damping * e,
                    chain.stiffness * e, forcing, omega, stop, restitution);
  s.chain = chain;
  return s;
}

System PaperSystem(double omega) {
  return UniformChain(ChainParameters{}, Eigen::Vector2d(0.5, 0.0), omega, 0.1, 0.7);
}

System GeneralSystem(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                     const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing, double omega,
                     double stop, double restitution, std::optional<int> contact_dof) {
  System s;
  s.mass = mass;
  s.damping = damping;
  s.stiffness = stiffness;
  s.forcing = forcing;
  s.omega = omega;
  s.stop = stop;
  s.restitution = restitution;
  s.contact_dof = contact_dof.value_or(static_cast<int>(mass.rows()) - 1);
  return s;
}

void ValidateParameters(const System& s) {
  if (s.chain) ValidateChain(*s.chain);
  ValidateMatrices(s);
  ValidateScalars(s);
}

void Validate(const System& s) {
  ValidateParameters(s);
  // Constructing the flows rejects an undamped resonance (no bounded
  // steady response): the same test the simulator relies on.
  LinearFlow(s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(s.Dof()), s.omega);
  if (s.Dof() > 1) ValidateStuckSubsystem(s);
}

HybridState RestState(const System& s) {
  HybridState state;
  state.x = Eigen::VectorXd::Zero(s.Dof());
  state.v = Eigen::VectorXd::Zero(s.Dof());
  return state;
}

void ValidateState(const System& s, const HybridState& state) {
  const int n = s.Dof();
  Require(
      state.x.size() == n && state.v.size() == n,
      fmt::format("the initial state must have N = {} positions and {} velocities, got {} and {}",
                  n, n, static_cast<int>(state.x.size()), static_cast<int>(state.v.size())));
  Require(std::isfinite(state.t) && state.x.allFinite() && state.v.allFinite(),
          "the initial state has a NaN or infinite entry");
  const int c = s.contact_dof;
  Require(state.x(c) <= s.stop,
          fmt::format("initial x{} = {} is beyond the stop xs = {}; it must be <= xs", c + 1,
                      state.x(c), s.stop));
  Require(!state.stuck || (state.x(c) == s.stop && state.v(c) == 0.0),
          fmt::format("a stuck initial state needs x{} = xs and v{} = 0", c + 1, c + 1));
}

namespace detail {

StuckSubsystem StuckSubsystemOf(const System& s) {
  const int c = s.contact_dof;
  return {WithoutIndex(s.mass, c), WithoutIndex(s.damping, c), WithoutIndex(s.stiffness, c),
          WithoutIndex(s.forcing, c),
          -WithoutIndex(Eigen::VectorXd(s.stiffness.col(c)), c) * s.stop};
}

std::string StuckSubsystemError(const System& s, const std::string& why) {
  return fmt::format("stuck subsystem (mass {} held at the stop): {}", s.contact_dof + 1, why);
}

}  // namespace detail
}  // namespace impactkit
