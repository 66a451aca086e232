// The little of MPI that lueur-mpi needs, wrapped: who this rank is, agreeing that every rank is fine before going
// on (so that a bad option or a missing file ends every rank cleanly, with one line from rank 0), broadcasts of
// plain values, and the exact sums' reduction. Only src/mpi includes MPI.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace lueur {

struct MpiWorld {
  int rank = 0;
  int size = 1;
  int ranks_on_node = 1;  ///< ranks sharing this rank's machine (they share its cores)
  bool root() const { return rank == 0; }
};

/// This process's place in MPI_COMM_WORLD (after MPI_Init).
MpiWorld mpi_world();

/// Collective: every rank passes its error ("" when fine). Returns true when all are fine; otherwise false on every
/// rank, and on rank 0 `message` is the lowest failing rank's error ("rank N: ..." when it is not rank 0's own).
bool all_fine(const MpiWorld& world, const std::string& error, std::string& message);

/// Broadcasts a plain value (or a vector of them, of the same size everywhere) from rank 0.
template <typename T>
void broadcast(T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  MPI_Bcast(&value, sizeof(T), MPI_BYTE, 0, MPI_COMM_WORLD);
}
template <typename T>
void broadcast(std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  MPI_Bcast(values.data(), static_cast<int>(values.size() * sizeof(T)), MPI_BYTE, 0, MPI_COMM_WORLD);
}

/// Gathers one plain value from every rank on rank 0 (elsewhere the result is empty).
template <typename T>
std::vector<T> gather(const MpiWorld& world, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<T> all(world.root() ? static_cast<size_t>(world.size) : 0);
  MPI_Gather(&value, sizeof(T), MPI_BYTE, all.data(), sizeof(T), MPI_BYTE, 0, MPI_COMM_WORLD);
  return all;
}

/// Sums `values` over every rank into rank 0's `values` (elsewhere they are left as they were). Integer sums: the
/// result does not depend on the order MPI adds them in.
void reduce_sum_to_root(const MpiWorld& world, std::vector<int64_t>& values);

}  // namespace lueur
