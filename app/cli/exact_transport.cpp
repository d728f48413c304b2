#include "exact_transport.h"

#include <nlohmann/json.hpp>

#include "bounce/bake.h"
#include "bounce/bake_folder.h"
#include "bounce/scene.h"

namespace bounce::cli {

namespace fs = std::filesystem;

std::vector<const float*> ExactTransport::matrices() const {
  std::vector<const float*> m;
  for (const auto& c : channels) m.push_back(c.data());
  return m;
}

ExactTransport read_bake_folder(const fs::path& folder) {
  ExactTransport x;
  // "bakes/bunny/" normalises to a path whose last element is empty.
  fs::path normal = fs::absolute(folder).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();
  x.name = normal.filename().string();
  x.source = "bake folder " + folder.string();

  // The one bake reader checks the manifest, its version and every array;
  // only the exact matrix is read, not the compressed one.
  LoadedBake bake = BakeReader::read(folder, BakeReader::Dense::kRead);
  if (bake.dense.empty())
    throw Error((folder / bake_file::kDenseTransport).string(),
                "missing: this bake stored its transport matrix compressed only; bake the scene "
                "again with --dump-matrices (or --codec dense) to keep the exact matrix");
  x.name = bake.description.scene_name;
  x.n = bake.size();
  x.probe = std::move(bake.probe);
  x.channels = std::move(bake.dense);
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
