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

namespace {

// The paths of one gather's files: the vertices' names under `prefix`.
struct GatherFiles {
  const fs::path& dir;
  const char* prefix;
  fs::path operator()(const char* name) const { return dir / gather_file_name(prefix, name); }
};

// A one-dimensional array, read whole.
template <typename Reader>
auto read_vector(const GatherFiles& files, const char* name, Reader reader) {
  const fs::path file = files(name);
  auto array = reader(file);
  if (array.shape.size() != 1) throw Error(file.string(), "expected a one-dimensional array");
  return std::move(array.data);
}

std::vector<std::uint32_t> read_u32(const GatherFiles& files, const char* name) {
  return read_vector(files, name, [](const fs::path& f) { return read_npy_u32(f); });
}

std::vector<float> read_f32(const GatherFiles& files, const char* name) {
  return read_vector(files, name, [](const fs::path& f) { return read_npy_f32(f); });
}

// An array of shape [near sources, 3].
std::vector<glm::vec3> read_rows(const GatherFiles& files, const char* name) {
  const fs::path file = files(name);
  auto array = read_npy_f32(file);
  if (array.shape.size() != 2 || array.shape[1] != 3)
    throw Error(file.string(), "expected an array of shape [near sources, 3]");
  std::vector<glm::vec3> out(array.shape[0]);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = glm::vec3(array.data[3 * i], array.data[3 * i + 1], array.data[3 * i + 2]);
  return out;
}

// The patches' clusters and shares; the cluster count from the numbers.
void read_clusters(const GatherFiles& files, std::size_t patches, FinalGather& g) {
  g.cluster_of_patch = read_u32(files, bake_file::kGatherCluster);
  g.cluster_share = read_f32(files, bake_file::kGatherShare);
  const fs::path cluster_file = files(bake_file::kGatherCluster);
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
}

void read_near_sources(const GatherFiles& files, FinalGather& g) {
  g.near.patch = read_u32(files, bake_file::kGatherNearPatch);
  g.near.position = read_rows(files, bake_file::kGatherNearPosition);
  g.near.normal = read_rows(files, bake_file::kGatherNearNormal);
  g.near.albedo = read_rows(files, bake_file::kGatherNearAlbedo);
  if (g.near.position.size() != g.near.patch.size() ||
      g.near.normal.size() != g.near.patch.size() || g.near.albedo.size() != g.near.patch.size())
    throw Error(files(bake_file::kGatherNearPatch).string(),
                "the near sources' files differ in length");
}

// After the near sources: the spots are the last of them.
void read_spots(const GatherFiles& files, std::size_t samples, FinalGather& g) {
  g.spot_first = read_u32(files, bake_file::kGatherSpotFirst);
  g.spot_weight = read_f32(files, bake_file::kGatherSpotWeight);
  if (g.spot_first.size() != samples + 1)
    throw Error(files(bake_file::kGatherSpotFirst).string(),
                "expected one row start per sample and one more (" + std::to_string(samples + 1) +
                    "), found " + std::to_string(g.spot_first.size()));
  if (g.spot_weight.size() != g.spot_first.back() || g.spot_first.back() > g.near.size())
    throw Error(files(bake_file::kGatherSpotWeight).string(),
                "expected " + std::to_string(g.spot_first.back()) + " spot weights within " +
                    std::to_string(g.near.size()) + " near sources, found " +
                    std::to_string(g.spot_weight.size()) + " weights");
  g.near.spot_count = g.spot_first.back();
}

}  // namespace

std::optional<FinalGather> read_final_gather(const fs::path& dir, std::size_t patches,
                                             std::size_t samples, const char* prefix) {
  const GatherFiles files{dir, prefix};
  if (!fs::exists(files(bake_file::kGatherFirst))) return std::nullopt;
  FinalGather g;
  const std::vector<std::uint32_t> first = read_u32(files, bake_file::kGatherFirst);
  g.first.assign(first.begin(), first.end());
  g.source = read_u32(files, bake_file::kGatherSource);
  g.weight = read_f32(files, bake_file::kGatherWeight);
  read_clusters(files, patches, g);
  // Sources past the clusters are samples, then near sources (validate()
  // checks the range).
  if (std::any_of(g.source.begin(), g.source.end(),
                  [&](std::uint32_t s) { return s >= patches + g.clusters; }))
    g.samples = samples;
  if (fs::exists(files(bake_file::kGatherNearPatch))) {
    g.samples = samples;
    read_near_sources(files, g);
  }
  // Seen weights (bakes made before them have none: patches read their own
  // light).
  if (fs::exists(files(bake_file::kGatherSeenFirst))) {
    g.seen_first = read_u32(files, bake_file::kGatherSeenFirst);
    g.seen_sample = read_u32(files, bake_file::kGatherSeenSample);
    g.seen_weight = read_f32(files, bake_file::kGatherSeenWeight);
    g.samples = samples;
  }
  // Spots (bakes made before them have none: samples are lit at their
  // centres).
  if (fs::exists(files(bake_file::kGatherSpotFirst))) {
    g.samples = samples;
    read_spots(files, samples, g);
  }
  g.validate((dir / (std::string(prefix) + "*.npy")).string());
  g.compact_rows();
  return g;
}

}  // namespace bounce
