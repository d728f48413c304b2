#include "folder/light_probe_files.h"

#include <cmath>
#include <span>
#include <string>

#include "base/error.h"
#include "folder/bake_format.h"
#include "folder/final_gather_files.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {
constexpr std::size_t kVolumeColumns = 9;
}  // namespace

void write_light_probes(const fs::path& dir, const LightProbes& probes) {
  const std::span<const float> rows(reinterpret_cast<const float*>(probes.position.data()),
                                    3 * probes.position.size());
  write_npy(dir / bake_file::kProbePositions, rows, {probes.size(), 3});
  if (!probes.volumes.empty()) {
    std::vector<float> volumes;
    for (const ProbeLattice& v : probes.volumes) {
      const TransferGrid& g = v.grid;
      volumes.insert(volumes.end(),
                     {g.origin.x, g.origin.y, g.origin.z, g.cell_size, static_cast<float>(g.dims.x),
                      static_cast<float>(g.dims.y), static_cast<float>(g.dims.z),
                      static_cast<float>(v.first), static_cast<float>(v.count)});
    }
    write_npy(dir / bake_file::kProbeVolumes, std::span<const float>(volumes),
              {probes.volumes.size(), kVolumeColumns});
  }
  write_final_gather(dir, probes.gather, bake_file::kProbeGatherPrefix);
}

namespace {

std::vector<glm::vec3> read_positions(const fs::path& file) {
  const NpyArray<float> array = read_npy_f32(file);
  if (array.shape.size() != 2 || array.shape[1] != 3)
    throw Error(file.string(), "expected an array of shape [probes, 3]");
  std::vector<glm::vec3> out(array.shape[0]);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = glm::vec3(array.data[3 * i], array.data[3 * i + 1], array.data[3 * i + 2]);
    if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
      throw Error(file.string(), "probe " + std::to_string(i) + " has a non-finite position");
  }
  return out;
}

// A whole number in [lo, hi] stored as float32 (exact to 2^24).
std::size_t whole(const fs::path& file, std::size_t row, const char* what, float v, float lo,
                  float hi) {
  if (!(v >= lo && v <= hi) || v != std::floor(v))
    throw Error(file.string(), "volume " + std::to_string(row) + ": " + what + " " +
                                   std::to_string(v) + " is not a whole number from " +
                                   std::to_string(static_cast<long long>(lo)) + " to " +
                                   std::to_string(static_cast<long long>(hi)));
  return static_cast<std::size_t>(v);
}

// The volumes' lattices: each with a positive spacing and at least one cell
// per axis, their probes consecutive ranges after the surfaces' probes.
std::vector<ProbeLattice> read_volumes(const fs::path& file, std::size_t probes) {
  if (!fs::exists(file)) return {};
  const NpyArray<float> array = read_npy_f32(file);
  if (array.shape.size() != 2 || array.shape[1] != kVolumeColumns)
    throw Error(file.string(), "expected an array of shape [volumes, 9]");
  std::vector<ProbeLattice> out(array.shape[0]);
  constexpr float kMaxWhole = 16777216.0f;  // 2^24: every whole float below is exact
  std::size_t next = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float* row = array.data.data() + kVolumeColumns * i;
    ProbeLattice& v = out[i];
    v.grid.origin = glm::vec3(row[0], row[1], row[2]);
    v.grid.cell_size = row[3];
    if (!std::isfinite(row[0]) || !std::isfinite(row[1]) || !std::isfinite(row[2]) ||
        !(row[3] > 0.0f) || !std::isfinite(row[3]))
      throw Error(file.string(), "volume " + std::to_string(i) +
                                     ": its origin must be finite and its spacing positive");
    for (int a = 0; a < 3; ++a)
      v.grid.dims[a] = static_cast<int>(whole(file, i, "cells", row[4 + a], 1.0f, kMaxWhole));
    v.first = whole(file, i, "first probe", row[7], 0.0f, kMaxWhole);
    v.count = whole(file, i, "probe count", row[8], 0.0f, kMaxWhole);
    if (i == 0) next = v.first;
    if (v.first != next || v.first + v.count > probes)
      throw Error(file.string(), "volume " + std::to_string(i) + ": its probes " +
                                     std::to_string(v.first) + " to " +
                                     std::to_string(v.first + v.count) +
                                     " do not follow the previous volume's within the " +
                                     std::to_string(probes) + " probes");
    next = v.first + v.count;
  }
  if (next != probes)
    throw Error(file.string(), "the volumes end at probe " + std::to_string(next) + " of " +
                                   std::to_string(probes) + ": a volume's probes come last");
  return out;
}

}  // namespace

std::optional<LightProbes> read_light_probes(const fs::path& dir, std::size_t patches,
                                             std::size_t samples) {
  const fs::path positions = dir / bake_file::kProbePositions;
  if (!fs::exists(positions)) return std::nullopt;
  LightProbes probes;
  probes.position = read_positions(positions);
  probes.volumes = read_volumes(dir / bake_file::kProbeVolumes, probes.size());
  std::optional<FinalGather> gather =
      read_final_gather(dir, patches, samples, bake_file::kProbeGatherPrefix);
  const fs::path first =
      dir / gather_file_name(bake_file::kProbeGatherPrefix, bake_file::kGatherFirst);
  if (!gather) throw Error(first.string(), "missing: the probes' gather");
  if (gather->points() != probes.size() * kProbeDirections)
    throw Error(first.string(), "expected " + std::to_string(kProbeDirections) +
                                    " rows per probe (" + std::to_string(probes.size()) +
                                    " probes), found " + std::to_string(gather->points()));
  if (gather->near.size() > 0)
    throw Error(first.string(), "the probes' gather holds near sources, which probes do not use");
  probes.gather = std::move(*gather);
  return probes;
}

}  // namespace bounce
