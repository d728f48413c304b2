#include "bake/final_gather_files.h"

#include <limits>

#include "base/error.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;

void write_final_gather(const fs::path& dir, const FinalGather& g) {
  if (g.source.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error((dir / "gather_first.npy").string(),
                "the final gather has more than 2^32 entries: too many for its row starts");
  std::vector<std::uint32_t> first(g.first.begin(), g.first.end());
  write_npy(dir / "gather_first.npy", first, {first.size()});
  write_npy(dir / "gather_source.npy", g.source, {g.source.size()});
  write_npy(dir / "gather_weight.npy", g.weight, {g.weight.size()});
  write_npy(dir / "gather_cluster.npy", g.cluster_of_patch, {g.cluster_of_patch.size()});
  write_npy(dir / "gather_share.npy", g.cluster_share, {g.cluster_share.size()});
}

std::optional<FinalGather> read_final_gather(const fs::path& dir, std::size_t patches) {
  if (!fs::exists(dir / "gather_first.npy")) return std::nullopt;
  const auto one_dimensional = [](const fs::path& file, const std::vector<std::size_t>& shape) {
    if (shape.size() != 1) throw Error(file.string(), "expected a one-dimensional array");
  };
  FinalGather g;
  const fs::path first_file = dir / "gather_first.npy";
  const NpyArray<std::uint32_t> first = read_npy_u32(first_file);
  one_dimensional(first_file, first.shape);
  g.first.assign(first.data.begin(), first.data.end());
  const fs::path source_file = dir / "gather_source.npy";
  NpyArray<std::uint32_t> source = read_npy_u32(source_file);
  one_dimensional(source_file, source.shape);
  g.source = std::move(source.data);
  const fs::path weight_file = dir / "gather_weight.npy";
  NpyArray<float> weight = read_npy_f32(weight_file);
  one_dimensional(weight_file, weight.shape);
  g.weight = std::move(weight.data);
  const fs::path cluster_file = dir / "gather_cluster.npy";
  NpyArray<std::uint32_t> cluster = read_npy_u32(cluster_file);
  one_dimensional(cluster_file, cluster.shape);
  g.cluster_of_patch = std::move(cluster.data);
  const fs::path share_file = dir / "gather_share.npy";
  NpyArray<float> share = read_npy_f32(share_file);
  one_dimensional(share_file, share.shape);
  g.cluster_share = std::move(share.data);
  g.patches = patches;
  if (g.cluster_of_patch.size() != patches)
    throw Error(cluster_file.string(), "expected one cluster per patch (" +
                                           std::to_string(patches) + "), found " +
                                           std::to_string(g.cluster_of_patch.size()));
  std::size_t clusters = 0;
  for (const std::uint32_t c : g.cluster_of_patch)
    clusters = std::max<std::size_t>(clusters, std::size_t{c} + 1);
  g.clusters = clusters;
  g.validate((dir / "gather_*.npy").string());
  return g;
}

}  // namespace bounce
