// MPI_COMM_WORLD, agreement and the reduction.
#include "mpi/mpi_world.h"

#include <algorithm>

namespace lueur {

MpiWorld mpi_world() {
  MpiWorld world;
  MPI_Comm_rank(MPI_COMM_WORLD, &world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world.size);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, world.rank, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &world.ranks_on_node);
  MPI_Comm_free(&node);
  return world;
}

bool all_fine(const MpiWorld& world, const std::string& error, std::string& message) {
  const int mine = error.empty() ? world.size : world.rank;
  int first = world.size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == world.size) return true;
  if (first == 0) {
    if (world.root()) message = error;
    return false;
  }
  // The failing rank tells rank 0 what went wrong.
  if (world.rank == first) {
    const uint64_t length = error.size();
    MPI_Send(&length, 1, MPI_UINT64_T, 0, 0, MPI_COMM_WORLD);
    MPI_Send(error.data(), static_cast<int>(length), MPI_CHAR, 0, 1, MPI_COMM_WORLD);
  } else if (world.root()) {
    uint64_t length = 0;
    MPI_Recv(&length, 1, MPI_UINT64_T, first, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string text(length, '\0');
    MPI_Recv(text.data(), static_cast<int>(length), MPI_CHAR, first, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    message = "rank " + std::to_string(first) + ": " + text;
  }
  return false;
}

void reduce_sum_to_root(const MpiWorld& world, std::vector<int64_t>& values) {
  // MPI counts are ints: large images go in pieces.
  constexpr size_t kPiece = size_t{1} << 28;
  for (size_t at = 0; at < values.size(); at += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, values.size() - at));
    if (world.root())
      MPI_Reduce(MPI_IN_PLACE, values.data() + at, count, MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    else
      MPI_Reduce(values.data() + at, nullptr, count, MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  }
}

}  // namespace lueur
