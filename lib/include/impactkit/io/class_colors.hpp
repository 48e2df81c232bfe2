#pragma once
/// \file io/class_colors.hpp
/// The colour of each class of motion in every figure: a map's cells, a
/// basin picture's attractors and a diagram's branches. The colour is a
/// function of the class alone (kind, p, q), never of which classes a
/// figure happens to hold, so that P(1,2) is the same colour in every panel
/// of a paper.

#include <string>

#include "impactkit/analysis/classify.hpp"

namespace impactkit {

/// The colour of the class (kind, p, q) as "#rrggbb". p and q are read for
/// periodic P(p,q) and sticking P(∞,q) motions only (p is ignored for
/// sticking ones). The classes common in impact oscillators (P(1,1), P(n,1)
/// up to P(8,1), P(1,2), P(2,2), P(4,4), P(∞,1), ...) have hand-picked
/// colours at least 25 CIELAB units apart from each other and from the
/// three fixed ones: non-impacting near white, chaotic black, unresolved
/// dark grey. Every other period gets a hue a golden angle from that of the
/// next p at the same q (so that the periods of a cascade stay apart, at
/// least 10 units for p to p + 3), in three lightnesses in turn, at least 15
/// units from every hand-picked colour. `copy` > 0 shades the colour for
/// the copy-th further attractor of the same class (two P(1,1) orbits in one
/// basin picture), alternately darker and lighter.
std::string ClassColor(MotionKind kind, int p, int q, int copy = 0);

/// The colour of the entry that groups the periods a legend leaves out.
inline constexpr const char* kOtherClassesColor = "#b0b0b0";

}  // namespace impactkit
