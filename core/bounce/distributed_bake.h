#pragma once
// Public: one bake shared by the processes of an MPI job (docs/cluster.md).
// Only with the library bounce_distributed, which the build makes when MPI
// and ScaLAPACK are installed (it then defines BOUNCE_HAVE_MPI).
//
//   if (bounce::MpiSession::launched_by_mpi()) {
//     const bounce::MpiSession mpi;              // joins the job
//     bounce::MpiBakeDistribution distribution(mpi);
//     baker.set_distribution(&distribution);     // every rank runs the Baker
//     ...baker.run(progress); only mpi.is_root() writes the bake
//   }
//
// The result is the single-process bake's; a failure on any rank reaches
// every rank (MpiSession::agree) so that none waits for the others forever.
#include "distributed/mpi_bake_distribution.h"
#include "distributed/mpi_session.h"
