#include "distributed/mpi_bake_distribution.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>

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

void MpiBakeDistribution::merge_form_factors(FormFactorMatrix& f) {
  // Entry (p, q) was computed by the rank of row min(p, q) only; the others
  // hold +0, and x + 0 = x exactly whatever the order of the sum.
  const std::size_t count = f.values.size();
  constexpr auto kChunk = static_cast<std::size_t>(std::numeric_limits<int>::max() / 2);
  for (std::size_t first = 0; first < count; first += kChunk) {
    const int part = static_cast<int>(std::min(kChunk, count - first));
    float* data = f.values.data() + first;
    const int code =
        session_.is_root()
            ? MPI_Reduce(MPI_IN_PLACE, data, part, MPI_FLOAT, MPI_SUM, 0, MPI_COMM_WORLD)
            : MPI_Reduce(data, nullptr, part, MPI_FLOAT, MPI_SUM, 0, MPI_COMM_WORLD);
    if (code != MPI_SUCCESS)
      throw Error("MPI", text_format("MPI_Reduce of the form-factor rows failed (code %d)", code));
  }
  // Each rank capped entries above 1 in its own rows only: the manifest's
  // count is their sum.
  unsigned long long clamped = f.clamped_to_one, total = 0;
  const int code = MPI_Reduce(&clamped, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0,
                              MPI_COMM_WORLD);
  if (code != MPI_SUCCESS)
    throw Error("MPI", text_format("MPI_Reduce of the clamped-entry count failed (code %d)", code));
  if (session_.is_root()) f.clamped_to_one = static_cast<std::size_t>(total);
}

std::unique_ptr<TransportExecutor> MpiBakeDistribution::transport_executor() {
  return make_scalapack_executor();
}

void MpiBakeDistribution::serve_transport() { serve_scalapack_transport(); }

}  // namespace bounce
