#include "patches/surface_patch_lookup.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"

namespace bounce {

SurfacePatchLookup::SurfacePatchLookup(const Voxelization& vox, const SampleSet& samples,
                                       const std::vector<std::int32_t>& patch_of_sample)
    : grid_(vox.grid), samples_(samples), patch_of_sample_(patch_of_sample) {
  std::vector<std::uint64_t> cell_of_voxel;
  cell_of_voxel.reserve(vox.voxels.size());
  for (const auto& v : vox.voxels) cell_of_voxel.push_back(v.cell);
  add_entries(cell_of_voxel);
}

SurfacePatchLookup::SurfacePatchLookup(const VoxelGrid& grid,
                                       const std::vector<glm::ivec3>& voxel_cells,
                                       const SampleSet& samples,
                                       const std::vector<std::int32_t>& patch_of_sample)
    : grid_(grid), samples_(samples), patch_of_sample_(patch_of_sample) {
  const glm::ivec3 dims = grid.dims();
  std::vector<std::uint64_t> cell_of_voxel;
  cell_of_voxel.reserve(voxel_cells.size());
  for (std::size_t v = 0; v < voxel_cells.size(); ++v) {
    const glm::ivec3 c = voxel_cells[v];
    if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= dims.x || c.y >= dims.y || c.z >= dims.z)
      throw Error("surface lookup", "voxel " + std::to_string(v) + " lies outside the grid");
    cell_of_voxel.push_back(grid.linear_index(c));
  }
  add_entries(cell_of_voxel);
}

// A sample carries parts of its own voxel only, so each piece's cell is its
// sample's voxel's; the piece names its triangle and side.
void SurfacePatchLookup::add_entries(const std::vector<std::uint64_t>& cell_of_voxel) {
  for (std::size_t s = 0; s < samples_.samples.size(); ++s) {
    if (s >= patch_of_sample_.size() || patch_of_sample_[s] < 0) continue;
    const std::uint32_t v = samples_.samples[s].voxel;
    if (v >= cell_of_voxel.size())
      throw Error("surface lookup", "sample " + std::to_string(s) + " names voxel " +
                                        std::to_string(v) + " of " +
                                        std::to_string(cell_of_voxel.size()));
    for (std::uint32_t k = samples_.carried_first[s]; k < samples_.carried_first[s + 1]; ++k) {
      const CarriedArea& piece = samples_.carried[k];
      if (piece.triangle == CarriedArea::kUnknownTriangle)
        throw Error("surface lookup",
                    "the bake does not say which triangle its surface pieces "
                    "lie on (made by an older bounce): bake it again");
      entries_.push_back({2ull * piece.triangle + (piece.back ? 1 : 0), cell_of_voxel[v],
                          static_cast<std::uint32_t>(s)});
    }
  }
  std::sort(entries_.begin(), entries_.end());
  entries_.erase(std::unique(entries_.begin(), entries_.end(),
                             [](const Entry& a, const Entry& b) {
                               return a.side == b.side && a.cell == b.cell && a.sample == b.sample;
                             }),
                 entries_.end());
  if (entries_.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("surface lookup", "more than 2^32 surface pieces");
  const std::size_t sides = entries_.empty() ? 0 : entries_.back().side + 1;
  side_first_.assign(sides + 1, 0);
  for (const Entry& e : entries_) ++side_first_[e.side + 1];
  for (std::size_t s = 0; s < sides; ++s) side_first_[s + 1] += side_first_[s];
}

std::int32_t SurfacePatchLookup::patch_at(std::uint32_t triangle, bool back,
                                          const glm::vec3& x) const {
  const std::int32_t s = sample_at(triangle, back, x);
  return s < 0 ? -1 : patch_of_sample_[static_cast<std::size_t>(s)];
}

std::int32_t SurfacePatchLookup::sample_at(std::uint32_t triangle, bool back,
                                           const glm::vec3& x) const {
  const std::uint64_t side = 2ull * triangle + (back ? 1 : 0);
  if (side + 1 >= side_first_.size()) return -1;
  const auto side_begin = entries_.begin() + side_first_[side];
  const auto side_end = entries_.begin() + side_first_[side + 1];
  const float hair = 1e-4f * grid_.cell_size();
  for (int k = 0; k < 7; ++k) {
    glm::vec3 y = x;
    if (k > 0) y[(k - 1) / 2] += (k % 2 ? hair : -hair);
    const std::uint64_t cell = grid_.linear_index(grid_.cell_of(y));
    const Entry lo{side, cell, 0};
    const Entry hi{side, cell, std::numeric_limits<std::uint32_t>::max()};
    auto first = std::lower_bound(side_begin, side_end, lo);
    const auto last = std::upper_bound(first, side_end, hi);
    if (first == last) continue;
    std::uint32_t best = first->sample;
    float best_d = std::numeric_limits<float>::infinity();
    for (; first != last; ++first) {
      const glm::vec3 d = samples_.samples[first->sample].position - x;
      const float d2 = glm::dot(d, d);
      if (d2 < best_d) {
        best_d = d2;
        best = first->sample;
      }
    }
    // A part no ray hit went whole to the nearest sample of its voxel facing
    // the same way, which may stand on another surface (the floor under a
    // slab, given to a sample on the slab's top): that sample's light is not
    // this point's. Such a part stands for nothing here.
    const Sample& s = samples_.samples[best];
    if (std::abs(glm::dot(s.position - x, s.normal)) > kOffSurface * grid_.cell_size()) return -1;
    return patch_of_sample_[best] < 0 ? -1 : static_cast<std::int32_t>(best);
  }
  return -1;
}

}  // namespace bounce
