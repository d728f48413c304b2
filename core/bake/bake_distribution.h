#pragma once
// How Baker::run shares its stages with other processes (core/distributed:
// MPI ranks). Every process runs the same pipeline on the same scene up to the
// form factors; each computes only its share of the form-factor rows, holding
// only those, and form_factors gathers the full matrix on the root. The root then runs
// the rest of the bake, handing the dense algebra of the transport stage to
// transport_executor() and the block encoding of the compression stage to
// compression_executor(); the other processes serve those executors
// (serve_transport, then serve_compression) and return without a result. Without a distribution
// (nullptr) Baker::run is the single-process bake, unchanged.
#include <cstdint>
#include <memory>
#include <vector>

#include "base/progress.h"
#include "base/stage_stats.h"
#include "compress/codec.h"
#include "formfactor/form_factors.h"
#include "patches/clustering.h"
#include "patches/patch_set.h"
#include "transport/transport_executor.h"

namespace bounce {

class BakeDistribution {
 public:
  virtual ~BakeDistribution() = default;
  virtual bool is_root() const = 0;
  // This process's share of the clustering's sample-to-target form factors
  // (clustering.h), gathered on every process.
  virtual SampleRowSharing sample_row_sharing() = 0;
  // The form-factor rows this process computes (FormFactorSettings).
  virtual std::size_t row_offset() const = 0;
  virtual std::size_t row_stride() const = 0;
  // Collective; throws on every process when the processes computed
  // different patches (each computes them for itself, and rows computed for
  // different patches would not fit together).
  virtual void check_same_patches(const PatchSet& patches) = 0;
  // Collective: computes this process's rows (settings.row_offset,
  // row_stride) and gathers every process's rows into the full matrix on the
  // root. The other processes hold only their own rows and return a matrix
  // with n set and no values.
  virtual FormFactorMatrix form_factors(const Scene& scene, const RayTracer& tracer,
                                        const Voxelization& vox, const SampleSet& samples,
                                        const PatchSet& patches, const FormFactorSettings& settings,
                                        Progress* progress) = 0;
  // Root: the executor the transport stage uses; its destruction releases
  // the other processes from serve_transport.
  virtual std::unique_ptr<TransportExecutor> transport_executor() = 0;
  // Not the root: takes part in the root's products and solves until the
  // root's executor is destroyed, as a stage of its own ("transport")
  // appended to `stages`.
  virtual void serve_transport(std::vector<StageStats>& stages) = 0;
  // Root: the executor the compression stage's block encoding uses. Create
  // it with transport_executor() and destroy it after that one (however the
  // bake ends): its destruction releases the other processes from
  // serve_compression and receives their stages' peak memory.
  virtual std::unique_ptr<CompressionExecutor> compression_executor() = 0;
  // Not the root, after serve_transport: encodes the root's block rows until
  // its compression executor is destroyed, as a stage of its own
  // ("compress"); then sends every stage's peak memory to the root.
  virtual void serve_compression(std::vector<StageStats>& stages) = 0;
  // Root, once its compression executor is destroyed: each stage's peak
  // memory over the other processes, by stage name
  // (StageStats::peak_rss_bytes_other_ranks).
  virtual void add_other_ranks_peaks(std::vector<StageStats>& stages) const = 0;
};

}  // namespace bounce
