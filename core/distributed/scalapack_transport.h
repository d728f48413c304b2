#pragma once
// The transport stage's dense algebra on every rank of the MPI job, with
// ScaLAPACK on a 2-D block-cyclic process grid (Debian's
// libscalapack-openmpi): the series products by p?gemm, the K = infinity
// solve by p?getrf / p?getrs under the precision rule of
// solve_infinite_bounces (inverse_transport.h), with one difference: the
// condition number is computed exactly from the float32 solution
// ((I - M)^-1 = I + T) instead of estimated before solving, so a stiff system
// the lower bound let through is solved twice (float32, then float64).
//
// The root decides everything (compute_transport runs there only) and drives
// the other ranks through a small command protocol: it broadcasts a command
// and the full operands, every rank takes its block-cyclic share, calls
// ScaLAPACK collectively, and the root gathers the result. Operands are held
// whole on every rank (memory n^2 per matrix per rank): this distributes the
// O(n^3) work, not yet the memory (issue 9, part 2).
//
// Layout: the row-major buffers of transport.cpp read column-major are the
// transposes, so C = A B + beta C is computed as C^T = B^T A^T + beta C^T, and
// the solve factorises I - M^T and solves (I - M^T) T^T = M^T, exactly as
// inverse_transport.cpp hands the same buffers to LAPACK.
//
// Results differ from the single process in the order of the floating-point
// sums only (tests/distributed bound the difference).
#include <memory>
#include <string>

#include "transport/transport_executor.h"

namespace bounce {

// The process grid ScaLAPACK runs on: rows x cols = ranks, as square as the
// rank count allows (rows <= cols).
struct ProcessGridShape {
  int rows = 1;
  int cols = 1;
};
ProcessGridShape process_grid_shape(int ranks);

// Root: the executor compute_transport uses. Collective with
// serve_scalapack_transport on the other ranks; its destructor releases them.
std::unique_ptr<TransportExecutor> make_scalapack_executor();

// Not the root: follows the root's commands until its executor is destroyed.
void serve_scalapack_transport();

}  // namespace bounce
