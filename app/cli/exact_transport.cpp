#include "exact_transport.h"

#include <nlohmann/json.hpp>

#include "bake/bake.h"
#include "bake/bake_reader.h"
#include "base/diagnostics.h"
#include "base/error.h"
#include "io/npy.h"
#include "scene/scene_loader.h"

namespace bounce::cli {

namespace fs = std::filesystem;

namespace {

// patches.npy: position xyz, normal xyz, area, ... (docs/bake-format.md).
constexpr std::size_t kPatchAreaColumn = 6;

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::string s = "[";
  for (std::size_t k = 0; k < shape.size(); ++k) s += (k ? " x " : "") + std::to_string(shape[k]);
  return s + "]";
}

}  // namespace

std::vector<const float*> ExactTransport::matrices() const {
  std::vector<const float*> m;
  for (const auto& c : channels) m.push_back(c.data());
  return m;
}

bool is_bake_folder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_regular_file(path / "manifest.json", ec);
}

ExactTransport read_bake_folder(const fs::path& folder) {
  ExactTransport x;
  // "bakes/bunny/" normalises to a path whose last element is empty.
  fs::path normal = fs::absolute(folder).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();
  x.name = normal.filename().string();
  x.source = "bake folder " + folder.string();

  const fs::path manifest_path = folder / "manifest.json";
  const nlohmann::json manifest = read_manifest_json(manifest_path);
  if (!manifest.is_object() || !manifest.contains("format") ||
      manifest["format"] != nlohmann::json("bounce-bake"))
    throw Error(manifest_path.string(),
                "not a bounce bake manifest (\"format\" is not "
                "\"bounce-bake\")");
  if (manifest.contains("scene") && manifest["scene"].is_object() &&
      manifest["scene"].contains("name") && manifest["scene"]["name"].is_string())
    x.name = manifest["scene"]["name"].get<std::string>();

  const fs::path t_path = folder / "T.npy";
  if (!fs::exists(t_path))
    throw Error(t_path.string(),
                "missing: this bake stored its transport matrix compressed only; bake the scene "
                "again with --dump-matrices (or --codec dense) to keep the exact matrix");
  NpyArray<float> t = read_npy_f32(t_path);
  if (t.shape.size() != 3 || t.shape[0] < 1 || t.shape[0] > 3 || t.shape[1] != t.shape[2] ||
      t.shape[1] == 0)
    throw Error(t_path.string(),
                "expected float32 [1..3 channels x N x N], got shape " + shape_text(t.shape));
  x.n = t.shape[1];
  const std::size_t n = x.n, stored = t.shape[0];

  const fs::path patches_path = folder / "patches.npy";
  const NpyArray<float> patches = read_npy_f32(patches_path);
  if (patches.shape.size() != 2 || patches.shape[0] != n || patches.shape[1] <= kPatchAreaColumn)
    throw Error(patches_path.string(), "expected float32 [" + std::to_string(n) +
                                           " patches x 15] to match T.npy, got shape " +
                                           shape_text(patches.shape));
  for (std::size_t p = 0; p < n; ++p)
    x.probe.area.push_back(patches.data[p * patches.shape[1] + kPatchAreaColumn]);

  const fs::path lights_path = folder / "lights_first_hit.npy";
  if (!fs::exists(lights_path))
    throw Error(lights_path.string(),
                "missing: the indirect-light error needs the first-hit light of the evaluation "
                "lights; bake the scene again with this version of bounce");
  const NpyArray<float> lights = read_npy_f32(lights_path);
  if (lights.shape.size() != 3 || lights.shape[1] != n || lights.shape[2] != 3)
    throw Error(lights_path.string(), "expected float32 [lights x " + std::to_string(n) +
                                          " x 3] to match T.npy, got shape " +
                                          shape_text(lights.shape));
  for (std::size_t l = 0; l < lights.shape[0]; ++l) {
    std::vector<glm::vec3> b(n);
    const float* src = lights.data.data() + l * n * 3;
    for (std::size_t p = 0; p < n; ++p) b[p] = {src[3 * p], src[3 * p + 1], src[3 * p + 2]};
    x.probe.first_hit.push_back(std::move(b));
  }

  // Which stored matrix stands for R, G and B (two colour channels may share
  // one). Without the entry, a three-channel T maps one to one.
  const auto* map = manifest.contains("transport") ? &manifest["transport"] : nullptr;
  if (map && map->contains("channel_of_rgb")) {
    const nlohmann::json& c = (*map)["channel_of_rgb"];
    if (!c.is_array() || c.size() != 3)
      throw Error(manifest_path.string(), "transport.channel_of_rgb must be 3 numbers");
    for (std::size_t k = 0; k < 3; ++k) {
      if (!c[k].is_number_integer())
        throw Error(manifest_path.string(), "transport.channel_of_rgb must be 3 whole numbers");
      const int v = c[k].get<int>();
      if (v < 0 || static_cast<std::size_t>(v) >= stored)
        throw Error(manifest_path.string(), "transport.channel_of_rgb names matrix " +
                                                std::to_string(v) +
                                                " but T.npy "
                                                "holds " +
                                                std::to_string(stored));
      x.probe.channel_of_rgb[k] = v;
    }
  } else if (stored == 3) {
    x.probe.channel_of_rgb = {0, 1, 2};
  } else if (stored == 1) {
    x.probe.channel_of_rgb = {0, 0, 0};
  } else {
    throw Error(manifest_path.string(),
                "transport.channel_of_rgb is missing and T.npy holds 2 matrices: which colour "
                "uses which is unknown");
  }

  for (std::size_t c = 0; c < stored; ++c) {
    const auto first = t.data.begin() + static_cast<std::ptrdiff_t>(c * n * n);
    x.channels.emplace_back(first, first + static_cast<std::ptrdiff_t>(n * n));
  }
  return x;
}

ExactTransport bake_exact_transport(const std::string& scene_path, BakeSettings settings,
                                    Progress& progress) {
  // The exact matrix is all the bench needs: no compression (that is what it
  // compares), no pictures, nothing written.
  settings.codec = CodecChoice::Dense;
  settings.kept_fraction.reset();
  settings.error_budget.reset();
  settings.size_limit.reset();
  settings.pictures = false;
  settings.dump_matrices = false;
  Diagnostics diagnostics;
  const Scene scene = SceneLoader(diagnostics).load(scene_path);
  BakeResult r = Baker(scene, settings, diagnostics).run(progress);
  ExactTransport x;
  x.name = scene.name;
  x.n = r.transport.n;
  x.source = "baked now: " + std::to_string(x.n) + " patches, grid " +
             std::to_string(r.settings.voxel_resolution.value_or(0));
  x.bake_seconds = r.total_seconds;
  x.probe = std::move(r.probe);
  for (ChannelTransport& c : r.transport.channels) x.channels.emplace_back(c.t.begin(), c.t.end());
  return x;
}

}  // namespace bounce::cli
