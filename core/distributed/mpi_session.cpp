#include "distributed/mpi_session.h"

#include <mpi.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace bounce {

void mpi_check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw Error(
      "MPI", std::string(what) + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

bool MpiSession::launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
      throw Error("MPI", "MPI_Init_thread failed: cannot join the MPI job");
  }
  // Errors come back as codes we turn into messages, not as aborts inside MPI.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
}

void MpiSession::agree(bool ok, const std::string& message) const {
  // The lowest failing rank, or size_ when none failed.
  int mine = ok ? size_ : rank_, first = size_;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size_) return;
  // The failing rank's message travels to the root.
  std::string text = message;
  if (first != 0) {
    if (rank_ == first) {
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, 0, MPI_COMM_WORLD);
    } else if (rank_ == 0) {
      MPI_Status status;
      MPI_Probe(first, 0, MPI_COMM_WORLD, &status);
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      text.assign(static_cast<std::size_t>(length), '\0');
      MPI_Recv(text.data(), length, MPI_CHAR, first, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
  }
  const std::string where =
      first == 0 ? std::string() : "rank " + std::to_string(first) + " of " + std::to_string(size_);
  throw RankFailure(where, text, rank_ == 0);
}

void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; for the compiler
}

}  // namespace bounce
