#include "bake/bake_writer.h"

#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/npy.h"

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

// Column layouts, documented in docs/bake-format.md.
constexpr std::size_t kPatchColumns = 15;
constexpr std::size_t kVoxelColumns = 9;
constexpr std::size_t kSampleColumns = 13;

std::vector<float> patch_rows(const BakeResult& r) {
  std::vector<float> rows;
  rows.reserve(r.patches.size() * kPatchColumns);
  for (const Patch& p : r.patches.patches) {
    rows.insert(rows.end(),
                {p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z,
                 p.area, p.albedo.r, p.albedo.g, p.albedo.b, static_cast<float>(p.voxel),
                 static_cast<float>(p.mesh), p.emission.r, p.emission.g, p.emission.b});
  }
  return rows;
}

std::vector<float> voxel_rows(const BakeResult& r) {
  std::vector<std::uint32_t> patch_count(r.voxels.voxels.size(), 0);
  for (const Patch& p : r.patches.patches) patch_count[p.voxel]++;
  std::vector<float> rows;
  rows.reserve(r.voxels.voxels.size() * kVoxelColumns);
  for (std::size_t v = 0; v < r.voxels.voxels.size(); ++v) {
    const OccupiedVoxel& ov = r.voxels.voxels[v];
    const glm::vec3 c = r.voxels.grid.cell_bounds(ov.coord).center();
    rows.insert(rows.end(), {static_cast<float>(ov.coord.x), static_cast<float>(ov.coord.y),
                             static_cast<float>(ov.coord.z), c.x, c.y, c.z, ov.area,
                             static_cast<float>(r.samples.first[v + 1] - r.samples.first[v]),
                             static_cast<float>(patch_count[v])});
  }
  return rows;
}

std::vector<float> sample_rows(const BakeResult& r) {
  std::vector<float> rows;
  rows.reserve(r.samples.samples.size() * kSampleColumns);
  for (std::size_t k = 0; k < r.samples.samples.size(); ++k) {
    const Sample& s = r.samples.samples[k];
    rows.insert(rows.end(),
                {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                 s.area, s.albedo.r, s.albedo.g, s.albedo.b, static_cast<float>(s.voxel),
                 static_cast<float>(r.patch_of_sample[k]), static_cast<float>(s.triangle)});
  }
  return rows;
}

}  // namespace

json make_manifest(const Scene& scene, const BakeResult& r, const Diagnostics& diagnostics) {
  json m;
  m["format"] = "bounce-bake";
  m["format_version"] = kBakeFormatVersion;
  json lights = json::array();
  for (const Light& l : scene.lights)
    lights.push_back({{"name", l.name},
                      {"type", light_type_name(l.type)},
                      {"position", vec(l.position)},
                      {"direction", vec(l.direction)},
                      {"color", vec(l.color)},
                      {"intensity", l.intensity}});
  const Bounds b = scene.bounds();
  m["scene"] = {{"name", scene.name},
                {"path", scene.path},
                {"triangles", scene.triangle_count()},
                {"materials", scene.materials.size()},
                {"meshes", scene.meshes.size()},
                {"bounds", {{"min", vec(b.lo)}, {"max", vec(b.hi)}}},
                {"lights", lights}};
  const BakeSettings& s = r.settings;
  m["settings"] = {{"voxel_resolution", s.voxel_resolution.value_or(0)},
                   {"patches_total_target", s.patches_total ? json(*s.patches_total) : json()},
                   {"patches_per_voxel", s.patches_per_voxel.value_or(0)},
                   {"patch_mode", to_string(s.patch_mode)},
                   {"samples_per_face", s.samples_per_face.value_or(0)},
                   {"visibility_rays", s.visibility_rays},
                   {"seed", s.seed},
                   {"dump_matrices", s.dump_matrices}};
  const VoxelGrid& g = r.voxels.grid;
  m["grid"] = {{"origin", vec(g.bounds().lo)},
               {"cell_size", g.cell_size()},
               {"dims", {g.dims().x, g.dims().y, g.dims().z}}};
  m["counts"] = {{"triangles", scene.triangle_count()},
                 {"grid_cells", g.cell_count()},
                 {"occupied_voxels", r.voxels.voxels.size()},
                 {"samples", r.samples.samples.size()},
                 {"patches", r.patches.size()},
                 {"patches_before_pruning", r.patches_before_pruning}};
  m["sampling"] = {{"surface_area", r.samples.surface_area},
                   {"sampled_area", r.samples.sampled_area},
                   {"unsampled_area", r.samples.unsampled_area},
                   {"voxels_without_samples", r.samples.voxels_without_samples}};
  if (s.patch_mode == PatchMode::Virtual)
    m["clustering"] = {{"feature_targets", r.clustering.feature_targets},
                       {"target_block_voxels", r.clustering.target_block},
                       {"voxels_above_target", r.clustering.voxels_above_target}};
  json stages = json::array();
  for (const StageStats& st : r.stages)
    stages.push_back(
        {{"name", st.name}, {"seconds", st.seconds}, {"peak_rss_bytes", st.peak_rss_bytes}});
  m["stages"] = stages;
  m["total_seconds"] = r.total_seconds;
  const FormFactorChecks& c = r.checks;
  m["checks"]["form_factors"] = {{"precision", "float32 storage, float32 kernel sums per pair"},
                                 {"row_sum_max", c.row_sum_max},
                                 {"row_sum_mean", c.row_sum_mean},
                                 {"rows_above_one", c.rows_above_one},
                                 {"value_max", c.value_max},
                                 {"reciprocity_error_max", c.reciprocity_error_max},
                                 {"reciprocity_error_rel", c.reciprocity_error_rel},
                                 {"non_finite", c.non_finite},
                                 {"patches_seeing_nothing", c.patches_seeing_nothing}};
  json warnings = json::array(), left_out = json::array();
  for (const Diagnostic& d : diagnostics.all()) {
    json e = {{"where", d.where}, {"message", d.message}};
    (d.kind == Diagnostic::Kind::Warning ? warnings : left_out).push_back(e);
  }
  m["warnings"] = warnings;
  m["left_out"] = left_out;
  return m;
}

json write_bake(const fs::path& out_dir, const Scene& scene, const BakeResult& r,
                const Diagnostics& diagnostics) {
  AtomicDirectory dir(out_dir);
  json files = json::array();
  auto record = [&](const std::string& name, const std::string& what) {
    files.push_back(
        {{"name", name}, {"bytes", fs::file_size(dir.path() / name)}, {"content", what}});
  };
  const std::size_t n = r.patches.size();
  write_npy(dir.path() / "patches.npy", patch_rows(r), {n, kPatchColumns});
  record("patches.npy",
         "float32 [patches x 15]: position xyz, normal xyz, area, albedo rgb, "
         "voxel index, mesh index, emission rgb");
  write_npy(dir.path() / "voxels.npy", voxel_rows(r), {r.voxels.voxels.size(), kVoxelColumns});
  record("voxels.npy",
         "float32 [occupied voxels x 9]: cell ijk, centre xyz, surface area, "
         "sample count, patch count");
  write_npy(dir.path() / "samples.npy", sample_rows(r), {r.samples.samples.size(), kSampleColumns});
  record("samples.npy",
         "float32 [samples x 13]: position xyz, normal xyz, area, albedo rgb, "
         "voxel index, patch index (-1 = left out), triangle index");
  if (r.settings.dump_matrices) {
    write_npy(dir.path() / "F.npy", r.form_factors.values, {n, n});
    record("F.npy", "float32 [patches x patches]: form factors, row = source");
  }
  json m = make_manifest(scene, r, diagnostics);
  m["files"] = files;
  {
    AtomicFile manifest(dir.path() / "manifest.json");
    manifest.stream() << m.dump(2) << '\n';
    manifest.commit();
  }
  dir.commit();
  return m;
}

}  // namespace bounce
