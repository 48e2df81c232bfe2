#pragma once
/// \file system.hpp
/// The impact oscillator: N masses with linear coupling, limited by rigid
/// stops. Each stop limits one mass i from above (x_i <= xs) or from below
/// (x_i >= xs); one mass may have a stop on each side (a clearance), and
/// several masses stops of their own.
///
///     M x'' + C x' + K x = A cos(Ω t)      while every mass is inside its stops
///     v_i(t+) = -r v_i(t-)                 when x_i reaches a stop moving towards it
///
/// (by an impulse through M: the other velocities move too when M couples
/// the masses; hybrid/stop.hpp). The seed's model, one upper stop on the
/// last mass, is the case of one stop.
///
/// The paper's case (Wagg & Bishop 2001) is the uniform chain M = m I,
/// C = c E, K = k E with E tridiagonal (E_ii = 2 for i < N, E_NN = 1,
/// off-diagonals -1). PaperSystem() is the default of every command.

#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/core/errors.hpp"
// A stop's parameters are declared beside its law, as data (the header
// includes nothing of the library): a contact law is one folder.
#include "impactkit/hybrid/stop_parameters.hpp"

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

/// The most stops a system may have: a set of stops holding their masses
/// is a bit set (StopSet).
inline constexpr int kMaxStops = 64;

/// A set of stops by index, bit k for stop k: the stops holding their
/// masses (sticking) in a hybrid state.
using StopSet = std::uint64_t;
inline constexpr StopSet StopBit(int stop) { return StopSet{1} << stop; }

/// A complete impact oscillator. Matrices are N x N, symmetric; M and K
/// positive definite, C positive semi-definite.
struct System {
  Eigen::MatrixXd mass;       ///< M
  Eigen::MatrixXd damping;    ///< C
  Eigen::MatrixXd stiffness;  ///< K
  Eigen::VectorXd forcing;    ///< A, force amplitudes: f(t) = A cos(Ω t)
  double omega = 1.0;         ///< Ω, forcing frequency (> 0)
  /// The stops, at least one; stop 1 of the files and the command line is
  /// stops[0] (parameters xs and r), stop k is stops[k - 1] (xs<k>, r<k>).
  std::vector<StopParameters> stops = {StopParameters{}};
  /// Set when the system is a uniform chain: then m, k, c and n can be
  /// changed by name and the matrices are rebuilt.
  std::optional<ChainParameters> chain;

  int Dof() const { return static_cast<int>(mass.rows()); }
  /// T = 2π/Ω.
  double ForcingPeriod() const;
  /// The forcing phase of time t: t mod T, in [0, T).
  double Phase(double t) const;
  int StopCount() const { return static_cast<int>(stops.size()); }
};

/// The coupling matrix E of the uniform chain (N x N).
Eigen::MatrixXd ChainCouplingMatrix(int dof);

/// The uniform chain with the given forcing (length N), Ω, and one upper
/// stop at xs on the last mass with restitution r.
System UniformChain(const ChainParameters& chain, const Eigen::VectorXd& forcing, double omega,
                    double stop, double restitution);

/// The paper's system: N = 2, m = k = 1, c = 0.1, A = (0.5, 0), xs = 0.1,
/// r = 0.7, Ω = 1 unless given.
System PaperSystem(double omega = 1.0);

/// A general system with one upper stop. `contact_dof` is the index of the
/// mass that meets the stop, 0-based as everywhere in the library (the
/// system file's key `contact_dof` is 1-based, as users count masses);
/// default the last.
System GeneralSystem(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                     const Eigen::MatrixXd& stiffness, const Eigen::VectorXd& forcing, double omega,
                     double stop, double restitution,
                     std::optional<int> contact_dof = std::nullopt);

/// Checks every field and the scales derived from them (docs/bad-input.md:
/// entries within 1e-150 … 1e150, natural frequencies within a ratio of
/// 1e5, a forcing period at most 1e6 periods of the fastest mode, a forced
/// response below 1e150); throws InvalidInput naming the first bad one and
/// the allowed range. A system is data: the one check that needs its flows
/// decomposed, an undamped resonance, is Validate's
/// (hybrid/system_flows.hpp), which callers that build no flows use.
void ValidateParameters(const System& system);

/// The hybrid state: time, positions, velocities, and the stops that hold
/// their masses (sticking).
struct HybridState {
  double t = 0.0;
  Eigen::VectorXd x;
  Eigen::VectorXd v;
  StopSet held = 0;  ///< bit k: stop k holds its mass at its position
  bool Stuck() const { return held != 0; }
};

/// Rest at t = 0: x = v = 0, free.
HybridState RestState(const System& system);

/// The stops whose masses are at them at rest (x_i = xs, v_i = 0): the set
/// a state may hold.
StopSet StopsAtRest(const System& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);

/// Throws InvalidInput if the state has the wrong size, a non-finite entry,
/// a mass beyond one of its stops, or a held stop whose mass is not at it
/// at rest (x_i = xs, v_i = 0).
void ValidateState(const System& system, const HybridState& state);

}  // namespace impactkit
