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
// the other ranks through a small command protocol: it broadcasts a command,
// sends each rank only its block-cyclic share of the operands (packed by the
// root, one rank at a time), every rank calls ScaLAPACK collectively, and the
// root receives the shares of the result the same way. Whole matrices exist
// on the root only; the other ranks hold about n^2 / ranks entries per
// operand. (Packing by hand rather than p?gemr2d from a 1 x 1 grid on the
// root: the root's extra memory is then exactly one share, the float shares
// are converted to I - M^T and to float64 on each rank, and the gather is the
// same code reversed.)
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
