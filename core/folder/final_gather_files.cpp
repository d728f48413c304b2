#include "folder/final_gather_files.h"

#include <algorithm>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "base/error.h"
#include "folder/bake_format.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;

std::string gather_file_name(const char* prefix, const char* vertex_name) {
  const std::string_view name(vertex_name), base(bake_file::kGatherPrefix);
  return std::string(prefix) + std::string(name.substr(base.size()));
}

void write_final_gather(const fs::path& dir, const FinalGather& g) {
  write_final_gather(dir, g, bake_file::kGatherPrefix);
}

std::optional<FinalGather> read_final_gather(const fs::path& dir, std::size_t patches,
                                             std::size_t samples) {
  return read_final_gather(dir, patches, samples, bake_file::kGatherPrefix);
}

void write_final_gather(const fs::path& dir, const FinalGather& g, const char* prefix) {
  const auto file = [&dir, prefix](const char* name) {
    return dir / gather_file_name(prefix, name);
  };
  if (g.source.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error(file(bake_file::kGatherFirst).string(),
                "the final gather has more than 2^32 entries: too many for its row starts");
  std::vector<std::uint32_t> first(g.first.begin(), g.first.end());
  write_npy(file(bake_file::kGatherFirst), first, {first.size()});
  write_npy(file(bake_file::kGatherSource), g.source, {g.source.size()});
  write_npy(file(bake_file::kGatherWeight), g.weight, {g.weight.size()});
  write_npy(file(bake_file::kGatherCluster), g.cluster_of_patch, {g.cluster_of_patch.size()});
  write_npy(file(bake_file::kGatherShare), g.cluster_share, {g.cluster_share.size()});
  if (!g.seen_first.empty()) {
    write_npy(file(bake_file::kGatherSeenFirst), g.seen_first, {g.seen_first.size()});
    write_npy(file(bake_file::kGatherSeenSample), g.seen_sample, {g.seen_sample.size()});
    write_npy(file(bake_file::kGatherSeenWeight), g.seen_weight, {g.seen_weight.size()});
  }
  if (g.near.size() == 0) return;
  const auto rows = [](const std::vector<glm::vec3>& v) {
    return std::span<const float>(reinterpret_cast<const float*>(v.data()), 3 * v.size());
  };
  write_npy(file(bake_file::kGatherNearPosition), rows(g.near.position), {g.near.size(), 3});
  write_npy(file(bake_file::kGatherNearNormal), rows(g.near.normal), {g.near.size(), 3});
  write_npy(file(bake_file::kGatherNearAlbedo), rows(g.near.albedo), {g.near.size(), 3});
  write_npy(file(bake_file::kGatherNearPatch), g.near.patch, {g.near.size()});
  if (g.spot_first.empty()) return;
  write_npy(file(bake_file::kGatherSpotFirst), g.spot_first, {g.spot_first.size()});
  write_npy(file(bake_file::kGatherSpotWeight), g.spot_weight, {g.spot_weight.size()});
}

std::optional<FinalGather> read_final_gather(const fs::path& dir, std::size_t patches,
                                             std::size_t samples, const char* prefix) {
  const auto file = [&dir, prefix](const char* name) {
    return dir / gather_file_name(prefix, name);
  };
  if (!fs::exists(file(bake_file::kGatherFirst))) return std::nullopt;
  // Each file one-dimensional, read whole.
  const auto vector_of = [&file](const char* name, auto reader) {
    const fs::path path = file(name);
    auto array = reader(path);
    if (array.shape.size() != 1) throw Error(path.string(), "expected a one-dimensional array");
    return std::move(array.data);
  };
  const auto u32 = [](const fs::path& f) { return read_npy_u32(f); };
  const auto f32 = [](const fs::path& f) { return read_npy_f32(f); };
  FinalGather g;
  const std::vector<std::uint32_t> first = vector_of(bake_file::kGatherFirst, u32);
  g.first.assign(first.begin(), first.end());
  g.source = vector_of(bake_file::kGatherSource, u32);
  g.weight = vector_of(bake_file::kGatherWeight, f32);
  g.cluster_of_patch = vector_of(bake_file::kGatherCluster, u32);
  g.cluster_share = vector_of(bake_file::kGatherShare, f32);
  const fs::path cluster_file = file(bake_file::kGatherCluster);
  g.patches = patches;
  if (g.cluster_of_patch.size() != patches)
    throw Error(cluster_file.string(), "expected one cluster per patch (" +
                                           std::to_string(patches) + "), found " +
                                           std::to_string(g.cluster_of_patch.size()));
  std::size_t clusters = 0;
  for (const std::uint32_t c : g.cluster_of_patch)
    clusters = std::max<std::size_t>(clusters, std::size_t{c} + 1);
  // Clusters are numbered densely and each holds at least one patch, so a
  // larger number is damage -- and would size every frame's light buffer.
  if (clusters > patches)
    throw Error(cluster_file.string(), "names cluster " + std::to_string(clusters - 1) + ", but " +
                                           std::to_string(patches) +
                                           " patches make at most that many clusters");
  g.clusters = clusters;
  // Sources past the clusters are samples, then near sources (validate()
  // checks the range).
  for (const std::uint32_t s : g.source)
    if (s >= patches + clusters) {
      g.samples = samples;
      break;
    }
  if (fs::exists(file(bake_file::kGatherNearPatch))) {
    g.samples = samples;
    const auto rows = [&file](const char* name) {
      const fs::path path = file(name);
      auto array = read_npy_f32(path);
      if (array.shape.size() != 2 || array.shape[1] != 3)
        throw Error(path.string(), "expected an array of shape [near sources, 3]");
      std::vector<glm::vec3> out(array.shape[0]);
      for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = glm::vec3(array.data[3 * i], array.data[3 * i + 1], array.data[3 * i + 2]);
      return out;
    };
    g.near.patch = vector_of(bake_file::kGatherNearPatch, u32);
    g.near.position = rows(bake_file::kGatherNearPosition);
    g.near.normal = rows(bake_file::kGatherNearNormal);
    g.near.albedo = rows(bake_file::kGatherNearAlbedo);
    if (g.near.position.size() != g.near.patch.size() ||
        g.near.normal.size() != g.near.patch.size() || g.near.albedo.size() != g.near.patch.size())
      throw Error(file(bake_file::kGatherNearPatch).string(),
                  "the near sources' files differ in length");
  }
  // Seen weights (bakes made before them have none: patches read their own
  // light).
  if (fs::exists(file(bake_file::kGatherSeenFirst))) {
    g.seen_first = vector_of(bake_file::kGatherSeenFirst, u32);
    g.seen_sample = vector_of(bake_file::kGatherSeenSample, u32);
    g.seen_weight = vector_of(bake_file::kGatherSeenWeight, f32);
    g.samples = samples;
  }
  // Spots (bakes made before them have none: samples are lit at their
  // centres).
  if (fs::exists(file(bake_file::kGatherSpotFirst))) {
    g.spot_first = vector_of(bake_file::kGatherSpotFirst, u32);
    g.spot_weight = vector_of(bake_file::kGatherSpotWeight, f32);
    g.samples = samples;
    if (g.spot_first.size() != samples + 1)
      throw Error(file(bake_file::kGatherSpotFirst).string(),
                  "expected one row start per sample and one more (" + std::to_string(samples + 1) +
                      "), found " + std::to_string(g.spot_first.size()));
    if (g.spot_weight.size() != g.spot_first.back() || g.spot_first.back() > g.near.size())
      throw Error(file(bake_file::kGatherSpotWeight).string(),
                  "expected " + std::to_string(g.spot_first.back()) + " spot weights within " +
                      std::to_string(g.near.size()) + " near sources, found " +
                      std::to_string(g.spot_weight.size()) + " weights");
    g.near.spot_count = g.spot_first.back();
  }
  g.validate((dir / (std::string(prefix) + "*.npy")).string());
  g.compact_rows();
  return g;
}

}  // namespace bounce
