#pragma once
/// \file system.hpp
/// The impact oscillator: N masses with linear coupling, one of which (the
/// contact DOF, by default the last) is limited by a rigid stop.
///
///     M x'' + C x' + K x = A cos(Ω t)      while x_c < xs     (free flight)
///     v_c(t+) = -r v_c(t-)                 when x_c reaches xs with v_c > 0
///
/// (by an impulse through M: the other velocities move too when M couples
/// the masses; hybrid/stop.hpp)
///
/// The paper's case (Wagg & Bishop 2001) is the uniform chain M = m I,
/// C = c E, K = k E with E tridiagonal (E_ii = 2 for i < N, E_NN = 1,
/// off-diagonals -1). PaperSystem() is the default of every command.

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/core/errors.hpp"

namespace impactkit {

/// The parameters of the paper's uniform chain (m_i = m, c_i = c, k_i = k).
struct ChainParameters {
  int dof = 2;             ///< number of masses N (>= 1)
  double mass = 1.0;       ///< m (> 0)
  double stiffness = 1.0;  ///< k (> 0)
  double damping = 0.1;    ///< c (>= 0)
};

/// The most masses a system may have: the modal decomposition costs O(N³)
/// and each event O(N²) (docs/performance.md gives the costs).
inline constexpr int kMaxDegreesOfFreedom = 1000;

/// A complete impact oscillator. Matrices are N x N, symmetric; M and K
/// positive definite, C positive semi-definite.
struct System {
  Eigen::MatrixXd mass;       ///< M
  Eigen::MatrixXd damping;    ///< C
  Eigen::MatrixXd stiffness;  ///< K
  Eigen::VectorXd forcing;    ///< A, force amplitudes: f(t) = A cos(Ω t)
  double omega = 1.0;         ///< Ω, forcing frequency (> 0)
  double stop = 0.1;          ///< xs, position of the stop for the contact DOF
  double restitution = 0.7;   ///< r in [0, 1]
  int contact_dof = 1;        ///< index (0-based) of the mass that meets the stop
  /// Set when the system is a uniform chain: then m, k, c and n can be
  /// changed by name and the matrices are rebuilt.
  std::optional<ChainParameters> chain;

  int Dof() const { return static_cast<int>(mass.rows()); }
  /// T = 2π/Ω.
  double ForcingPeriod() const;
  /// The forcing phase of time t: t mod T, in [0, T).
  double Phase(double t) const;
};

/// The coupling matrix E of the uniform chain (N x N).
Eigen::MatrixXd ChainCouplingMatrix(int dof);

/// The uniform chain with the given forcing (length N), Ω, xs and r.
System UniformChain(const ChainParameters& chain, const Eigen::VectorXd& forcing, double omega,
                    double stop, double restitution);

/// The paper's system: N = 2, m = k = 1, c = 0.1, A = (0.5, 0), xs = 0.1,
/// r = 0.7, Ω = 1 unless given.
System PaperSystem(double omega = 1.0);

/// A general system. `contact_dof` is the index of the mass that meets the
/// stop, 0-based as everywhere in the library (the system file's key
/// `contact_dof` is 1-based, as users count masses); default the last.
System GeneralSystem(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                     const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing, double omega,
                     double stop, double restitution,
                     std::optional<int> contact_dof = std::nullopt);

/// Checks every field and the scales derived from them (docs/bad-input.md:
/// entries within 1e-150 … 1e150, natural frequencies within a ratio of
/// 1e5, a forcing period at most 1e6 periods of the fastest mode, a forced
/// response below 1e150); throws InvalidInput naming the first bad one and
/// the allowed range. Also rejects an undamped system forced at one of its
/// natural frequencies (no bounded steady response exists).
void Validate(const System& system);

/// Every check of Validate() except the resonances, which need the flows
/// decomposed: for callers that decompose them next anyway (HybridSystem,
/// whose flows reject a resonance themselves).
void ValidateParameters(const System& system);

/// The hybrid state: time, positions, velocities, and whether the contact
/// mass is held at the stop (sticking).
struct HybridState {
  double t = 0.0;
  Eigen::VectorXd x;
  Eigen::VectorXd v;
  bool stuck = false;
};

/// Rest at t = 0: x = v = 0, free.
HybridState RestState(const System& system);

/// Throws InvalidInput if the state has the wrong size, a non-finite entry,
/// or the contact mass beyond the stop (x_c > xs), or stuck without
/// x_c = xs, v_c = 0.
void ValidateState(const System& system, const HybridState& state);

}  // namespace impactkit
