#include "distributed/mpi_compression.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "base/error.h"
#include "distributed/mpi_session.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

// Tags of the point-to-point messages of the block encoding (the bake's
// other messages use 0 .. 9).
constexpr int kCodesTag = 20;
constexpr int kWeightsTag = 21;
constexpr int kStatusTag = 22;
constexpr int kBlocksTag = 23;

// Large buffers travel in messages of at most this many bytes: an image
// strip of a large matrix exceeds MPI's 32-bit counts.
constexpr std::size_t kMessageBytes = std::size_t{1} << 26;

// A rank other than the root whose number this variable holds fails its
// block encoding, to test the failure path (tests/distributed).
constexpr const char* kFailureForTests = "BOUNCE_TEST_FAIL_BLOCK_ENCODING_ON_RANK";

void send_bytes(const void* data, std::size_t bytes, int to, int tag) {
  const auto* p = static_cast<const char*>(data);
  for (std::size_t at = 0; at < bytes; at += kMessageBytes) {
    const std::size_t part = std::min(kMessageBytes, bytes - at);
    mpi_check(MPI_Send(p + at, static_cast<int>(part), MPI_BYTE, to, tag, MPI_COMM_WORLD),
              "MPI_Send of block encoding data");
  }
}

void receive_bytes(void* data, std::size_t bytes, int from, int tag) {
  auto* p = static_cast<char*>(data);
  for (std::size_t at = 0; at < bytes; at += kMessageBytes) {
    const std::size_t part = std::min(kMessageBytes, bytes - at);
    mpi_check(MPI_Recv(p + at, static_cast<int>(part), MPI_BYTE, from, tag, MPI_COMM_WORLD,
                       MPI_STATUS_IGNORE),
              "MPI_Recv of block encoding data");
  }
}

enum class Op : int { Stop = 0, Encode = 1 };

// Broadcast by the root before each encoding: everything BlockEncoding holds.
struct Command {
  Op op = Op::Stop;
  int format = 0;  // DdsFormat
  int bc1 = 0;     // Bc1Encoder
  int bc4_per_channel = 0;
  unsigned long long width = 0;
};

// The command from the root. A rank waits for it through most of the stage
// (the root's split, ordering and error measurement), and MPI's blocking
// calls wait by polling, which on a node shared with the root (or other jobs)
// takes a core from them: the wait tests the broadcast every millisecond and
// sleeps in between. (A nonblocking broadcast matches only nonblocking ones,
// so the root's side is one too.)
void broadcast(Command& c) {
  MPI_Request request;
  mpi_check(MPI_Ibcast(&c, sizeof c, MPI_BYTE, 0, MPI_COMM_WORLD, &request), "MPI_Ibcast");
  for (;;) {
    int done = 0;
    mpi_check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

BlockEncoding encoding_of(const Command& c) {
  BlockEncoding e;
  e.width = static_cast<std::size_t>(c.width);
  e.format = static_cast<DdsFormat>(c.format);
  e.bc1 = static_cast<Bc1Encoder>(c.bc1);
  e.bc4_per_channel = c.bc4_per_channel != 0;
  return e;
}

// Codes of one block row: 4 texel rows.
std::size_t codes_per_block_row(const BlockEncoding& e) { return 4 * e.width * e.texel_channels(); }

std::size_t blocks_bytes(const BlockEncoding& e, std::size_t block_rows) {
  return e.images() * block_rows * e.block_row_bytes();
}

// A rank's answer: a status message (empty: done, else the error), then on
// success its blocks.
void send_status(const std::string& error) {
  mpi_check(MPI_Send(error.data(), static_cast<int>(error.size()), MPI_CHAR, 0, kStatusTag,
                     MPI_COMM_WORLD),
            "MPI_Send of a block encoding status");
}

std::string receive_status(int from) {
  MPI_Status status;
  mpi_check(MPI_Probe(from, kStatusTag, MPI_COMM_WORLD, &status), "MPI_Probe");
  int length = 0;
  mpi_check(MPI_Get_count(&status, MPI_CHAR, &length), "MPI_Get_count");
  std::string text(static_cast<std::size_t>(length), '\0');
  mpi_check(
      MPI_Recv(text.data(), length, MPI_CHAR, from, kStatusTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
      "MPI_Recv of a block encoding status");
  return text;
}

class MpiCompressionExecutor : public CompressionExecutor {
 public:
  MpiCompressionExecutor() { MPI_Comm_size(MPI_COMM_WORLD, &ranks_); }
  ~MpiCompressionExecutor() override {
    try {
      Command stop;
      broadcast(stop);  // the other ranks return from serve_mpi_compression
    } catch (...) {
      // An MPI failure here leaves nothing to release; mpirun ends the job.
    }
  }

  std::string description() const override {
    return text_format("by contiguous ranges of block rows on %d MPI ranks, gathered on rank 0",
                       ranks_);
  }

  std::vector<std::uint8_t> encode_blocks(const BlockEncoding& e,
                                          std::span<const std::uint8_t> codes,
                                          std::span<const float> weights) override {
    const std::size_t rows = e.block_rows(), per_row = codes_per_block_row(e);
    if (codes.size() != rows * per_row || weights.size() != codes.size())
      throw Error("compress", "block encoding: the image does not match its width");
    Command cmd;
    cmd.op = Op::Encode;
    cmd.format = static_cast<int>(e.format);
    cmd.bc1 = static_cast<int>(e.bc1);
    cmd.bc4_per_channel = e.bc4_per_channel ? 1 : 0;
    cmd.width = e.width;
    broadcast(cmd);
    const auto ranks = static_cast<std::size_t>(ranks_);
    // Each rank's rows, one rank at a time: a rank starts encoding as soon as
    // it has its rows.
    for (std::size_t r = 1; r < ranks; ++r) {
      const BlockRowRange range = block_rows_of_rank(r, ranks, rows);
      const int to = static_cast<int>(r);
      send_bytes(codes.data() + range.first * per_row, range.count() * per_row, to, kCodesTag);
      send_bytes(weights.data() + range.first * per_row, range.count() * per_row * sizeof(float),
                 to, kWeightsTag);
    }
    std::vector<std::uint8_t> blocks(blocks_bytes(e, rows));
    const BlockRowRange own = block_rows_of_rank(0, ranks, rows);
    place_block_rows(e, own.first, own.count(),
                     encode_block_rows(e, own.count(), codes.subspan(0, own.count() * per_row),
                                       weights.subspan(0, own.count() * per_row)),
                     blocks);
    // Every rank's answer is received, failures included, before any error
    // is thrown: a rank left sending would block the release that follows.
    std::string failure;
    std::vector<std::uint8_t> received;
    for (std::size_t r = 1; r < ranks; ++r) {
      const int from = static_cast<int>(r);
      const std::string error = receive_status(from);
      if (!error.empty()) {
        if (failure.empty())
          failure =
              text_format("block encoding failed on rank %zu of %zu: %s", r, ranks, error.c_str());
        continue;
      }
      const BlockRowRange range = block_rows_of_rank(r, ranks, rows);
      received.resize(blocks_bytes(e, range.count()));
      receive_bytes(received.data(), received.size(), from, kBlocksTag);
      place_block_rows(e, range.first, range.count(), received, blocks);
    }
    if (!failure.empty()) throw Error("compress", failure);
    return blocks;
  }

 private:
  int ranks_ = 1;
};

}  // namespace

BlockRowRange block_rows_of_rank(std::size_t rank, std::size_t ranks, std::size_t block_rows) {
  return {rank * block_rows / ranks, (rank + 1) * block_rows / ranks};
}

std::unique_ptr<CompressionExecutor> make_mpi_compression_executor() {
  return std::make_unique<MpiCompressionExecutor>();
}

void serve_mpi_compression() {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const char* fail = std::getenv(kFailureForTests);
  const bool fail_here = fail && std::atoi(fail) == rank;
  for (;;) {
    Command cmd;
    broadcast(cmd);
    if (cmd.op == Op::Stop) return;
    const BlockEncoding e = encoding_of(cmd);
    const std::size_t per_row = codes_per_block_row(e);
    const BlockRowRange range = block_rows_of_rank(static_cast<std::size_t>(rank),
                                                   static_cast<std::size_t>(ranks), e.block_rows());
    std::vector<std::uint8_t> codes(range.count() * per_row);
    std::vector<float> weights(range.count() * per_row);
    receive_bytes(codes.data(), codes.size(), 0, kCodesTag);
    receive_bytes(weights.data(), weights.size() * sizeof(float), 0, kWeightsTag);
    std::vector<std::uint8_t> blocks;
    std::string error;
    try {
      if (fail_here)
        throw Error("compress", std::string("failure requested by ") + kFailureForTests);
      blocks = encode_block_rows(e, range.count(), codes, weights);
      if (blocks.size() != blocks_bytes(e, range.count()))
        throw Error("compress", "block encoding returned the wrong number of blocks");
    } catch (const std::exception& ex) {
      error = ex.what();
      if (error.empty()) error = "unknown error";
    }
    send_status(error);
    if (error.empty()) send_bytes(blocks.data(), blocks.size(), 0, kBlocksTag);
  }
}

}  // namespace bounce
