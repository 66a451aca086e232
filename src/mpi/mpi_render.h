// lueur-mpi's render: every rank opens the scene and renders its share of each round's frames into exact sums with
// all its threads; rank 0 plans the rounds (shares in proportion to each rank's measured speed), gathers the sums
// by an MPI reduction at powers of two of the frame count, at checkpoints and at the end, and writes the image.
#pragma once

#include "mpi/mpi_world.h"

namespace lueur {

/// Runs the whole program on this rank. Returns the exit status (0, or 2 after rank 0 printed one line).
int run_mpi_render(const MpiWorld& world, int argc, char** argv);

}  // namespace lueur
