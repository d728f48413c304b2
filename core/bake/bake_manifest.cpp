#include "bake/bake_manifest.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "folder/bake_format.h"
#include "runtime/final_gather_settings.h"
#include "settings/settings_table.h"

namespace bounce {

using nlohmann::json;

namespace {

json vec(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

// How many rows of CSR row starts `first` hold at least one entry.
std::size_t non_empty_rows(const std::vector<std::uint32_t>& first) {
  std::size_t rows = 0;
  for (std::size_t i = 0; i + 1 < first.size(); ++i) rows += first[i + 1] > first[i] ? 1 : 0;
  return rows;
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

}  // namespace

// Which probes the bake placed: `auto` resolved by what the placement did
// (r.settings keeps `auto`, so that a re-bake compares what was asked).
ProbePlacementMode placed_probes(const BakeResult& r) {
  const ProbePlacementMode asked = r.settings.light_probes;
  if (asked != ProbePlacementMode::Auto) return asked;
  if (r.probe_placement.surfaces) return ProbePlacementMode::On;
  return r.light_probes.volumes.empty() ? ProbePlacementMode::Off : ProbePlacementMode::VolumesOnly;
}

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
    m["clustering"] = {
        {"feature_targets", r.clustering.feature_targets},
        {"target_block_voxels", r.clustering.target_block},
        {"voxels_above_target", r.clustering.voxels_above_target},
        {"voxels_with_separated_samples", r.clustering.voxels_with_separated_samples},
        {"separated_sample_pairs", r.clustering.separated_sample_pairs}};
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

}  // namespace bounce
