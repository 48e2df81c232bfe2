#pragma once
/// \file grid_cell.hpp
/// One cell of a two-dimensional brute-force grid (a parameter map,
/// parameter_map.hpp, or a basin picture, basins.hpp): what its steady motion
/// is, in a few numbers. A cell is what travels between threads, processes
/// (MPI) and runs (checkpoints), so it has an exact text form: every double
/// in its shortest round-trip decimal, so a cell read back is the same bits.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/analysis/sweep.hpp"

namespace impactkit {

/// One impact of a periodic attractor's last q forcing periods.
struct AttractorImpact {
  double phase = 0.0;     ///< t mod T, in [0, T)
  double velocity = 0.0;  ///< impact speed v_c(t-)
};

struct GridCell {
  std::int64_t index = 0;  ///< row-major: row * columns + column
  MotionKind kind = MotionKind::kUnresolved;
  /// The period P(p, q) of periodic, sticking (p unused) and repeating
  /// non-impacting motion (p = 0); both 0 when there is none.
  int p = 0;
  int q = 0;
  double max_v = 0.0;       ///< largest impact speed recorded; NaN without impacts
  double range_xN = 0.0;    ///< largest per-period max - min of the contact mass; NaN if none
  double lyapunov = 0.0;    ///< largest exponent when computed and valid, else NaN
  bool restarted = false;   ///< as SweepPoint::restarted
  std::int64_t events = 0;  ///< as SweepPoint::events (the cell's cost)
  /// Basins only: the impacts of the last q recorded periods of a periodic or
  /// sticking motion (the attractor's orbit); empty otherwise.
  std::vector<AttractorImpact> orbit;
};

/// The cell of a sweep point: the same period, speeds, ranges and exponent
/// that `impactkit sweep --summary` reports for it.
GridCell CellOf(std::int64_t index, const SweepPoint& point);

/// "periodic", ..., as ToString(MotionKind), read back; throws InvalidInput.
MotionKind MotionKindFromName(std::string_view name);

/// One line, no newline: index kind p q max_v range_xN lyapunov restarted
/// events n phase_1 velocity_1 ... phase_n velocity_n.
std::string CellToText(const GridCell& cell);

/// The cell of CellToText's line. Throws InvalidInput naming what is wrong.
GridCell CellFromText(std::string_view line);

}  // namespace impactkit
