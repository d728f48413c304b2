#include "bake/bake_writer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "bake/bake_pictures.h"
#include "compress/dds.h"
#include "folder/final_gather_files.h"
#include "folder/light_probe_files.h"
#include "io/atomic_file.h"
#include "io/npy.h"
#include "runtime/final_gather_settings.h"
#include "settings/settings_table.h"

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

// How many rows of CSR row starts `first` hold at least one entry.
std::size_t non_empty_rows(const std::vector<std::uint32_t>& first) {
  std::size_t rows = 0;
  for (std::size_t i = 0; i + 1 < first.size(); ++i) rows += first[i + 1] > first[i] ? 1 : 0;
  return rows;
}

constexpr std::size_t kPatchColumns = patch_column::kCount;
constexpr std::size_t kVoxelColumns = voxel_column::kCount;
constexpr std::size_t kSampleColumns = sample_column::kCount;

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

// The polygons of surface each sample carries (SampleSet::carried), so that
// a bake read back integrates point lights over them as the bake did
// (runtime/direct_light.cpp) instead of evaluating them at the samples.
void write_carried_polygons(const fs::path& dir, const SampleSet& samples) {
  std::vector<std::uint32_t> polygons;
  std::vector<float> areas, vertices;
  polygons.reserve(carried_polygon_column::kCount * samples.carried.size());
  areas.reserve(samples.carried.size());
  vertices.reserve(3 * samples.carried_vertices.size());
  for (const glm::vec3& v : samples.carried_vertices)
    vertices.insert(vertices.end(), {v.x, v.y, v.z});
  if (samples.carried_first.size() == samples.samples.size() + 1)
    for (std::size_t k = 0; k < samples.samples.size(); ++k)
      for (std::uint32_t c = samples.carried_first[k]; c < samples.carried_first[k + 1]; ++c) {
        const CarriedArea& piece = samples.carried[c];
        polygons.insert(polygons.end(), {static_cast<std::uint32_t>(k), piece.first_vertex,
                                         piece.vertex_count, piece.triangle, piece.back ? 1u : 0u});
        areas.push_back(piece.area);
      }
  write_npy(dir / bake_file::kCarriedPolygons, std::span<const std::uint32_t>(polygons),
            {areas.size(), carried_polygon_column::kCount});
  write_npy(dir / bake_file::kCarriedArea, std::span<const float>(areas), {areas.size()});
  write_npy(dir / bake_file::kCarriedVertices, std::span<const float>(vertices),
            {samples.carried_vertices.size(), kBakeVectorComponents});
}

std::string rgb_label(const std::vector<int>& rgb) {
  std::string s;
  for (int c : rgb) s += "RGB"[c];
  return s;
}

json error_json(const MatrixError& e) {
  return {{"mean_abs", e.mean_abs},
          {"max_abs", e.max_abs},
          {"sum_abs", e.sum_abs},
          {"rel_frobenius", e.rel_frobenius}};
}

json transport_json(const TransportResult& t) {
  json channels = json::array();
  for (const ChannelTransport& c : t.channels)
    channels.push_back(
        {{"rgb", rgb_label(c.rgb)},
         {"bounces",
          c.bounces == TransportSettings::kInfiniteBounces ? json("inf") : json(c.bounces)},
         {"auto_bounces", c.auto_bounces},
         {"method", c.method},
         {"gemms", c.gemms},
         {"precision", precision_name(c.precision)},
         {"spectral_radius", c.spectral_radius},
         {"spectral_radius_bounds", {c.spectral_radius_lower, c.spectral_radius_upper}},
         {"truncation_bound",
          std::isfinite(c.truncation_bound) ? json(c.truncation_bound) : json("inf")},
         {"condition_number", c.condition_number},
         {"seconds", c.seconds}});
  json decisions = json::array();
  for (const TransportDecision& d : t.decisions)
    decisions.push_back({{"what", d.what}, {"why", d.why}});
  return {{"patches", t.n},
          {"grey", t.grey},
          {"channels", channels},
          {"backend", t.backend},
          {"backend_probe",
           {{"n", t.probe_n},
            {"openblas_seconds", t.probe_openblas_seconds},
            {"clblast_seconds", t.probe_clblast_seconds}}},
          {"non_finite", 0},  // compute_transport throws on any
          {"seconds", t.seconds},
          {"decisions", decisions}};
}

json storage_json(const MatrixStorage& s, std::size_t probe_lights_total) {
  json decisions = json::array();
  for (const TransportDecision& d : s.decisions)
    decisions.push_back({{"what", d.what}, {"why", d.why}});
  json m = {{"codec", s.codec},
            {"decisions", decisions},
            {"seconds", s.seconds},
            {"sizes",
             {{"dense_rgb_float32_bytes", s.dense_rgb_bytes},
              {"dense_stored_float32_bytes", s.dense_bytes},
              {"stored_bytes", s.stored_bytes},
              {"ratio_to_dense_rgb", s.ratio_to_dense_rgb()}}}};
  if (!s.compressed) return m;
  const CompressedMatrix& c = *s.compressed;
  m["sizes"]["sparse_bytes"] = c.sparse_bytes();
  m["sizes"]["block_bytes"] = c.block_bytes();
  m["sizes"]["permutation_bytes"] = c.permutation_bytes();
  m["format"] = c.format == DdsFormat::kBc4 ? "BC4" : "BC1";
  m["stored_channels"] = c.channels;
  m["padded_size"] = c.padded;
  m["encoder"] = c.encoder;
  m["ordering"] = c.ordering;
  m["kept_fraction"] = c.kept_fraction;
  m["kept_storage"] = kept_storage_name(c.kept_storage);
  m["light_weighted"] = c.light_weighted;
  m["kept_passes"] = c.kept_passes;
  m["lights_rebalanced"] = c.lights_rebalanced;
  m["lights_rebalance_tried"] = c.lights_rebalance_tried;
  m["error_budget"] = s.error_budget ? json(*s.error_budget) : json();
  if (s.error_budget) {
    m["error_budget_metric"] = "errors.indirect_light.rel_rms_max";
    m["error_budget_met"] = s.error_budget_met;
    m["error_budget_outcome"] = s.error_budget_outcome;
    m["size_limit"] = s.size_limit ? json(*s.size_limit) : json();
    m["size_limit_bytes"] = s.size_limit_bytes;
  }
  json trials = json::array();
  for (const KeptFractionTrial& t : s.trials)
    trials.push_back({{"kept_fraction", t.kept_fraction},
                      {"rel_frobenius", t.rel_frobenius},
                      {"light_rel_rms_max", t.light.rel_rms_max},
                      {"light_rel_rms_mean", t.light.rel_rms_mean},
                      {"bytes", t.bytes},
                      {"rows_measured", t.rows}});
  m["kept_fraction_trials"] = trials;
  json quantizers = json::array();
  for (const LogQuantizer& q : c.quantizers)
    quantizers.push_back({{"vmax", q.vmax}, {"range", q.range}});
  m["quantizers"] = quantizers;
  json per_channel = json::array();
  for (const MatrixError& e : s.errors.channels) per_channel.push_back(error_json(e));
  const IndirectLightError& li = s.errors.indirect;
  m["errors"] = error_json(s.errors.matrix);
  m["errors"]["per_channel"] = per_channel;
  m["errors"]["indirect_light"] = {{"lights", li.lights},
                                   {"lights_total", probe_lights_total},
                                   {"rel_rms_mean", li.rel_rms_mean},
                                   {"rel_rms_max", li.rel_rms_max}};
  if (s.vertex_indirect)
    m["errors"]["indirect_light_vertices"] = {{"lights", s.vertex_indirect->lights},
                                              {"lights_total", probe_lights_total},
                                              {"rel_rms_mean", s.vertex_indirect->rel_rms_mean},
                                              {"rel_rms_max", s.vertex_indirect->rel_rms_max}};
  m["stage_seconds"] = {{"split", c.seconds_split},
                        {"ordering", c.seconds_ordering},
                        {"encoding", c.seconds_encoding}};
  // Over both kept passes: a second pass encodes only the blocks it changed.
  m["blocks_encoded"] = c.blocks_encoded;
  return m;
}

json rejected_json(std::size_t enclosed, std::size_t sees_nothing) {
  return json::array(
      {{{"reason",
         "inside a closed solid: more than half of its test rays meet the back of "
         "a one-sided face"},
        {"count", enclosed}},
       {{"reason", "sees no surface: every test ray leaves the scene or meets a back face"},
        {"count", sees_nothing}}});
}

std::size_t placed_in(const std::vector<VolumePlacement>& volumes) {
  std::size_t n = 0;
  for (const VolumePlacement& v : volumes) n += v.placed;
  return n;
}

// The light probes: the placement rules, how many each placed, which were
// rejected and why, and what their gather holds.
json light_probes_json(const BakeResult& r) {
  const ProbePlacement& pl = r.probe_placement;
  const FinalGather& g = r.light_probes.gather;
  json volumes = json::array();
  for (const VolumePlacement& v : pl.volumes)
    volumes.push_back({{"min", {v.volume.lo.x, v.volume.lo.y, v.volume.lo.z}},
                       {"max", {v.volume.hi.x, v.volume.hi.y, v.volume.hi.z}},
                       {"spacing", v.volume.spacing},
                       {"lattice", {v.lattice.dims.x, v.lattice.dims.y, v.lattice.dims.z}},
                       {"candidates", v.candidates},
                       {"probes", v.placed},
                       {"rejected", rejected_json(v.rejected_enclosed, v.rejected_sees_nothing)}});
  json surfaces = {
      {"placed", pl.surfaces},
      {"rule", "the centre of every empty voxel sharing a face with an occupied voxel"},
      {"candidates", pl.candidates},
      {"probes", r.light_probes.size() - placed_in(pl.volumes)},
      {"rejected", rejected_json(pl.rejected_enclosed, pl.rejected_sees_nothing)}};
  if (!pl.surfaces_skipped.empty()) surfaces["skipped"] = pl.surfaces_skipped;
  return {{"probes", r.light_probes.size()},
          {"test_rays", kProbeTestRays},
          {"surfaces", surfaces},
          {"volumes", volumes},
          {"directions", kProbeDirections},
          {"sh", "irradiance, real SH L2, 9 coefficients (docs/bake-format.md, Light probes)"},
          {"rays_per_direction", g.rays},
          {"entries", g.source.size()},
          {"entries_per_probe",
           static_cast<double>(g.source.size()) /
               static_cast<double>(std::max<std::size_t>(1, r.light_probes.size()))},
          {"enclosed_directions", g.points_enclosed},
          {"rays",
           {{"landed", g.rays_landed},
            {"escaped", g.rays_escaped},
            {"back_faces", g.rays_back},
            {"unrepresented_surface", g.rays_unrepresented}}},
          {"bytes",
           12 * r.light_probes.size() + 4 * (g.first.size() + g.source.size() + g.weight.size() +
                                             2 * g.cluster_of_patch.size() + g.seen_first.size() +
                                             g.seen_sample.size() + g.seen_weight.size())}};
}

// Every setting by its manifest key (settings_table.h): unset ones as null,
// choices and named values (bounces "auto", "inf") by name.
json settings_json(const BakeSettings& s) {
  json out = json::object();
  for (const SettingRow& row : settings_table()) {
    const SettingValue v = row.get(s);
    const auto* number = std::get_if<std::int64_t>(&v);
    const bool named =
        number && std::any_of(row.named.begin(), row.named.end(),
                              [&](const NamedValue& n) { return n.value == *number; });
    out[row.manifest_key] =
        named ? json(setting_text(row, v))
              : std::visit(
                    [](const auto& x) -> json {
                      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>)
                        return nullptr;
                      else
                        return x;
                    },
                    v);
  }
  return out;
}

// Which probes the bake placed: `auto` resolved by what the placement did
// (r.settings keeps `auto`, so that a re-bake compares what was asked).
ProbePlacementMode placed_probes(const BakeResult& r) {
  const ProbePlacementMode asked = r.settings.light_probes;
  if (asked != ProbePlacementMode::Auto) return asked;
  if (r.probe_placement.surfaces) return ProbePlacementMode::On;
  return r.light_probes.volumes.empty() ? ProbePlacementMode::Off : ProbePlacementMode::VolumesOnly;
}

// The settings as the bake used them: the scene's defaults and the grid
// resolution (r.settings), and what the compression chose for the codec,
// kept fraction, error budget, size limit and ordering left to it.
BakeSettings resolved_settings(const BakeResult& r) {
  BakeSettings s = r.settings;
  const MatrixStorage& st = r.storage;
  if (!st.codec.empty()) setting_row("codec").set(s, st.codec);
  if (st.compressed) {
    s.kept_fraction = st.compressed->kept_fraction;
    setting_row("ordering").set(s, st.compressed->ordering);
  }
  s.error_budget = st.error_budget;
  s.size_limit = st.size_limit;
  s.light_probes = placed_probes(r);
  return s;
}

// T.npy: every stored channel, float32 [channels x n x n].
void write_dense_transport(const fs::path& path, const TransportResult& t) {
  std::vector<std::span<const float>> channels;
  for (const ChannelTransport& c : t.channels) channels.emplace_back(c.t);
  write_npy(path, channels, {t.channels.size(), t.n, t.n});
}

}  // namespace

json make_manifest(const Scene& scene, const BakeResult& r, const Diagnostics& diagnostics) {
  json m;
  m["format"] = kBakeFormatName;
  m["format_version"] = kBakeFormatVersion;
  // What the bake's inputs hash to (bake/bake_key.h): a bake of the same
  // inputs finds this folder up to date.
  if (!r.key.empty()) m["key"] = r.key;
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
                {"masked_materials",
                 scene.has_masks()
                     ? std::count_if(scene.materials.begin(), scene.materials.end(),
                                     [](const Material& mat) { return mat.alpha_mask != nullptr; })
                     : 0},
                {"meshes", scene.meshes.size()},
                {"bounds", {{"min", vec(b.lo)}, {"max", vec(b.hi)}}},
                {"lights", lights}};
  // Every setting once as asked for and once as the bake used it.
  m["settings"] = {{"requested", settings_json(r.requested)},
                   {"resolved", settings_json(resolved_settings(r))}};
  // Per mesh: its patch density and what it got, to check a density's effect.
  std::vector<std::size_t> mesh_patches(scene.meshes.size(), 0);
  for (const Patch& p : r.patches.patches)
    if (p.mesh < mesh_patches.size()) ++mesh_patches[p.mesh];
  std::vector<double> mesh_area(scene.meshes.size(), 0.0);
  for (std::size_t t = 0; t < scene.triangle_count(); ++t)
    mesh_area[scene.triangle_mesh[t]] += scene.triangle_area(t);
  json meshes = json::array();
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    meshes.push_back({{"name", scene.meshes[i].name},
                      {"patch_density", scene.meshes[i].patch_density},
                      {"patches", mesh_patches[i]},
                      {"area", mesh_area[i]}});
  m["meshes"] = meshes;
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
                   {"centre_sampled_area", r.samples.centre_sampled_area},
                   {"centre_samples", r.samples.centre_samples},
                   {"cut_away_area", r.samples.cut_away_area},
                   {"voxels_without_samples", r.samples.voxels_without_samples}};
  if (r.settings.patch_mode == PatchMode::Virtual)
    m["clustering"] = {{"feature_targets", r.clustering.feature_targets},
                       {"target_block_voxels", r.clustering.target_block},
                       {"voxels_above_target", r.clustering.voxels_above_target}};
  json stages = json::array();
  for (const StageStats& st : r.stages) {
    json stage = {
        {"name", st.name}, {"seconds", st.seconds}, {"peak_rss_bytes", st.peak_rss_bytes}};
    // Distributed bake: the other ranks' highest peak in the same stage, and
    // the highest over all ranks.
    if (st.peak_rss_bytes_other_ranks > 0) {
      stage["peak_rss_bytes_other_ranks"] = st.peak_rss_bytes_other_ranks;
      stage["peak_rss_bytes_all_ranks"] =
          std::max(st.peak_rss_bytes, st.peak_rss_bytes_other_ranks);
    }
    stages.push_back(stage);
  }
  m["stages"] = stages;
  m["total_seconds"] = r.total_seconds;
  // Peak RSS per stage (stages[].peak_rss_bytes) is this process's (rank 0's
  // in a distributed bake), and counts the resident pages of mapped matrices.
  m["memory"] = {{"out_of_core", r.out_of_core.on},
                 {"why", r.out_of_core.why},
                 {"dense_footprint_bytes", r.out_of_core.dense_footprint_bytes},
                 {"physical_memory_bytes", r.out_of_core.physical_memory_bytes}};
  if (r.out_of_core.on) m["memory"]["matrix_dir"] = r.out_of_core.dir.string();
  const auto checks_json = [](const FormFactorChecks& c) {
    return json{{"row_sum_max", c.row_sum_max},
                {"row_sum_mean", c.row_sum_mean},
                {"rows_above_one", c.rows_above_one},
                {"value_max", c.value_max},
                {"clamped_to_one", c.clamped_to_one},
                {"reciprocity_error_max", c.reciprocity_error_max},
                {"reciprocity_error_rel", c.reciprocity_error_rel},
                {"non_finite", c.non_finite},
                {"patches_seeing_nothing", c.patches_seeing_nothing}};
  };
  // The stored (balanced) F's checks at the top level; the quadrature's as
  // it came out under "raw".
  json& ff = m["checks"]["form_factors"];
  ff = checks_json(r.checks);
  ff["raw"] = checks_json(r.checks_raw);
  if (r.settings.closure_rays > 0) {
    ff["precision"] =
        "float32 storage; kernel sums per pair in float32; balancing in float64 on the "
        "symmetric exchange matrix stored in float32";
    ff["rows_above_closure"] = r.checks.rows_above_closure;
    ff["closure_excess_max"] = r.checks.closure_excess_max;
    ff["closure"] = {{"rays_per_patch", r.closure.rays_per_patch},
                     {"mean_area_weighted", r.closure.mean},
                     {"min", r.closure.min},
                     {"max", r.closure.max},
                     {"open_patches", r.closure.open_patches},
                     {"standard_error_max", r.closure.standard_error_max}};
    ff["balance"] = {{"method", "symmetric Sinkhorn-Knopp scaling of (A F + (A F)^T) / 2"},
                     {"iterations", r.balance.iterations},
                     {"converged", r.balance.converged},
                     {"tolerance", BalanceSettings{}.tolerance},
                     {"residual", r.balance.residual},
                     {"row_scale_min", r.balance.row_scale_min},
                     {"row_scale_max", r.balance.row_scale_max},
                     {"kept_raw_targets", r.balance.kept_raw_targets},
                     {"limited_targets", r.balance.limited_targets},
                     {"max_row_scale", BalanceSettings{}.max_row_scale}};
  } else {
    ff["precision"] = "float32 storage, float32 kernel sums per pair (not balanced)";
  }
  if (r.vertex_gather.points() > 0) {
    const FinalGather& fg = r.vertex_gather;
    m["final_gather"] = {
        {"transfer", "final gather"},
        {"vertices", fg.points()},
        {"entries", fg.source.size()},
        {"entries_per_vertex", static_cast<double>(fg.source.size()) /
                                   static_cast<double>(std::max<std::size_t>(1, fg.points()))},
        {"kept_per_vertex_max", FinalGatherSettings{}.kept},
        {"coverage", FinalGatherSettings{}.coverage},
        {"samples_kept_per_vertex_max",
         [&fg] {
           FinalGatherSettings settings;
           settings.rays = fg.rays;
           return settings.sample_cap();
         }()},
        {"sample_coverage", FinalGatherSettings{}.sample_coverage},
        {"sample_entries", std::count_if(fg.source.begin(), fg.source.end(),
                                         [&fg](std::uint32_t source) {
                                           return source >= fg.patches + fg.clusters &&
                                                  source < fg.patches + fg.clusters + fg.samples;
                                         })},
        {"near_sources", fg.near.size()},
        {"near_entries", std::count_if(fg.source.begin(), fg.source.end(),
                                       [&fg](std::uint32_t source) {
                                         return source >= fg.patches + fg.clusters + fg.samples;
                                       })},
        {"near_resolution_per_voxel", FinalGatherSettings{}.near_resolution},
        // Spots (runtime/final_gather.h): points where the vertices' far
        // rays landed on each sample, lit every frame with the near sources.
        {"spots",
         {{"samples", non_empty_rows(fg.spot_first)},
          {"points", fg.spots()},
          {"resolution_per_voxel", FinalGatherSettings{}.spot_resolution}}},
        {"clusters", fg.clusters},
        {"enclosed_vertices", fg.points_enclosed},
        {"rays",
         {{"landed", fg.rays_landed},
          {"escaped", fg.rays_escaped},
          {"back_faces", fg.rays_back},
          {"near", fg.rays_near},
          {"unrepresented_surface", fg.rays_unrepresented}}},
        // Seen weights (runtime/seen_first_hit.h): the patches whose first-hit
        // light is their samples' as the vertices' rays saw them.
        {"seen_weights",
         {{"patches", non_empty_rows(fg.seen_first)}, {"entries", fg.seen_sample.size()}}},
        {"bytes", 4 * (fg.first.size() + fg.source.size() + fg.weight.size() +
                       2 * fg.cluster_of_patch.size() + fg.seen_first.size() +
                       fg.seen_sample.size() + fg.seen_weight.size() + fg.spot_first.size() +
                       fg.spot_weight.size() + 10 * fg.near.size())}};
  } else {
    m["final_gather"] = {{"transfer", "nearest patches"}};
  }
  if (placed_probes(r) != ProbePlacementMode::Off) m["light_probes"] = light_probes_json(r);
  m["transport"] = transport_json(r.transport);
  m["transport"]["channel_of_rgb"] = r.probe.channel_of_rgb;
  m["compression"] = storage_json(r.storage, r.probe_lights_total);
  json warnings = json::array(), left_out = json::array();
  for (const Diagnostic& d : diagnostics.all()) {
    json e = {{"where", d.where}, {"message", d.message}};
    if (!d.detail.empty()) e["detail"] = d.detail;
    (d.kind == Diagnostic::Kind::Warning ? warnings : left_out).push_back(e);
  }
  m["warnings"] = warnings;
  m["left_out"] = left_out;
  return m;
}

namespace {

// The folder's contents, written into `dir` (the temporary folder).
json write_bake_files(const AtomicDirectory& dir, const Scene& scene, const BakeResult& r,
                      const Diagnostics& diagnostics);

// An error from writing one file names the file by its temporary path
// (".NAME.partial-PID-N/patches.npy"), which is gone once the failed bake
// has cleaned up. Say it about the bake folder the user asked for instead.
[[noreturn]] void rethrow_for_target(const AtomicDirectory& dir, const fs::path& file,
                                     const std::string& why) {
  if (file.empty()) throw IoError(dir.target().string(), "cannot write the bake: " + why);
  fs::path relative = file.lexically_relative(dir.path());
  if (relative.empty() || *relative.begin() == "..") relative = file;
  throw IoError(dir.target().string(), "cannot write " + relative.string() + ": " + why);
}

}  // namespace

json write_bake(const fs::path& out_dir, const Scene& scene, const BakeResult& r,
                const Diagnostics& diagnostics) {
  AtomicDirectory dir(out_dir);
  json m;
  try {
    m = write_bake_files(dir, scene, r, diagnostics);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    // Error::what() is "<where>: <why>"; keep <why>, name <where> relative to the folder.
    std::string why = e.what();
    if (!e.where().empty() && why.rfind(e.where() + ": ", 0) == 0)
      why = why.substr(e.where().size() + 2);
    rethrow_for_target(dir, e.where(), why);
  } catch (const fs::filesystem_error& e) {
    rethrow_for_target(dir, e.path1(), e.code().message());
  }
  dir.commit();
  return m;
}

namespace {

json write_bake_files(const AtomicDirectory& dir, const Scene& scene, const BakeResult& r,
                      const Diagnostics& diagnostics) {
  json files = json::array();
  auto record = [&](const std::string& name, const std::string& what) {
    files.push_back(
        {{"name", name}, {"bytes", fs::file_size(dir.path() / name)}, {"content", what}});
  };
  const std::size_t n = r.patches.size();
  write_npy(dir.path() / bake_file::kPatches, patch_rows(r), {n, kPatchColumns});
  record(bake_file::kPatches, "float32 [patches x " + std::to_string(kPatchColumns) +
                                  "]: position xyz, normal xyz, area, albedo rgb, "
                                  "voxel index, mesh index, emission rgb");
  write_npy(dir.path() / bake_file::kVoxels, voxel_rows(r),
            {r.voxels.voxels.size(), kVoxelColumns});
  record(bake_file::kVoxels, "float32 [occupied voxels x " + std::to_string(kVoxelColumns) +
                                 "]: cell ijk, centre xyz, surface area, "
                                 "sample count, patch count");
  write_npy(dir.path() / bake_file::kSamples, sample_rows(r),
            {r.samples.samples.size(), kSampleColumns});
  record(bake_file::kSamples, "float32 [samples x " + std::to_string(kSampleColumns) +
                                  "]: position xyz, normal xyz, area, albedo rgb, "
                                  "voxel index, patch index (-1 = left out), triangle index");
  write_carried_polygons(dir.path(), r.samples);
  record(bake_file::kCarriedPolygons,
         "uint32 [polygons x 5]: sample index, first vertex, vertex count, scene triangle and "
         "side (1: back) of each planar polygon of surface a sample stands for, in sample order");
  record(bake_file::kCarriedArea, "float32 [polygons]: the area each polygon stands for");
  record(bake_file::kCarriedVertices, "float32 [vertices x 3]: the polygons' vertices xyz");
  if (r.closure.closure.size() == n && r.balance.row_scale.size() == n) {
    std::vector<float> rows;
    rows.reserve(2 * n);
    for (std::size_t p = 0; p < n; ++p)
      rows.insert(rows.end(), {r.closure.closure[p], r.balance.row_scale[p]});
    write_npy(dir.path() / bake_file::kClosure, rows, {n, closure_column::kCount});
    record(bake_file::kClosure,
           "float32 [patches x 2]: closure (share of the patch's light that lands on sampled "
           "surface, the row sum F is balanced to), row scale the balancing applied (balanced / "
           "raw row sum)");
  }
  if (r.vertex_gather.points() > 0) {
    write_final_gather(dir.path(), r.vertex_gather);
    record(bake_file::kGatherFirst, "uint32 [lit-mesh vertices + 1]: final gather row starts");
    record(bake_file::kGatherSource,
           "uint32 [entries]: patch each entry gathers from, or patches + cluster index, or "
           "patches + clusters + sample index, or patches + clusters + samples + near source");
    record(bake_file::kGatherWeight, "float32 [entries]: vertex-to-patch (or cluster) form factor");
    record(bake_file::kGatherCluster, "uint32 [patches]: cluster of each patch");
    record(bake_file::kGatherShare,
           "float32 [patches]: each patch's share of its cluster's light (of the rays folded "
           "into the cluster)");
    if (!r.vertex_gather.seen_first.empty()) {
      record(bake_file::kGatherSeenFirst,
             "uint32 [patches + 1]: row starts of each patch's seen weights");
      record(bake_file::kGatherSeenSample, "uint32 [entries]: a sample of the patch");
      record(bake_file::kGatherSeenWeight,
             "float32 [entries]: its share of the gather's rays read through the patch: a "
             "patch entry's light is the sum of share x the sample's light");
    }
    if (r.vertex_gather.near.size() > 0) {
      record(bake_file::kGatherNearPosition,
             "float32 [near sources x 3]: where each near source is lit every frame");
      record(bake_file::kGatherNearNormal, "float32 [near sources x 3]: the side it is lit on");
      record(bake_file::kGatherNearAlbedo, "float32 [near sources x 3]: its mean albedo");
      record(bake_file::kGatherNearPatch,
             "uint32 [near sources]: the patch whose multi-bounce light T b it carries");
    }
    if (!r.vertex_gather.spot_first.empty()) {
      record(bake_file::kGatherSpotFirst,
             "uint32 [samples + 1]: row starts of each sample's spots, the last near sources");
      record(bake_file::kGatherSpotWeight,
             "float32 [spots]: the spot's share of the sample's light (of the far rays that "
             "landed on the sample's spots)");
    }
  }
  if (placed_probes(r) != ProbePlacementMode::Off) {
    write_light_probes(dir.path(), r.light_probes);
    record(bake_file::kProbePositions, "float32 [probes x 3]: light probe positions");
    if (!r.light_probes.volumes.empty())
      record(bake_file::kProbeVolumes,
             "float32 [volumes x 9]: each probe volume's lattice (origin x y z, spacing, cells "
             "x y z) and its probes (first, count)");
    const auto probe_file = [](const char* name) {
      return gather_file_name(bake_file::kProbeGatherPrefix, name);
    };
    record(probe_file(bake_file::kGatherFirst),
           "uint32 [probes x 14 + 1]: row starts of the probes' gather, probe p's direction k "
           "in row 14 p + k");
    record(probe_file(bake_file::kGatherSource), "uint32 [entries]: as gather_source.npy");
    record(probe_file(bake_file::kGatherWeight),
           "float32 [entries]: direction-to-source form factor");
    record(probe_file(bake_file::kGatherCluster), "uint32 [patches]: cluster of each patch");
    record(probe_file(bake_file::kGatherShare),
           "float32 [patches]: each patch's share of its cluster's light");
    if (!r.light_probes.gather.seen_first.empty()) {
      record(probe_file(bake_file::kGatherSeenFirst),
             "uint32 [patches + 1]: row starts of each patch's seen weights");
      record(probe_file(bake_file::kGatherSeenSample), "uint32 [entries]: a sample of the patch");
      record(probe_file(bake_file::kGatherSeenWeight),
             "float32 [entries]: its share of the probes' rays read through the patch");
    }
  }
  if (r.settings.dump_matrices) {
    write_npy(dir.path() / bake_file::kFormFactors, r.form_factors.values, {n, n});
    record(bake_file::kFormFactors, "float32 [patches x patches]: form factors, row = source");
  }
  if (!r.storage.compressed || r.settings.dump_matrices) {
    write_dense_transport(dir.path() / bake_file::kDenseTransport, r.transport);
    record(bake_file::kDenseTransport,
           "float32 [stored channels x patches x patches]: multi-bounce matrix, exact; "
           "channel_of_rgb in the manifest maps R, G, B to its channels");
  }
  {
    std::vector<float> b;
    for (const auto& light : r.probe.first_hit)
      for (const glm::vec3& v : light) b.insert(b.end(), {v.r, v.g, v.b});
    write_npy(dir.path() / bake_file::kLightsFirstHit, b,
              {r.probe.first_hit.size(), n, kBakeVectorComponents});
    record(bake_file::kLightsFirstHit,
           "float32 [evaluation lights x patches x 3]: light leaving each patch after the first "
           "hit (albedo x direct irradiance) for the scene's lights and four unit test lights; "
           "the indirect-light error is measured with these");
  }
  if (r.storage.compressed) {
    const CompressedMatrix& c = *r.storage.compressed;
    const auto side = static_cast<std::uint32_t>(c.padded);
    write_dds(dir.path() / bake_file::kCompressedTransport, c.format, side, side, c.blocks);
    record(bake_file::kCompressedTransport,
           std::string(c.format == DdsFormat::kBc4 ? "BC4" : "BC1") +
               " [padded x padded]: log codes of the reordered matrix (row/column k = "
               "patch permutation[k]); see compression.quantizers");
    write_npy(dir.path() / bake_file::kPermutation, c.permutation, {n});
    record(bake_file::kPermutation,
           "uint32 [patches]: stored row/column k holds patch permutation[k]");
    for (std::size_t ch = 0; ch < c.kept.size(); ++ch) {
      const CsrMatrix& k = c.kept[ch];
      const int channel = static_cast<int>(ch);
      const std::string row_ptr = bake_file::kept(channel, bake_file::KeptPart::kRowPtr),
                        col = bake_file::kept(channel, bake_file::KeptPart::kCol),
                        value = bake_file::kept(channel, bake_file::KeptPart::kValue);
      write_npy(dir.path() / row_ptr, k.row_ptr, {k.row_ptr.size()});
      record(row_ptr,
             "uint32 [patches + 1]: CSR row starts of the kept entries of stored channel " +
                 std::to_string(ch));
      if (kept_columns_are_short(c.kept_storage, n)) {
        const std::vector<std::uint16_t> short_col(k.col.begin(), k.col.end());
        write_npy(dir.path() / col, short_col, {short_col.size()});
        record(col, "uint16 [kept]: CSR column (patch order)");
      } else {
        write_npy(dir.path() / col, k.col, {k.col.size()});
        record(col, "uint32 [kept]: CSR column (patch order)");
      }
      if (c.kept_storage == KeptStorage::kFloat16) {
        std::vector<std::uint16_t> bits(k.value.size());
        to_half_bits(k.value, bits);
        write_npy_half(dir.path() / value, bits, {bits.size()});
        record(value, "float16 [kept]: CSR values, rounded to half precision");
      } else {
        write_npy(dir.path() / value, k.value, {k.value.size()});
        record(value, "float32 [kept]: CSR values, exact");
      }
    }
  }
  if (r.settings.pictures)
    for (const WrittenPicture& p : write_matrix_pictures(dir.path(), r)) record(p.name, p.content);
  json m = make_manifest(scene, r, diagnostics);
  m["files"] = files;
  {
    AtomicFile manifest(dir.path() / bake_file::kManifest);
    manifest.stream() << m.dump(2) << '\n';
    manifest.commit();
  }
  return m;
}

}  // namespace

}  // namespace bounce
