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

void write_light_probes(const fs::path& dir, const LightProbes& probes) {
  const std::span<const float> rows(reinterpret_cast<const float*>(probes.position.data()),
                                    3 * probes.position.size());
  write_npy(dir / bake_file::kProbePositions, rows, {probes.size(), 3});
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

}  // namespace

std::optional<LightProbes> read_light_probes(const fs::path& dir, std::size_t patches,
                                             std::size_t samples) {
  const fs::path positions = dir / bake_file::kProbePositions;
  if (!fs::exists(positions)) return std::nullopt;
  LightProbes probes;
  probes.position = read_positions(positions);
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
