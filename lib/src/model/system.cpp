#include "impactkit/model/system.hpp"

#include <fmt/format.h>

#include <Eigen/SparseLU>
#include <bit>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "core/require.hpp"
#include "core/symmetric_eigen.hpp"

namespace impactkit {
namespace {

void RequireFinite(const Eigen::MatrixXd& m, std::string_view name) {
  Require(m.allFinite(), "{} has a NaN or infinite entry; all entries must be finite", name);
}

void RequireSquare(const Eigen::MatrixXd& m, int n, std::string_view name) {
  Require(m.rows() == n && m.cols() == n, "{} must be {} x {} (N = {}), got {} x {}", name, n, n, n,
          static_cast<int>(m.rows()), static_cast<int>(m.cols()));
  RequireFinite(m, name);
  const double scale = m.cwiseAbs().maxCoeff();
  Require((m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale, "{} must be symmetric", name);
}

void ValidateChain(const ChainParameters& chain) {
  Require(chain.dof >= 1, "n (number of masses) must be >= 1, got {}", chain.dof);
  Require(std::isfinite(chain.mass) && chain.mass > 0, "m (mass) must be finite and > 0, got {}",
          chain.mass);
  Require(std::isfinite(chain.stiffness) && chain.stiffness > 0,
          "k (stiffness) must be finite and > 0, got {}", chain.stiffness);
  Require(std::isfinite(chain.damping) && chain.damping >= 0,
          "c (damping) must be finite and >= 0, got {}", chain.damping);
}

void ValidateMatrices(const System& s) {
  const int n = s.Dof();
  Require(n >= 1, "the system needs at least one mass (N >= 1)");
  Require(n <= kMaxDegreesOfFreedom, "the system has N = {} masses; at most {}", n,
          kMaxDegreesOfFreedom);
  RequireSquare(s.mass, n, "M (mass matrix)");
  RequireSquare(s.damping, n, "C (damping matrix)");
  RequireSquare(s.stiffness, n, "K (stiffness matrix)");
  const double m_scale = s.mass.cwiseAbs().maxCoeff();
  Require(m_scale > 0 && detail::EigenvaluesExceed(s.mass, 1e-12 * m_scale),
          "M (mass matrix) must be positive definite (every mass > 0)");
  const double k_scale = s.stiffness.cwiseAbs().maxCoeff();
  Require(k_scale > 0 && detail::EigenvaluesExceed(s.stiffness, 1e-12 * k_scale),
          "K (stiffness matrix) must be positive definite (every mass tied by a spring)");
  const double c_scale = s.damping.cwiseAbs().maxCoeff();
  // (>= −1e-12 c_scale: no eigenvalue below it, to the rounding of a count.)
  Require(c_scale == 0 || detail::EigenvaluesExceed(s.damping, -1e-12 * c_scale),
          "C (damping matrix) must be positive semi-definite (no negative damping)");
}

/// Double arithmetic in the flow squares frequencies and multiplies
/// amplitudes by them: magnitudes within 1e±150 leave it room both ways.
constexpr double kLargest = 1e150;
constexpr double kSmallest = 1e-150;
/// Above this ratio of natural frequencies the slowest mode's ω² is lost in
/// the rounding of the fastest's (relative error ε × ratio² ~ 2e-6).
constexpr double kMaxFrequencyRatio = 1e5;
/// The event search steps on the fastest mode's time scale: a forcing
/// period of more than this many of its periods takes over ~0.1 s each.
constexpr double kMaxPeriodRatio = 1e6;

/// A magnitude of at most kLargest; a scale (a mass, a stiffness, a
/// frequency) also at least kSmallest. Small entries elsewhere (a forcing
/// of 1e-300, a damping of 1e-200) are harmless: they only underflow to 0.
void RequireScale(double value, std::string_view name, bool is_scale = false) {
  const double magnitude = std::abs(value);
  if (is_scale) {
    Require(magnitude >= kSmallest && magnitude <= kLargest,
            "{} must be within {:g} … {:g} in magnitude, got {:g}", name, kSmallest, kLargest,
            value);
  }
  Require(magnitude <= kLargest, "{} must be at most {:g} in magnitude, got {:g}", name, kLargest,
          value);
}

void RequireScales(const Eigen::MatrixXd& m, std::string_view name) {
  for (Eigen::Index i = 0; i < m.size(); ++i) RequireScale(m.data()[i], name);
}

/// The names of the parameters a matrix comes from: the chain's m, k, c
/// when the system is a chain, the matrix otherwise.
const char* Named(const System& s, const char* chain_name, const char* matrix_name) {
  return s.chain ? chain_name : matrix_name;
}

/// Below this many masses a dense LU is cheaper than a sparse one, whose
/// set-up allocates dozens of blocks (for N = 2 it was an eighth of a
/// connected diagram's allocations: a system is validated at every
/// parameter value a continuation visits).
constexpr int kSparseResponseMinDof = 32;

/// Z⁻¹ A for the dynamic stiffness Z; a sparse LU where Z is tridiagonal
/// (a chain's: O(N) against the dense O(N³)) and large, infinite where Z
/// is singular.
Eigen::VectorXcd ForcedResponse(const Eigen::MatrixXcd& z, const Eigen::VectorXcd& a,
                                bool tridiagonal) {
  if (!tridiagonal || z.rows() < kSparseResponseMinDof) return z.partialPivLu().solve(a);
  const Eigen::SparseMatrix<std::complex<double>> sparse = z.sparseView();
  Eigen::SparseLU<Eigen::SparseMatrix<std::complex<double>>> lu(sparse);
  if (lu.info() != Eigen::Success) {
    return Eigen::VectorXcd::Constant(a.size(), std::numeric_limits<double>::infinity());
  }
  return lu.solve(a);
}

/// The scales derived from the entries: natural frequencies, the forcing
/// period on the fastest mode's time scale, the forced response.
void ValidateDerivedScales(const System& s) {
  const char* mk =
      Named(s, "m (mass) and k (stiffness)", "M (mass matrix) and K (stiffness matrix)");
  const Eigen::VectorXd squares = detail::SolveGeneralized(s.stiffness, s.mass, false).values;
  const double slowest = std::sqrt(squares.minCoeff()), fastest = std::sqrt(squares.maxCoeff());
  Require(slowest >= kSmallest && fastest <= kLargest,
          "{} give natural frequencies from {:g} to {:g}; they must lie within {:g} … "
          "{:g}",
          mk, slowest, fastest, kSmallest, kLargest);
  Require(fastest <= kMaxFrequencyRatio * slowest,
          "{} give natural frequencies from {:g} to {:g}, a ratio of {:.3g}; at most "
          "{:.0e} (the slowest mode would be lost in the rounding of the fastest)",
          mk, slowest, fastest, fastest / slowest, kMaxFrequencyRatio);
  Require(fastest <= kMaxPeriodRatio * s.omega,
          "omega = {:g} is too slow for this system: one forcing period spans {:.3g} "
          "periods of its fastest mode (frequency {:g}); at most {:.0e}, omega >= {:.3g}",
          s.omega, fastest / s.omega, fastest, kMaxPeriodRatio, fastest / kMaxPeriodRatio);
  const Eigen::MatrixXcd dynamic_stiffness =
      (s.stiffness - s.omega * s.omega * s.mass).cast<std::complex<double>>() +
      std::complex<double>(0.0, s.omega) * s.damping.cast<std::complex<double>>();
  const double response =
      ForcedResponse(dynamic_stiffness, s.forcing.cast<std::complex<double>>(),
                     detail::IsTridiagonal(s.mass) && detail::IsTridiagonal(s.stiffness) &&
                         detail::IsTridiagonal(s.damping))
          .cwiseAbs()
          .maxCoeff();
  // Resonance (an infinite or NaN response) is the flows' to report.
  Require(!(std::isfinite(response) && response > kLargest),
          "A (forcing) gives a forced response of amplitude {:g} at omega = {:g}; at "
          "most {:g}",
          response, s.omega, kLargest);
}

/// How messages name stop k's position: xs (stop position), or xs<k>
/// (position of stop k) with several stops.
std::string PositionName(const System& s, int k) {
  constexpr const StopParameterRow& kPosition = kStopParameterRows[0];
  static_assert(kPosition.member == &StopParameters::position);
  return StopParameterLabel(kPosition, k, s.StopCount());
}

void ValidateStop(const System& s, int k) {
  const StopParameters& stop = s.stops[k];
  const int n = s.Dof();
  const bool on_a_mass = stop.dof >= 0 && stop.dof < n;
  if (s.StopCount() == 1) {
    Require(on_a_mass, "contact DOF must be in [1, {}], got {}", n, stop.dof + 1);
  } else {
    Require(on_a_mass, "the mass of stop {} must be in [1, {}], got {}", k + 1, n, stop.dof + 1);
  }
  CheckStopParameterRanges(stop, k, s.StopCount());
}

/// Two stops on one mass: one above and one below it, leaving room
/// between them (two on one side would make one of them unreachable).
void ValidateStopPair(const System& s, int j, int k) {
  const StopParameters &a = s.stops[j], &b = s.stops[k];
  if (a.dof != b.dof) return;
  Require(a.side != b.side,
          "stops {} and {} both limit mass {} from {}: one of them could never be "
          "reached; give a mass at most one stop on each side",
          j + 1, k + 1, a.dof + 1, a.side == StopSide::kUpper ? "above" : "below");
  const StopParameters &upper = a.side == StopSide::kUpper ? a : b,
                       &lower = a.side == StopSide::kUpper ? b : a;
  Require(lower.position < upper.position,
          "the stops of mass {} leave it no room: the lower one at {} must be below "
          "the upper one at {}",
          a.dof + 1, lower.position, upper.position);
}

void ValidateStops(const System& s) {
  Require(!s.stops.empty(), "the system needs at least one stop");
  Require(s.StopCount() <= kMaxStops, "the system has {} stops; at most {}", s.StopCount(),
          kMaxStops);
  for (int k = 0; k < s.StopCount(); ++k) ValidateStop(s, k);
  for (int j = 0; j < s.StopCount(); ++j) {
    for (int k = j + 1; k < s.StopCount(); ++k) ValidateStopPair(s, j, k);
  }
}

void ValidateScalars(const System& s) {
  const int n = s.Dof();
  Require(s.forcing.size() == n, "A (forcing) must have N = {} entries, got {}", n,
          static_cast<int>(s.forcing.size()));
  Require(s.forcing.allFinite(), "A (forcing) has a NaN or infinite entry");
  Require(std::isfinite(s.omega) && s.omega > 0,
          "omega (forcing frequency) must be finite and > 0, got {}", s.omega);
  ValidateStops(s);
}

}  // namespace

double System::ForcingPeriod() const { return 2.0 * std::numbers::pi / omega; }

double System::Phase(double t) const {
  const double period = ForcingPeriod();
  // t − n T for n = ⌊t/T⌋ is a double (as fmod's result is), so one fused
  // multiply–add gives it exactly; where t/T rounded across an integer the
  // result falls outside [0, T) and fmod decides. The same bits as fmod,
  // which costs ~170 instructions at t/T ~ 10^5 (once per impact).
  const double phase = std::fma(-std::floor(t / period), period, t);
  if (phase >= 0 && phase < period) return phase;
  const double remainder = std::fmod(t, period);
  return remainder < 0 ? remainder + period : remainder;
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
  Require(chain.dof >= 1, "n (number of masses) must be >= 1, got {}", chain.dof);
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
  s.stops = {StopParameters{contact_dof.value_or(static_cast<int>(mass.rows()) - 1),
                            StopSide::kUpper, stop, restitution}};
  return s;
}

void ValidateParameters(const System& s) {
  if (s.chain) ValidateChain(*s.chain);
  ValidateMatrices(s);
  ValidateScalars(s);
  if (s.chain) {
    RequireScale(s.chain->mass, "m (mass)", true);
    RequireScale(s.chain->stiffness, "k (stiffness)", true);
    RequireScale(s.chain->damping, "c (damping)");
  } else {
    RequireScales(s.mass, "every entry of M (mass matrix)");
    RequireScales(s.stiffness, "every entry of K (stiffness matrix)");
    RequireScales(s.damping, "every entry of C (damping matrix)");
  }
  RequireScales(s.forcing, "every entry of A (forcing)");
  RequireScale(s.omega, "omega (forcing frequency)", true);
  for (int k = 0; k < s.StopCount(); ++k) RequireScale(s.stops[k].position, PositionName(s, k));
  ValidateDerivedScales(s);
}

HybridState RestState(const System& s) {
  HybridState state;
  state.x = Eigen::VectorXd::Zero(s.Dof());
  state.v = Eigen::VectorXd::Zero(s.Dof());
  return state;
}

StopSet StopsAtRest(const System& s, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  StopSet at_rest = 0;
  for (int k = 0; k < s.StopCount(); ++k) {
    const StopParameters& stop = s.stops[k];
    if (x(stop.dof) == stop.position && v(stop.dof) == 0.0) at_rest |= StopBit(k);
  }
  return at_rest;
}

void ValidateState(const System& s, const HybridState& state) {
  const int n = s.Dof();
  Require(state.x.size() == n && state.v.size() == n,
          "the initial state must have N = {} positions and {} velocities, got {} and {}", n, n,
          static_cast<int>(state.x.size()), static_cast<int>(state.v.size()));
  Require(std::isfinite(state.t) && state.x.allFinite() && state.v.allFinite(),
          "the initial state has a NaN or infinite entry");
  for (int k = 0; k < s.StopCount(); ++k) {
    const StopParameters& stop = s.stops[k];
    const int c = stop.dof;
    const bool upper = stop.side == StopSide::kUpper;
    Require(stop.Sign() * (state.x(c) - stop.position) <= 0,
            "initial x{} = {} is beyond the stop {} = {}; it must be {} {}", c + 1, state.x(c),
            StopParameterName("xs", k), stop.position,
            upper ? "<=" : ">=", StopParameterName("xs", k));
  }
  Require(state.held < (s.StopCount() == kMaxStops ? ~StopSet{0} : StopBit(s.StopCount())),
          "the held stops name a stop beyond the system's {}", s.StopCount());
  const StopSet not_at_rest = state.held & ~StopsAtRest(s, state.x, state.v);
  if (not_at_rest != 0) {
    const int k = std::countr_zero(not_at_rest);
    const int c = s.stops[k].dof;
    throw InvalidInput(fmt::format("a stuck initial state needs x{} = {} and v{} = 0", c + 1,
                                   StopParameterName("xs", k), c + 1));
  }
}

}  // namespace impactkit
