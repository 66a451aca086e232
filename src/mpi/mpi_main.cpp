// lueur-mpi: the headless renderer across the ranks of an MPI job. Same options and same image bytes as
// `lueur --headless`; the window and the single-machine binary never link MPI.
#include <mpi.h>

#include "core/memory_budget.h"
#include "mpi/mpi_render.h"

int main(int argc, char** argv) {
  lueur::map_large_arrays_alone();
  MPI_Init(&argc, &argv);
  const int status = lueur::run_mpi_render(lueur::mpi_world(), argc, argv);
  MPI_Finalize();
  return status;
}
