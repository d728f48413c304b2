#pragma once
// Which patch stands for a point on the scene's surface: the point's triangle
// side and voxel cell name the triangle part; each sample carries the
// Voronoi cell of its position within the parts it stands for (samples.h), so
// the nearest sample carrying that part is the one whose piece holds the
// point, and its patch stands for it. Used where light is followed by rays:
// a ray's first hit tells which patch it lands on.
//
// A part no sample carries (unsampled surface, or a pruned patch's), or one
// carried by a sample on another surface, has no patch: light landing there
// is not represented by the bake.
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "patches/samples.h"
#include "voxel/voxelization.h"

namespace bounce {

class SurfacePatchLookup {
 public:
  // `patch_of_sample[s]`: the patch sample s belongs to, or -1 (left out).
  SurfacePatchLookup(const Voxelization& vox, const SampleSet& samples,
                     const std::vector<std::int32_t>& patch_of_sample);
  // The same from a bake read back, which keeps no voxelization: each carried
  // polygon's triangle and side (CarriedArea::triangle, back) and the cell of
  // its sample's voxel (`voxel_cells`, by Sample::voxel), since a sample
  // carries parts of its own voxel only. Throws bounce::Error when a polygon's
  // triangle is unknown (a bake made before folders kept it) or a sample names
  // a voxel `voxel_cells` does not have.
  SurfacePatchLookup(const VoxelGrid& grid, const std::vector<glm::ivec3>& voxel_cells,
                     const SampleSet& samples, const std::vector<std::int32_t>& patch_of_sample);

  // The patch standing for point x on side `back` of triangle `triangle`, or
  // -1. A point on a cell face may round into the neighbouring cell: the
  // cells a hair away along each axis are tried as well.
  std::int32_t patch_at(std::uint32_t triangle, bool back, const glm::vec3& x) const;
  // The sample whose piece holds that point (on the point's own surface), or
  // -1; patch_at is its patch.
  std::int32_t sample_at(std::uint32_t triangle, bool back, const glm::vec3& x) const;
  std::int32_t patch_of(std::uint32_t sample) const { return patch_of_sample_[sample]; }
  std::size_t sample_count() const { return samples_.samples.size(); }
  const SampleSet& samples() const { return samples_; }

  // A carrying sample farther than this (voxel sizes) from the point's
  // plane stands on another surface: no patch (samples.h).
  static constexpr float kOffSurface = kSameSurfaceCells;

 private:
  struct Entry {
    std::uint64_t side;  // 2 * triangle + back
    std::uint64_t cell;
    std::uint32_t sample;
    bool operator<(const Entry& o) const {
      return side != o.side ? side < o.side : (cell != o.cell ? cell < o.cell : sample < o.sample);
    }
  };
  // Fills and sorts entries_ from the samples' carried pieces; the cell of
  // voxel v (Sample::voxel) is cell_of_voxel[v].
  void add_entries(const std::vector<std::uint64_t>& cell_of_voxel);

  const VoxelGrid& grid_;
  const SampleSet& samples_;
  const std::vector<std::int32_t>& patch_of_sample_;
  std::vector<Entry> entries_;  // sorted
  // Entries of side s: [side_first_[s], side_first_[s + 1]). A lookup, one
  // per gather ray, searches its side's few entries, not all of them.
  std::vector<std::uint32_t> side_first_;
};

}  // namespace bounce
