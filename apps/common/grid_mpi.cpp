#include "common/grid_mpi.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <sstream>
#include <thread>

namespace impactkit::cli::mpi {
namespace {

constexpr int kRequestTag = 1;  ///< a rank asks for a unit (no payload)
constexpr int kUnitTag = 2;     ///< rank 0's answer: a unit number, -1 to stop
constexpr int kResultTag = 3;   ///< a finished unit: "unit\n" then a CellToText line per cell

}  // namespace

std::pair<int, int> Start() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  if (provided < MPI_THREAD_SERIALIZED) {
    Abort("this MPI library does not support calls from several threads, one at a time");
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  return {rank, ranks};
}

void Finish() { MPI_Finalize(); }

void Abort(const std::string& message) {
  fmt::print(stderr, "impactkit: error: {}\n", message);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();  // MPI_Abort does not return; this tells the compiler so
}

bool Agree(bool ok) {
  int value = ok ? 1 : 0;
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value != 0;
}

void Serve(int ranks, const std::function<int()>& take,
           const std::function<void(int, std::vector<GridCell>&)>& receive) {
  int stopped = 0;
  while (stopped < ranks - 1) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      // Polling with a pause instead of a blocking receive: Open MPI's
      // blocking receive spins, which would take a core from rank 0's own
      // worker threads.
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (status.MPI_TAG == kRequestTag) {
      MPI_Recv(nullptr, 0, MPI_CHAR, status.MPI_SOURCE, kRequestTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      int unit = take();
      MPI_Send(&unit, 1, MPI_INT, status.MPI_SOURCE, kUnitTag, MPI_COMM_WORLD);
      if (unit < 0) ++stopped;
      continue;
    }
    int size = 0;
    MPI_Get_count(&status, MPI_CHAR, &size);
    std::string text(static_cast<std::size_t>(size), '\0');
    MPI_Recv(text.data(), size, MPI_CHAR, status.MPI_SOURCE, kResultTag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    std::istringstream lines(text);
    int unit = -1;
    lines >> unit;
    std::vector<GridCell> cells;
    std::string line;
    std::getline(lines, line);  // the rest of the unit's line
    while (std::getline(lines, line)) cells.push_back(CellFromText(line));
    receive(unit, cells);
  }
}

int Request() {
  MPI_Send(nullptr, 0, MPI_CHAR, 0, kRequestTag, MPI_COMM_WORLD);
  int unit = -1;
  MPI_Recv(&unit, 1, MPI_INT, 0, kUnitTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return unit;
}

void Send(int unit, const std::vector<GridCell>& cells) {
  std::string text = fmt::format("{}\n", unit);
  for (const GridCell& cell : cells) text += CellToText(cell) + "\n";
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kResultTag, MPI_COMM_WORLD);
}

}  // namespace impactkit::cli::mpi
