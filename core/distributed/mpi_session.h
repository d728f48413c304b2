#pragma once
// This process's place in an MPI job (OpenMPI's mpirun, Slurm's srun): joins
// the job on construction and leaves it on destruction. Only the distributed
// bake uses MPI; a `bounce` started without mpirun never initialises it.
#include <string>

#include "base/error.h"

namespace bounce {

// An error every rank knows about (agreed collectively). On the root it
// carries the failing rank's message; the other ranks exit quietly, so the
// job prints one line.
class RankFailure : public Error {
 public:
  RankFailure(std::string where, const std::string& what, bool root)
      : Error(std::move(where), what), root_(root) {}
  bool reported_here() const noexcept { return root_; }

 private:
  bool root_;
};

// Throws bounce::Error naming `what` and MPI's text for `code` unless it is
// MPI_SUCCESS (an int, so this header needs no <mpi.h>).
void mpi_check(int code, const char* what);

class MpiSession {
 public:
  // True when the environment says an MPI launcher started this process
  // (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK), whatever the rank count.
  static bool launched_by_mpi();

  MpiSession();   // MPI_Init_thread (funneled: only the main thread calls MPI)
  ~MpiSession();  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  // Collective: returns when every rank passes ok. Otherwise throws
  // RankFailure on every rank; the root's names the lowest failing rank and
  // carries its message.
  void agree(bool ok, const std::string& message) const;

  // Ends the whole job (every rank) with `code`: for a failure the other
  // ranks cannot learn of in a collective (they may be waiting in one).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace bounce
