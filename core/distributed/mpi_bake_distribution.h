#pragma once
// The distributed bake: Baker's stages shared over the
// ranks of an MPI job. Every rank loads the scene, builds its own Embree BVH
// and computes the voxels, samples and patches itself (deterministic, checked
// by a fingerprint); form-factor rows are dealt out cyclically (row p to rank
// p mod R), each rank holding only its rows, and copied into place on the
// root, which gives the single-process matrix bit for bit (every entry is
// computed by exactly one rank with the same code); the transport stage's
// algebra runs on all ranks with ScaLAPACK, each holding only its share
// (scalapack_transport.h); the compression's block encoding by block rows on
// all ranks (mpi_compression.h); the rest of compression and writing stay on
// the root.
#include <map>
#include <string>

#include "bake/bake_distribution.h"
#include "distributed/mpi_session.h"

namespace bounce {

class MpiBakeDistribution : public BakeDistribution {
 public:
  explicit MpiBakeDistribution(const MpiSession& session) : session_(session) {}

  bool is_root() const override { return session_.is_root(); }
  std::size_t row_offset() const override { return static_cast<std::size_t>(session_.rank()); }
  std::size_t row_stride() const override { return static_cast<std::size_t>(session_.size()); }
  SampleRowSharing sample_row_sharing() override;
  void check_same_patches(const PatchSet& patches) override;
  FormFactorMatrix form_factors(const Scene& scene, const RayTracer& tracer,
                                const Voxelization& vox, const SampleSet& samples,
                                const PatchSet& patches, const FormFactorSettings& settings,
                                Progress* progress) override;
  std::unique_ptr<TransportExecutor> transport_executor() override;
  void serve_transport(std::vector<StageStats>& stages) override;
  std::unique_ptr<CompressionExecutor> compression_executor() override;
  void serve_compression(std::vector<StageStats>& stages) override;
  void add_other_ranks_peaks(std::vector<StageStats>& stages) const override;

 private:
  const MpiSession& session_;
  // Root: the other ranks' peak RSS per stage name (the highest), received
  // when the compression executor releases them.
  std::map<std::string, std::uint64_t> other_peaks_;
};

// A 64-bit FNV-1a hash of everything about the patches the form factors read
// (positions, normals, areas, albedos, members).
std::uint64_t patch_fingerprint(const PatchSet& patches);

}  // namespace bounce
