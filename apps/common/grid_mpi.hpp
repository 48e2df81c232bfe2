#pragma once
/// \file common/grid_mpi.hpp
/// The MPI transport of grid_driver: rank 0 hands out unit numbers and
/// receives finished units as text (CellToText lines); the other ranks ask,
/// compute and send. Compiled only when CMake finds MPI
/// (IMPACTKIT_HAVE_MPI); no MPI type appears in this header.

#include <functional>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_task.hpp"

namespace impactkit::cli::mpi {

/// MPI_Init_thread (serialised calls); returns {rank, ranks}.
std::pair<int, int> Start();
void Finish();
/// Ends every rank after an error that one rank cannot report to the others.
[[noreturn]] void Abort(const std::string& message);

/// Rank 0 and all others agree on `ok` (rank 0's); returns it.
bool Agree(bool ok);

/// Rank 0: serves requests for units from `take` (-1: none left) and passes
/// each unit received to `receive`, until every other rank has been told to
/// stop. Calls `take` and `receive` on this thread only.
void Serve(int ranks, const std::function<int()>& take,
           const std::function<void(int, std::vector<GridCell>&)>& receive);

/// Ranks > 0: the next unit from rank 0 (-1: stop), and a finished unit to it.
int Request();
void Send(int unit, const std::vector<GridCell>& cells);

}  // namespace impactkit::cli::mpi
