#pragma once
/// \file diagram_output.hpp
/// A connected diagram as result files carry it: its JSON document and its
/// branches' labels, the one schema that `impactkit diagram` and `paper`
/// and Python's Diagram.to_json write (docs/cli.md).

#include <cstddef>
#include <string>

#include "impactkit/continuation/diagram.hpp"

namespace impactkit {

/// Branch k's label: the first seed's "main", the other seeds' "seed<k+1>",
/// and a branch born at a node by that node's kind and its index: "pd3" at
/// a period doubling, "bp4" at a branch point, "pf5" at a pitchfork,
/// "graze6" at a grazing.
std::string BranchLabel(const Diagram& diagram, std::size_t k);

/// The diagram as JSON text: parameter, complete, message, seconds, its
/// nodes (id, type, param, p, q, branch, multiplier(s), monitor, eta, and a
/// grazing's vanishing impact), its edges (from, to, branch, section, p, q,
/// releases and each point's param, stable, leading impact speeds v and
/// range_xN) and its labelled branches (io/branch_output.hpp).
std::string DiagramJson(const Diagram& diagram);

}  // namespace impactkit
