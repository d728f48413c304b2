#include "distributed/mpi_bake_distribution.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "distributed/mpi_compression.h"
#include "distributed/scalapack_transport.h"
#include "transport/text_format.h"

namespace bounce {

namespace {

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
};

// Tags of the point-to-point messages to the root.
constexpr int kRowsTag = 1;
constexpr int kStagesTag = 2;

// Form-factor rows travel to the root in messages of whole rows of about
// this many floats (4 MB): the root's receive buffer stays small and the
// messages large enough for the transfer to run at speed.
constexpr std::size_t kMessageFloats = std::size_t{1} << 20;

// The own rows k = first .. end-1 of `rows` that go in one message: whole
// rows, at least one, up to kMessageFloats floats. The root computes the
// same grouping for every rank from (n, offset, stride) alone.
struct RowGroup {
  std::size_t first = 0, end = 0;  // own-row indices
  std::size_t floats = 0;
};

std::vector<RowGroup> row_groups(std::size_t n, std::size_t offset, std::size_t stride) {
  std::vector<RowGroup> groups;
  RowGroup g;
  std::size_t k = 0;
  for (std::size_t p = offset; p < n; p += stride, ++k) {
    const std::size_t length = FormFactorRows::segment_length(n, p);
    if (g.end > g.first && g.floats + length > kMessageFloats) {
      groups.push_back(g);
      g = RowGroup{k, k, 0};
    }
    g.end = k + 1;
    g.floats += length;
  }
  if (g.end > g.first) groups.push_back(g);
  return groups;
}

int message_count(std::size_t floats) {
  if (floats > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("MPI", "a message of form-factor rows exceeds the 32-bit MPI count");
  return static_cast<int>(floats);
}

// The root: puts the compact rows `segments` (own rows first .. end-1 of the
// rank dealt rows offset, offset + stride, ...) in their places in f.
void place_rows(const float* segments, const RowGroup& group, std::size_t offset,
                std::size_t stride, FormFactorMatrix& f) {
  const std::size_t n = f.n;
  float* values = f.values.data();
  for (std::size_t k = group.first; k < group.end; ++k) {
    const std::size_t p = offset + k * stride;
    for (std::size_t q = p; q < n; ++q) values[p * n + q] = segments[q - p];
    const float* column = segments + (n - p);
    for (std::size_t q = p + 1; q < n; ++q) values[q * n + p] = column[q - p - 1];
    segments += FormFactorRows::segment_length(n, p);
  }
}

// A stage list as one message: per stage, its name, a zero byte and its peak
// RSS (8 bytes).
std::vector<char> pack_stages(const std::vector<StageStats>& stages) {
  std::vector<char> bytes;
  for (const StageStats& s : stages) {
    bytes.insert(bytes.end(), s.name.begin(), s.name.end());
    bytes.push_back('\0');
    const std::uint64_t peak = s.peak_rss_bytes;
    const auto* raw = reinterpret_cast<const char*>(&peak);
    bytes.insert(bytes.end(), raw, raw + sizeof peak);
  }
  return bytes;
}

void unpack_stages(const std::vector<char>& bytes, std::map<std::string, std::uint64_t>& peak) {
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::size_t end =
        std::find(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end(), '\0') -
        bytes.begin();
    if (end + 1 + sizeof(std::uint64_t) > bytes.size()) break;  // malformed: ignore the rest
    std::uint64_t value = 0;
    std::memcpy(&value, bytes.data() + end + 1, sizeof value);
    std::uint64_t& slot = peak[std::string(bytes.data() + at, end - at)];
    slot = std::max(slot, value);
    at = end + 1 + sizeof value;
  }
}

// The root's compression executor: the MPI one, and once it has released
// the other ranks, their stage peaks (each sends them when released, so the
// root receives them on every path, errors included).
class ReleasingCompressionExecutor : public CompressionExecutor {
 public:
  ReleasingCompressionExecutor(std::unique_ptr<CompressionExecutor> inner, int ranks,
                               std::map<std::string, std::uint64_t>& other_peaks)
      : inner_(std::move(inner)), ranks_(ranks), other_peaks_(other_peaks) {}
  ~ReleasingCompressionExecutor() override {
    inner_.reset();  // Stop: the other ranks leave serve_compression
    try {
      for (int r = 1; r < ranks_; ++r) {
        MPI_Status status;
        mpi_check(MPI_Probe(r, kStagesTag, MPI_COMM_WORLD, &status), "MPI_Probe");
        int count = 0;
        mpi_check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
        std::vector<char> bytes(static_cast<std::size_t>(count));
        mpi_check(MPI_Recv(bytes.data(), count, MPI_CHAR, r, kStagesTag, MPI_COMM_WORLD,
                           MPI_STATUS_IGNORE),
                  "MPI_Recv of stage statistics");
        unpack_stages(bytes, other_peaks_);
      }
    } catch (...) {
      // The statistics are for the manifest only; an MPI failure ends the job.
    }
  }
  std::vector<std::uint8_t> encode_blocks(const BlockEncoding& e,
                                          std::span<const std::uint8_t> codes,
                                          std::span<const float> weights) override {
    return inner_->encode_blocks(e, codes, weights);
  }
  std::string description() const override { return inner_->description(); }

 private:
  std::unique_ptr<CompressionExecutor> inner_;
  int ranks_;
  std::map<std::string, std::uint64_t>& other_peaks_;
};

}  // namespace

std::uint64_t patch_fingerprint(const PatchSet& patches) {
  Fnv1a f;
  const std::size_t n = patches.size();
  f.add(&n, sizeof n);
  for (const Patch& p : patches.patches) {
    f.add(&p.position, sizeof p.position);
    f.add(&p.normal, sizeof p.normal);
    f.add(&p.albedo, sizeof p.albedo);
    f.add(&p.area, sizeof p.area);
  }
  f.add(patches.member_first.data(), patches.member_first.size() * sizeof(std::uint32_t));
  f.add(patches.member_samples.data(), patches.member_samples.size() * sizeof(std::uint32_t));
  return f.h;
}

SampleRowSharing MpiBakeDistribution::sample_row_sharing() {
  SampleRowSharing s;
  s.part = static_cast<std::size_t>(session_.rank());
  s.parts = static_cast<std::size_t>(session_.size());
  const std::size_t parts = s.parts;
  // Every rank's rows copied into place on every rank: the same matrix as
  // one process's, bit for bit (each row is computed by one rank, with the
  // same code).
  s.gather = [parts](float* f, std::size_t ns, std::size_t nt) {
    std::vector<int> counts(parts), offsets(parts);
    for (std::size_t r = 0; r < parts; ++r) {
      const SampleRows rows = sample_rows_of(r, parts, ns);
      counts[r] = message_count((rows.end - rows.first) * nt);
      offsets[r] = message_count(rows.first * nt);
    }
    mpi_check(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, f, counts.data(), offsets.data(),
                             MPI_FLOAT, MPI_COMM_WORLD),
              "MPI_Allgatherv of the clustering's form factors");
  };
  return s;
}

void MpiBakeDistribution::check_same_patches(const PatchSet& patches) {
  const std::uint64_t mine = patch_fingerprint(patches);
  std::uint64_t lowest = 0, highest = 0;
  MPI_Allreduce(&mine, &lowest, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &highest, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
  if (lowest != highest)
    throw RankFailure("distributed bake",
                      "the ranks computed different patches from the same scene and settings "
                      "(different bounce builds or libraries on the nodes?); nothing was written",
                      session_.is_root());
}

FormFactorMatrix MpiBakeDistribution::form_factors(
    const Scene& scene, const RayTracer& tracer, const Voxelization& vox, const SampleSet& samples,
    const PatchSet& patches, const FormFactorSettings& settings, Progress* progress) {
  // Entry (p, q) is computed by the rank of row min(p, q) only, with the same
  // code as one process: copying it into place gives the single-process
  // matrix bit for bit.
  const auto ranks = static_cast<std::size_t>(session_.size());
  FormFactorMatrix f;
  std::size_t clamped = 0;
  if (session_.is_root()) {
    // The root's own rows straight into the full matrix; the others' rows
    // into their places as they arrive, rank by rank.
    f = compute_form_factors(scene, tracer, vox, samples, patches, settings, progress);
    clamped = f.clamped_to_one;
    std::vector<float> buffer;
    for (std::size_t r = 1; r < ranks; ++r)
      for (const RowGroup& g : row_groups(f.n, r, ranks)) {
        buffer.resize(g.floats);
        mpi_check(MPI_Recv(buffer.data(), message_count(g.floats), MPI_FLOAT, static_cast<int>(r),
                           kRowsTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
                  "MPI_Recv of form-factor rows");
        place_rows(buffer.data(), g, r, ranks, f);
      }
  } else {
    // Only this rank's rows (about n^2 / ranks floats), sent and dropped.
    FormFactorRows rows =
        compute_form_factor_rows(scene, tracer, vox, samples, patches, settings, progress);
    clamped = rows.clamped_to_one;
    f.n = rows.n;
    for (const RowGroup& g : row_groups(rows.n, rows.row_offset, rows.row_stride))
      mpi_check(MPI_Send(rows.values.data() + rows.first[g.first], message_count(g.floats),
                         MPI_FLOAT, 0, kRowsTag, MPI_COMM_WORLD),
                "MPI_Send of form-factor rows");
  }
  // Each rank capped entries above 1 in its own rows only: the manifest's
  // count is their sum.
  unsigned long long mine = clamped, total = 0;
  mpi_check(MPI_Reduce(&mine, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD),
            "MPI_Reduce of the clamped-entry count");
  if (session_.is_root()) f.clamped_to_one = static_cast<std::size_t>(total);
  return f;
}

std::unique_ptr<TransportExecutor> MpiBakeDistribution::transport_executor() {
  return make_scalapack_executor();
}

void MpiBakeDistribution::serve_transport(std::vector<StageStats>& stages) {
  const StageTimer timer("transport");
  serve_scalapack_transport();
  stages.push_back(timer.finish());
}

std::unique_ptr<CompressionExecutor> MpiBakeDistribution::compression_executor() {
  return std::make_unique<ReleasingCompressionExecutor>(make_mpi_compression_executor(),
                                                        session_.size(), other_peaks_);
}

void MpiBakeDistribution::serve_compression(std::vector<StageStats>& stages) {
  const StageTimer timer("compress");
  serve_mpi_compression();
  stages.push_back(timer.finish());
  const std::vector<char> bytes = pack_stages(stages);
  mpi_check(
      MPI_Send(bytes.data(), message_count(bytes.size()), MPI_CHAR, 0, kStagesTag, MPI_COMM_WORLD),
      "MPI_Send of stage statistics");
}

void MpiBakeDistribution::add_other_ranks_peaks(std::vector<StageStats>& stages) const {
  for (StageStats& s : stages) {
    const auto found = other_peaks_.find(s.name);
    if (found == other_peaks_.end()) continue;
    s.peak_rss_bytes_other_ranks = found->second;
  }
}

}  // namespace bounce
