#pragma once
// Virtual patches: greedy clustering of the samples inside each voxel with the
// metric of the virtual-patch method,
//   M(i,j) = (1 + |C_i - C_j|) (2 - n_i.n_j) (1 + sqrt(sum_h (F_ih - F_jh)^2 + (F_hi - F_hj)^2)),
// merging the closest pair until `patches_per_voxel` remain, or, with a total
// budget (`--patches-total`), taking the cheapest next merge of any voxel
// until the budget remains: each voxel's greedy sequence is the same, only
// where it stops differs, so flat, evenly lit voxels end with one patch and
// the patches go to curved or unevenly lit ones (on the Cornell box with the
// bunny, the bunny's vertex error at equal patch count falls 20-40%,
// docs/benchmarks.md).
//
// The form-factor term needs each sample's form factors to everything else.
// Sample-to-sample F is S x S (S = tens of thousands), so the sum over h runs
// over *targets*: the occupied voxels (or blocks of voxels when there are more
// than `max_targets`), with F from a sample to a target summed over the
// target's samples and visibility from one ray to the target's most central
// sample. By reciprocity the column term is F_{t,i} = A_i F_{i,t} / A_t, so
// one vector per sample serves both terms. Merges follow the paper's rules:
// as a source F_{(i+j),t} = (A_i F_it + A_j F_jt)/(A_i + A_j); as a receiver
// columns add.
//
// Two clusters whose normals are more than 90 degrees apart are never merged
// (their merged normal would be meaningless, e.g. the two sides of a thin
// wall); such a voxel keeps more than `patches_per_voxel` patches and the
// count is reported. Nor are two clusters with a surface between their
// samples (the floor on the two sides of that wall, SampleSeparation).
#include <cstdint>
#include <functional>
#include <vector>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"

namespace bounce {

// How a distributed bake shares the costliest part of the clustering, the
// sample-to-target form factors: the samples are cut into `parts` contiguous
// ranges of rows (sample_rows_of), this process computes the rows of range
// `part`, and `gather` (collective) copies every process's rows into place,
// so every process then holds the matrix a single process computes, bit for
// bit. Without `gather` every row is computed here.
struct SampleRowSharing {
  std::size_t part = 0;
  std::size_t parts = 1;
  // f: the ns x nt row-major matrix with this process's rows filled in.
  std::function<void(float* f, std::size_t ns, std::size_t nt)> gather;
};

// The sample rows [first, end) of range `part` of `parts` over ns samples.
struct SampleRows {
  std::size_t first = 0, end = 0;
};
SampleRows sample_rows_of(std::size_t part, std::size_t parts, std::size_t ns);

struct ClusteringSettings {
  int patches_per_voxel = 3;
  // > 0: instead of patches_per_voxel in every voxel, merge the cheapest pair
  // of the whole scene (still never across voxels) until this many patches
  // remain, so flat voxels end with one patch and curved or shaded ones keep
  // more.
  std::size_t total_patches = 0;
  // Patch density of each mesh (MeshInfo::patch_density, indexed by
  // Sample::mesh; empty, or all 1: every surface alike). A voxel's density is
  // the area-weighted mean of its samples'. Under a total budget each voxel
  // keeps density x what it keeps at density 1, times one factor for the
  // whole scene that brings the total back to the budget; with
  // patches_per_voxel it keeps density x patches_per_voxel (rounded, at
  // least 1).
  std::vector<float> mesh_density;
  std::size_t max_targets = 2048;
  SampleRowSharing sharing;
};

struct ClusteringStats {
  std::size_t feature_targets = 0;
  std::uint32_t target_block = 1;         // voxels per target along each axis
  std::uint32_t voxels_above_target = 0;  // voxels that kept more patches than asked
  // Voxels with samples on two sides of a surface between them, and such
  // pairs of samples, which no patch holds together (SampleSeparation).
  std::uint32_t voxels_with_separated_samples = 0;
  std::size_t separated_sample_pairs = 0;
};

PatchSet cluster_virtual_patches(const RayTracer& tracer, const Voxelization& vox,
                                 const SampleSet& samples, const ClusteringSettings& settings,
                                 ClusteringStats& stats, Progress* progress = nullptr);

// The voxel baseline of the published method: one patch per occupied voxel and dominant
// normal direction (+x, -x, +y, -y, +z, -z).
PatchSet voxel_patches(const SampleSet& samples);

}  // namespace bounce
