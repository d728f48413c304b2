#include "bake/bake_patch_light.h"

#include <iterator>
#include <string>

#include "base/error.h"
#include "runtime/dense_transport.h"
#include "runtime/direct_light.h"

namespace bounce {

namespace {

std::vector<const float*> pointers(const std::vector<std::vector<float>>& matrices) {
  std::vector<const float*> out;
  for (const auto& m : matrices) out.push_back(m.data());
  return out;
}

}  // namespace

std::size_t light_set_count(const LoadedBake& bake) {
  return bake.probe.first_hit.empty() ? 0 : 1 + bake.probe.first_hit.size();
}

std::vector<glm::vec3> light_set_first_hit(const LoadedBake& bake, std::size_t set) {
  const std::vector<std::vector<glm::vec3>>& hits = bake.probe.first_hit;
  if (set >= light_set_count(bake))
    throw Error(bake.dir.string(), "light set " + std::to_string(set) + " of " +
                                       std::to_string(light_set_count(bake)));
  if (set > 0) return hits[set - 1];
  const std::size_t n = bake.size();
  std::vector<glm::vec3> light(n, glm::vec3(0.0f));
  // The evaluation lights begin with the scene's own; the bake adds the
  // fixed point lights and suns, and an area light last when the scene has
  // emissive triangles.
  const std::size_t scene_lights = bake.manifest.at("scene").at("lights").size();
  const bool area =
      hits.size() > scene_lights + kEvaluationPointLights + std::size(kEvaluationSuns);
  for (std::size_t l = 0; l < hits.size(); ++l)
    if (l < scene_lights || (area && l + 1 == hits.size()))
      for (std::size_t p = 0; p < n; ++p) light[p] += hits[l][p];
  return light;
}

PatchRadiosity patch_radiosity(const LoadedBake& bake) {
  const std::size_t n = bake.size();
  PatchRadiosity r;
  r.lit = !bake.probe.first_hit.empty() && !bake.dense.empty();
  std::vector<glm::vec3> indirect;
  if (r.lit)
    dense_indirect(pointers(bake.dense), n, bake.channel_of_rgb, bake.probe.first_hit[0], indirect);
  r.radiosity.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    r.radiosity[p] = bake.patches.patches[p].emission;
    if (r.lit) r.radiosity[p] += bake.probe.first_hit[0][p] + indirect[p];
  }
  return r;
}

std::vector<std::vector<float>> decode_compressed(const LoadedBake& bake) {
  if (!bake.compressed) throw Error(bake.dir.string(), "no compressed matrix to decode");
  const std::size_t n = bake.size();
  std::vector<std::vector<float>> decoded;
  for (int c = 0; c < bake.compressed->channels; ++c) {
    decoded.emplace_back(n * n);
    decompress_channel(*bake.compressed, c, decoded.back().data());
  }
  return decoded;
}

PatchIndirectError compressed_indirect_error(const LoadedBake& bake,
                                             const std::vector<std::vector<float>>& decoded,
                                             std::size_t set, std::optional<std::size_t> patch) {
  if (!bake.compressed || bake.dense.empty())
    throw Error(bake.dir.string(),
                "the indirect-light error needs a compressed matrix and the exact T.npy");
  const std::size_t n = bake.size();
  if (patch && *patch >= n)
    throw Error(bake.dir.string(),
                "patch " + std::to_string(*patch) + " of " + std::to_string(n) + " patches");
  const std::vector<glm::vec3> light = light_set_first_hit(bake, set);
  const std::vector<const float*> exact = pointers(bake.dense);
  std::vector<float> area;
  for (const Patch& p : bake.patches.patches) area.push_back(p.area);
  PatchIndirectError r;
  r.error = patch_light_error(exact, pointers(decoded), n, bake.channel_of_rgb, light, area);
  if (patch)
    r.explanation =
        row_error_contributions(*bake.compressed, exact, bake.channel_of_rgb, light, *patch);
  return r;
}

}  // namespace bounce
