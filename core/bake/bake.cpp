#include "bake/bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "raytrace/ray_tracer.h"
#include "runtime/direct_light.h"
#include "runtime/mesh_transfer.h"

namespace bounce {

namespace {

int dominant_direction(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return 2 * axis + (n[axis] < 0.0f ? 1 : 0);
}

std::size_t predicted_patches(const Scene& scene, const Voxelization& vox, int per_voxel,
                              PatchMode mode) {
  if (mode == PatchMode::Virtual) return vox.voxels.size() * static_cast<std::size_t>(per_voxel);
  std::size_t count = 0;
  for (const OccupiedVoxel& v : vox.voxels) {
    std::set<int> directions;
    for (std::uint32_t k = 0; k < v.part_count; ++k) {
      const std::uint32_t t = vox.parts[v.first_part + k].triangle;
      const glm::vec3 n = scene.triangle_cross(t);
      directions.insert(dominant_direction(n));
      if (scene.two_sided(t)) directions.insert(dominant_direction(-n));
    }
    count += directions.size();
  }
  return count;
}

std::string fmt(double v, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// Rows the balancing had to scale by more than 25% are where the form-factor
// quadrature (or the visibility rays) struggled: name their meshes, the
// worst first, so an artist sees where.
void warn_far_scaled_rows(const Scene& scene, const PatchSet& patches, const BalanceStats& balance,
                          Diagnostics& diagnostics) {
  constexpr double kFar = 1.25;
  std::map<std::uint32_t, std::size_t> per_mesh;
  std::size_t count = 0;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const double s = balance.row_scale[p];
    if (s <= kFar && s >= 1.0 / kFar) continue;
    ++per_mesh[patches.patches[p].mesh];
    ++count;
  }
  if (count == 0) return;
  std::vector<std::pair<std::size_t, std::uint32_t>> worst;
  for (const auto& [mesh, k] : per_mesh) worst.emplace_back(k, mesh);
  std::sort(worst.rbegin(), worst.rend());
  std::string names;
  for (std::size_t i = 0; i < std::min<std::size_t>(worst.size(), 4); ++i) {
    const std::uint32_t mesh = worst[i].second;
    names += (i ? ", '" : "'") +
             (mesh < scene.meshes.size() ? scene.meshes[mesh].name : std::to_string(mesh)) + "' (" +
             std::to_string(worst[i].first) + ")";
  }
  if (worst.size() > 4) names += " and " + std::to_string(worst.size() - 4) + " more meshes";
  diagnostics.warn("form factors",
                   std::to_string(count) + " of " + std::to_string(patches.size()) +
                       " patches needed their form-factor row scaled by more than 25% to reach "
                       "their closure (range " +
                       fmt(balance.row_scale_min, 3) + " .. " + fmt(balance.row_scale_max, 3) +
                       "), on " + names);
}

std::vector<float> patch_densities(const Scene& scene) {
  std::vector<float> d;
  d.reserve(scene.meshes.size());
  for (const MeshInfo& m : scene.meshes) d.push_back(m.patch_density);
  return d;
}

}  // namespace

int Baker::resolution_for_patch_count(const Scene& scene, int patches_total, int per_voxel,
                                      PatchMode mode) {
  const Bounds bounds = scene.bounds();
  // Patch count grows monotonically (roughly as r^2 for surfaces) with the
  // resolution r: bisect on r.
  int lo = 1, hi = 1;
  auto count_at = [&](int r) {
    return predicted_patches(scene, voxelize(scene, VoxelGrid(bounds, r)), per_voxel, mode);
  };
  const auto target = static_cast<std::size_t>(patches_total);
  while (hi < VoxelGrid::kMaxResolution && count_at(hi) < target)
    hi = std::min(2 * hi, VoxelGrid::kMaxResolution);
  lo = std::max(1, hi / 2);
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (count_at(mid) < target ? lo : hi) = mid;
  }
  const auto dist = [&](int r) {
    const double c = static_cast<double>(count_at(r));
    return std::abs(std::log(c / static_cast<double>(target)));
  };
  return dist(lo) <= dist(hi) ? lo : hi;
}

BakeResult Baker::run(Progress& progress, const BakeResult* previous) const {
  const auto start = std::chrono::steady_clock::now();
  BakeResult r;
  RebakePlan plan;  // a full bake
  if (previous) {
    plan = plan_rebake(scene_, previous->settings, settings_);
    // The scene itself is taken to be the previous bake's, except for the
    // patch densities, which a scene.json edit may change without touching
    // the geometry.
    if (plan.first != BakeStage::Geometry && previous->patch_density != patch_densities(scene_)) {
      plan.first = BakeStage::Geometry;
      plan.reasons.push_back("patch density of a mesh (re-runs from geometry)");
    }
    if (plan.first != BakeStage::Geometry) {
      r = *previous;
      r.stages.clear();
      // The reused stages, timed when they ran, and what they said then.
      const auto reused = [&](std::initializer_list<const char*> names, BakeStage stage) {
        for (const StageStats& st : previous->stages)
          for (const char* name : names)
            if (st.name == name) {
              r.stages.push_back(st);
              r.stages.back().name += " (reused)";
            }
        for (const Diagnostic& d : previous->stage_diagnostics[static_cast<std::size_t>(stage)]) {
          if (d.kind == Diagnostic::Kind::Warning)
            diagnostics_.warn(d.where, d.message, d.detail);
          else
            diagnostics_.left_out(d.where, d.message);
        }
      };
      reused({"voxelize", "ray tracer (BVH build)", "sample", "texture", "patches"},
             BakeStage::Geometry);
      if (!plan.runs(BakeStage::FormFactors))
        reused(
            {"form factors", "checks", "closure", "balance", "final gather", "evaluation lights"},
            BakeStage::FormFactors);
      if (!plan.runs(BakeStage::Transport)) reused({"transport"}, BakeStage::Transport);
      if (!plan.runs(BakeStage::Compress)) reused({"compress"}, BakeStage::Compress);
    }
  }
  const std::optional<int> resolved_resolution =
      plan.runs(BakeStage::Geometry) ? std::nullopt : r.settings.voxel_resolution;
  r.settings = settings_;
  r.requested = settings_;
  r.settings.apply_scene_defaults(scene_.defaults);
  r.settings.validate();
  if (resolved_resolution) r.settings.voxel_resolution = resolved_resolution;
  r.plan = plan;
  // Collects the diagnostics a stage raises into r.stage_diagnostics.
  const auto record_from = [&](BakeStage stage, std::size_t first) {
    const std::vector<Diagnostic> all = diagnostics_.all();
    auto& out = r.stage_diagnostics[static_cast<std::size_t>(stage)];
    out.assign(all.begin() + static_cast<std::ptrdiff_t>(std::min(first, all.size())), all.end());
  };
  std::size_t diagnostics_before = diagnostics_.all().size();
  if (plan.runs(BakeStage::Geometry)) {
    StageTimer timer("voxelize");
    int resolution = BakeSettings::kDefaultVoxelResolution;
    if (r.settings.voxel_resolution) {
      resolution = *r.settings.voxel_resolution;
    } else if (r.settings.patches_total) {
      progress.begin_stage("choose grid resolution", 1);
      resolution = resolution_for_patch_count(scene_, *r.settings.patches_total,
                                              *r.settings.patches_per_voxel, r.settings.patch_mode);
      progress.end_stage();
    }
    r.settings.voxel_resolution = resolution;
    r.voxels = voxelize(scene_, VoxelGrid(scene_.bounds(), resolution), &progress);
    const auto empty = r.voxels.grid.cell_count() - r.voxels.voxels.size();
    if (empty > 0)
      diagnostics_.left_out("voxelize", std::to_string(empty) + " of " +
                                            std::to_string(r.voxels.grid.cell_count()) +
                                            " grid cells are empty and get no samples or patches");
    r.stages.push_back(timer.finish());
  }

  // Only geometry and the stages after it that need rays use the tracer
  // (plan_rebake never starts at FormFactors: see there).
  std::optional<RayTracer> tracer;
  if (plan.runs(BakeStage::Geometry)) {
    StageTimer bvh_timer("ray tracer (BVH build)");
    tracer.emplace(scene_);
    r.stages.push_back(bvh_timer.finish());
  }

  if (plan.runs(BakeStage::Geometry)) {
    StageTimer timer("sample");
    SamplingSettings s;
    s.samples_per_face = *r.settings.samples_per_face;
    s.seed = r.settings.seed;
    r.samples = generate_samples(scene_, *tracer, r.voxels, s, &progress);
    if (r.samples.samples.empty())
      throw Error(scene_.path,
                  "no surface samples: no ray hit the scene's surfaces from inside any voxel");
    r.stages.push_back(timer.finish());
  }

  // A stage of its own, so that what textures cost shows in the manifest.
  if (plan.runs(BakeStage::Geometry) && !scene_.triangle_uv.empty()) {
    StageTimer timer("texture");
    apply_texture_albedo(scene_, r.voxels, r.samples, &progress);
    r.stages.push_back(timer.finish());
  }

  if (plan.runs(BakeStage::Geometry)) {
    StageTimer timer("patches");
    if (r.settings.patch_mode == PatchMode::Virtual) {
      ClusteringSettings c;
      c.patches_per_voxel = *r.settings.patches_per_voxel;
      // A total patch count is a total: the grid was chosen for it at
      // patches_per_voxel, the merges then go where they cost least.
      if (r.settings.patches_total)
        c.total_patches = static_cast<std::size_t>(*r.settings.patches_total);
      c.mesh_density = patch_densities(scene_);
      if (distribution_) c.sharing = distribution_->sample_row_sharing();
      r.patches = cluster_virtual_patches(*tracer, r.voxels, r.samples, c, r.clustering, &progress);
      if (r.clustering.voxels_above_target > 0)
        diagnostics_.warn("patches", std::to_string(r.clustering.voxels_above_target) +
                                         " voxels kept more than " +
                                         std::to_string(*r.settings.patches_per_voxel) +
                                         " patches: their samples face opposite ways and are "
                                         "never merged");
    } else {
      progress.begin_stage("voxel patches", 1);
      r.patches = voxel_patches(r.samples);
      progress.end_stage();
    }
    r.patch_density = patch_densities(scene_);
    r.stages.push_back(timer.finish());
    record_from(BakeStage::Geometry, diagnostics_before);
  }

  // Out of core: F is computed on the heap and moved to a mapped file once
  // final (after the checks), the transport maps each finished T (see
  // spill_to_file: matrices being written stay on the heap).
  r.out_of_core = decide_out_of_core(r.settings, r.patches.size());
  const std::optional<OutOfCorePolicy> out_of_core = policy_of(r.out_of_core);

  diagnostics_before = diagnostics_.all().size();
  // Distributed bake: the root's executors, created as soon as the other
  // processes wait for them and destroyed (releasing them) however run()
  // ends: the transport's first (declared last), then the compression's.
  std::unique_ptr<CompressionExecutor> compressor;
  std::unique_ptr<TransportExecutor> executor;
  if (distribution_ && !plan.runs(BakeStage::FormFactors))
    throw Error("bake", "a distributed bake cannot reuse an earlier bake's form factors");
  if (plan.runs(BakeStage::FormFactors)) {
    StageTimer timer("form factors");
    FormFactorSettings fs;
    fs.visibility_rays = r.settings.visibility_rays;
    if (distribution_) {
      distribution_->check_same_patches(r.patches);
      fs.row_offset = distribution_->row_offset();
      fs.row_stride = distribution_->row_stride();
      r.form_factors = distribution_->form_factors(scene_, *tracer, r.voxels, r.samples, r.patches,
                                                   fs, &progress);
      if (!distribution_->is_root()) {
        r.stages.push_back(timer.finish());
        distribution_->serve_transport(r.stages);
        distribution_->serve_compression(r.stages);
        return r;  // the root holds the bake
      }
      executor = distribution_->transport_executor();
      compressor = distribution_->compression_executor();
    } else {
      r.form_factors =
          compute_form_factors(scene_, *tracer, r.voxels, r.samples, r.patches, fs, &progress);
    }
    r.stages.push_back(timer.finish());
  }

  if (plan.runs(BakeStage::FormFactors)) {
    StageTimer timer("checks");
    // A patch that sees nothing also receives nothing (F is reciprocal), so it
    // can never carry indirect light: leave it out.
    r.patches_before_pruning = r.patches.size();
    std::vector<bool> keep(r.patches.size(), true);
    std::size_t dropped = 0;
    for (std::size_t p = 0; p < r.patches.size(); ++p) {
      double row = 0.0;
      for (std::size_t q = 0; q < r.patches.size(); ++q) row += r.form_factors(p, q);
      if (!(row > 0.0)) {
        keep[p] = false;
        ++dropped;
      }
    }
    if (dropped > 0) {
      if (dropped == r.patches.size())
        throw Error(scene_.path,
                    "no patch sees any other patch: nothing for light to bounce between");
      r.patches.keep_only(keep);
      r.form_factors = remove_patches(r.form_factors, keep);
      diagnostics_.left_out("patches", std::to_string(dropped) + " of " +
                                           std::to_string(r.patches_before_pruning) +
                                           " patches see no other patch (zero form-factor row) and "
                                           "can carry no indirect light");
    }
    r.patch_of_sample.assign(r.samples.samples.size(), -1);
    for (std::size_t p = 0; p < r.patches.size(); ++p)
      for (std::uint32_t k = r.patches.member_first[p]; k < r.patches.member_first[p + 1]; ++k)
        r.patch_of_sample[r.patches.member_samples[k]] = static_cast<std::int32_t>(p);
    if (out_of_core)
      r.form_factors.values = spill_to_file(std::move(r.form_factors.values), *out_of_core);
    r.checks_raw = check_form_factors(r.form_factors, r.patches);
    r.checks = r.checks_raw;
    if (r.checks.non_finite > 0)
      throw Error("form factors", std::to_string(r.checks.non_finite) + " NaN/Inf entries");
    r.stages.push_back(timer.finish());
  }

  if (plan.runs(BakeStage::FormFactors) && r.settings.closure_rays > 0) {
    StageTimer timer("closure");
    ClosureSettings cs;
    cs.rays_per_patch = r.settings.closure_rays;
    cs.seed = r.settings.seed;
    const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
    r.closure =
        measure_closure(scene_, *tracer, r.voxels, r.samples, r.patches, lookup, cs, &progress);
    r.stages.push_back(timer.finish());
  }
  if (plan.runs(BakeStage::FormFactors) && r.settings.closure_rays > 0) {
    StageTimer timer("balance");
    std::vector<float> area;
    area.reserve(r.patches.size());
    for (const Patch& p : r.patches.patches) area.push_back(p.area);
    r.balance = balance_form_factors(r.form_factors, area, r.closure.closure, {}, &progress);
    // A patch whose closure rays all missed what its quadrature saw kept its
    // raw row sum as target: that is its closure now.
    for (const std::size_t p : r.balance.raw_target_patches) {
      double row = 0.0;
      for (std::size_t q = 0; q < r.patches.size(); ++q) row += r.form_factors(p, q);
      r.closure.closure[p] = static_cast<float>(row);
    }
    r.checks = check_form_factors(r.form_factors, r.patches, &r.closure.closure);
    if (!r.balance.converged)
      diagnostics_.warn(
          "form factors",
          "balancing to the closure stopped after " + std::to_string(r.balance.iterations) +
              " iterations with rows within " + fmt(r.balance.residual, 3) +
              " of their closure (asked: " + fmt(BalanceSettings{}.tolerance, 3) + ")");
    warn_far_scaled_rows(scene_, r.patches, r.balance, diagnostics_);
    r.stages.push_back(timer.finish());
  }
  if (plan.runs(BakeStage::FormFactors) && r.settings.final_gather_rays > 0) {
    StageTimer timer("final gather");
    // The vertices bounce solve and the studio light: the scene's triangles
    // refined on the bake's grid (runtime/mesh_transfer.h).
    const LitMesh mesh = build_transfer_mesh(scene_, TransferGrid::from(r.voxels.grid),
                                             TransferSettings{}, &progress);
    const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
    FinalGatherSettings fg;
    fg.rays = r.settings.final_gather_rays;
    fg.seed = r.settings.seed;
    r.vertex_gather = build_final_gather(*tracer, lookup, r.patches.patches, r.voxels.grid,
                                         gather_points_of_vertices(mesh.positions, mesh.triangles),
                                         mesh.normals, fg, &progress);
    r.stages.push_back(timer.finish());
  }
  if (plan.runs(BakeStage::FormFactors) && r.checks.row_sum_max > 1.02)
    // Rows a little above 1 are the quadrature error of the near field
    // (~1%); say so only beyond that.
    diagnostics_.warn("form factors", std::to_string(r.checks.rows_above_one) +
                                          " patches have row sums above 1 (max " +
                                          fmt(r.checks.row_sum_max, 4) + ")");

  if (plan.runs(BakeStage::FormFactors)) {
    StageTimer timer("evaluation lights");
    // The first-hit light of the evaluation lights depends on the patches
    // only; channel_of_rgb is filled in after the transport stage.
    const std::vector<Light> lights = evaluation_lights(scene_);
    // The emissive triangles together count as one more light.
    const std::vector<AreaLight> area = area_lights(scene_);
    progress.begin_stage("direct light of the evaluation lights", lights.size() + 1);
    r.probe = IndirectLightProbe{};
    r.probe_lights_total = lights.size() + (area.empty() ? 0 : 1);
    for (const Patch& p : r.patches.patches) r.probe.area.push_back(p.area);
    for (const Light& light : lights) {
      progress.check();
      r.probe.first_hit.push_back(
          first_bounce(r.patches, direct_irradiance(*tracer, r.samples, r.patches, {light})));
      progress.advance();
    }
    if (!area.empty())
      r.probe.first_hit.push_back(
          first_bounce(r.patches, direct_irradiance(*tracer, r.samples, r.patches, {}, area)));
    progress.advance();
    progress.end_stage();
    r.stages.push_back(timer.finish());
    record_from(BakeStage::FormFactors, diagnostics_before);
  }

  diagnostics_before = diagnostics_.all().size();
  if (plan.runs(BakeStage::Transport)) {
    StageTimer timer("transport");
    std::vector<glm::vec3> albedo;
    albedo.reserve(r.patches.size());
    for (const Patch& p : r.patches.patches) albedo.push_back(p.albedo);
    {
      const OutOfCoreScope scope(out_of_core);  // where compute_transport puts each T
      r.transport = compute_transport(r.form_factors, albedo, r.settings.transport, &progress,
                                      diagnostics_, executor.get());
    }
    executor.reset();  // the other processes are done
    // F is not read again until the bake is written: out of core, its pages
    // go back to their file (no-op for a heap matrix).
    release_residency(r.form_factors.values);
    r.probe.channel_of_rgb = channel_of_rgb(r.transport);
    r.stages.push_back(timer.finish());
    record_from(BakeStage::Transport, diagnostics_before);
  }

  diagnostics_before = diagnostics_.all().size();
  if (plan.runs(BakeStage::Compress)) {
    StageTimer timer("compress");
    r.storage = store_transport(r.transport, r.probe, r.settings, &progress, diagnostics_,
                                compressor.get());
    for (const ChannelTransport& c : r.transport.channels) release_residency(c.t);
    r.stages.push_back(timer.finish());
    record_from(BakeStage::Compress, diagnostics_before);
  }
  if (distribution_) {
    compressor.reset();  // the other processes are done, and send their stages' peaks
    distribution_->add_other_ranks_peaks(r.stages);
  }
  r.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace bounce
