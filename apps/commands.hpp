#pragma once
/// \file commands.hpp
/// The subcommands of `impactkit`. Each registers its flags and its job on
/// the app; main() adds them all. A new job is a new Add...Command here and
/// a folder apps/<job>/ that defines it; what several jobs share is in
/// apps/common/.

#include <CLI/CLI.hpp>

namespace impactkit::cli {

/// `impactkit simulate`: a run from an initial state, transient discarded,
/// a window recorded to CSV/JSON/PNG and summarised (simulate/).
void AddSimulateCommand(CLI::App& app);

/// `impactkit orbit`: a periodic orbit P(p,q) as a fixed point of the impact
/// map, its impacts and multipliers (orbit/).
void AddOrbitCommand(CLI::App& app);

/// `impactkit continue`: a branch of orbits followed in one parameter, its
/// special points, and the branches born there (continue/).
void AddContinueCommand(CLI::App& app);

/// `impactkit curve`: a fold, period-doubling, Neimark-Sacker or grazing
/// point followed in two parameters, with its codimension-two points (curve/).
void AddCurveCommand(CLI::App& app);
/// `impactkit diagram`: the connected bifurcation diagram over a parameter
/// range, seeded by a sweep (diagram/).
void AddDiagramCommand(CLI::App& app);

/// `impactkit paper`: the paper's whole study in one run, summarised and
/// written into one folder (paper/).
void AddPaperCommand(CLI::App& app);

/// `impactkit sweep`: a brute-force bifurcation diagram over one named
/// parameter, with each value's motion classified (sweep/).
void AddSweepCommand(CLI::App& app);

/// `impactkit impactmap`, `returnmap` and `lyapunov`: impact phase against
/// speed, the low-velocity return map (with the Eq. 18 fit) and the impact
/// map's Lyapunov exponents (maps/).
void AddImpactMapCommand(CLI::App& app);
void AddReturnMapCommand(CLI::App& app);
void AddLyapunovCommand(CLI::App& app);

/// `impactkit map` and `basins`: two-parameter brute-force maps and basins
/// of attraction, on all cores and under mpirun, resumable (map/, basins/).
void AddMapCommand(CLI::App& app);
void AddBasinsCommand(CLI::App& app);
/// `impactkit resonance`: resonance curves without the stop (resonance/).
void AddResonanceCommand(CLI::App& app);

}  // namespace impactkit::cli
