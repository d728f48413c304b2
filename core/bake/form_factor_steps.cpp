// The form-factor stage of a bake: the form factors, their checks (pruning
// the patches that see nothing), closure and balancing, the final gather of
// the lit mesh's vertices, and the evaluation lights' first-hit light.
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "bake/bake_steps.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather_build.h"
#include "runtime/light_probe_gather.h"
#include "runtime/mesh_transfer.h"
#include "runtime/seen_first_hit.h"

namespace bounce {

namespace {

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

void form_factors_step(BakeRun& run) {
  BakeResult& r = run.result;
  FormFactorSettings fs;
  fs.visibility_rays = r.settings.visibility_rays;
  if (!run.distribution) {
    r.form_factors = compute_form_factors(run.scene, *run.tracer, r.voxels, r.samples, r.patches,
                                          fs, &run.progress);
    return;
  }
  run.distribution->check_same_patches(r.patches);
  fs.row_offset = run.distribution->row_offset();
  fs.row_stride = run.distribution->row_stride();
  r.form_factors = run.distribution->form_factors(run.scene, *run.tracer, r.voxels, r.samples,
                                                  r.patches, fs, &run.progress);
  if (!run.distribution->is_root()) return;
  run.executor = run.distribution->transport_executor();
  run.compressor = run.distribution->compression_executor();
}

// A process of a distributed bake that is not the root takes its share of
// the transport and the compression, then is done: the root holds the bake.
bool serves_the_root(const BakeRun& run) {
  return run.distribution && !run.distribution->is_root();
}

void serve_the_root_step(BakeRun& run) {
  run.distribution->serve_transport(run.result.stages);
  run.distribution->serve_compression(run.result.stages);
  run.finished = true;
}

void checks_step(BakeRun& run) {
  BakeResult& r = run.result;
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
      throw Error(run.scene.path,
                  "no patch sees any other patch: nothing for light to bounce between");
    r.patches.keep_only(keep);
    r.form_factors = remove_patches(r.form_factors, keep);
    run.diagnostics.left_out("patches", std::to_string(dropped) + " of " +
                                            std::to_string(r.patches_before_pruning) +
                                            " patches see no other patch (zero form-factor row) "
                                            "and can carry no indirect light");
  }
  r.patch_of_sample.assign(r.samples.samples.size(), -1);
  for (std::size_t p = 0; p < r.patches.size(); ++p)
    for (std::uint32_t k = r.patches.member_first[p]; k < r.patches.member_first[p + 1]; ++k)
      r.patch_of_sample[r.patches.member_samples[k]] = static_cast<std::int32_t>(p);
  // Out of core, F moves to its mapped file once final, i.e. here.
  if (run.out_of_core)
    r.form_factors.values = spill_to_file(std::move(r.form_factors.values), *run.out_of_core);
  r.checks_raw = check_form_factors(r.form_factors, r.patches);
  r.checks = r.checks_raw;
  if (r.checks.non_finite > 0)
    throw Error("form factors", std::to_string(r.checks.non_finite) + " NaN/Inf entries");
}

bool measures_closure(const BakeRun& run) { return run.result.settings.closure_rays > 0; }

void closure_step(BakeRun& run) {
  BakeResult& r = run.result;
  ClosureSettings cs;
  cs.rays_per_patch = r.settings.closure_rays;
  cs.seed = r.settings.seed;
  const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
  r.closure = measure_closure(run.scene, *run.tracer, r.voxels, r.samples, r.patches, lookup, cs,
                              &run.progress);
}

void balance_step(BakeRun& run) {
  BakeResult& r = run.result;
  std::vector<float> area;
  area.reserve(r.patches.size());
  for (const Patch& p : r.patches.patches) area.push_back(p.area);
  r.balance = balance_form_factors(r.form_factors, area, r.closure.closure, {}, &run.progress);
  // A patch whose closure rays all missed what its quadrature saw kept its
  // raw row sum as target: that is its closure now.
  for (const std::size_t p : r.balance.raw_target_patches) {
    double row = 0.0;
    for (std::size_t q = 0; q < r.patches.size(); ++q) row += r.form_factors(p, q);
    r.closure.closure[p] = static_cast<float>(row);
  }
  r.checks = check_form_factors(r.form_factors, r.patches, &r.closure.closure);
  if (!r.balance.converged)
    run.diagnostics.warn(
        "form factors",
        "balancing to the closure stopped after " + std::to_string(r.balance.iterations) +
            " iterations with rows within " + fmt(r.balance.residual, 3) +
            " of their closure (asked: " + fmt(BalanceSettings{}.tolerance, 3) + ")");
  warn_far_scaled_rows(run.scene, r.patches, r.balance, run.diagnostics);
}

bool gathers_vertices(const BakeRun& run) { return run.result.settings.final_gather_rays > 0; }

void final_gather_step(BakeRun& run) {
  BakeResult& r = run.result;
  // The vertices bounce solve and the studio light: the scene's triangles
  // refined on the bake's grid (runtime/mesh_transfer.h).
  const LitMesh mesh = build_transfer_mesh(run.scene, TransferGrid::from(r.voxels.grid),
                                           TransferSettings{}, &run.progress);
  const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
  FinalGatherSettings fg;
  fg.rays = r.settings.final_gather_rays;
  fg.near = static_cast<float>(r.settings.final_gather_near);
  fg.near_min_rays = r.settings.final_gather_near_min_rays;
  fg.spots = r.settings.final_gather_spots;
  fg.seed = r.settings.seed;
  r.vertex_gather = build_final_gather(*run.tracer, lookup, r.patches.patches, r.voxels.grid,
                                       gather_points_of_vertices(mesh.positions, mesh.triangles),
                                       mesh.normals, fg, &run.progress);
  // From here on a patch's first-hit light is its samples' as the vertices'
  // rays see them (runtime/seen_first_hit.h).
  set_seen_weights(r.vertex_gather, r.patches, "final gather");
}

bool places_light_probes(const BakeRun& run) {
  return run.result.settings.light_probes != ProbePlacementMode::Off;
}

void light_probes_step(BakeRun& run) {
  BakeResult& r = run.result;
  const BakeSettings& s = r.settings;
  ProbePlacementRequest request;
  request.surfaces = s.light_probes != ProbePlacementMode::VolumesOnly;
  request.surfaces_optional = s.light_probes == ProbePlacementMode::Auto;
  request.volumes = parse_probe_volumes(s.light_probe_volumes, "light_probe_volumes");
  request.max_probes = static_cast<std::size_t>(s.light_probes_max);
  request.max_setting = "light_probes_max";
  request.volumes_setting = "light_probe_volumes";
  r.probe_placement = place_light_probes(*run.tracer, r.voxels, request, &run.progress);
  if (!r.probe_placement.surfaces_skipped.empty())
    run.diagnostics.warn("light_probes", "no light probes next to the surfaces: " +
                                             r.probe_placement.surfaces_skipped +
                                             " (set light_probes_max, or light_probes off)");
  std::vector<ProbeLattice> lattices = r.probe_placement.lattices();
  const SurfacePatchLookup lookup(r.voxels, r.samples, r.patch_of_sample);
  const int rays = s.final_gather_rays > 0 ? s.final_gather_rays : FinalGatherSettings{}.rays;
  r.light_probes =
      gather_light_probes(*run.tracer, lookup, r.patches.patches, r.voxels.grid,
                          std::move(r.probe_placement.position), rays, s.seed, &run.progress);
  r.light_probes.volumes = std::move(lattices);
  r.probe_placement.position.clear();
}

// Rows a little above 1 are the quadrature error of the near field (~1%):
// say so only beyond that.
bool has_rows_above_one(const BakeRun& run) { return run.result.checks.row_sum_max > 1.02; }

void warn_rows_above_one_step(BakeRun& run) {
  const FormFactorChecks& checks = run.result.checks;
  run.diagnostics.warn("form factors", std::to_string(checks.rows_above_one) +
                                           " patches have row sums above 1 (max " +
                                           fmt(checks.row_sum_max, 4) + ")");
}

void evaluation_lights_step(BakeRun& run) {
  BakeResult& r = run.result;
  // The first-hit light of the evaluation lights depends on the patches
  // only; channel_of_rgb is filled in by the transport stage.
  const std::vector<Light> lights = evaluation_lights(run.scene);
  // The emissive triangles together count as one more light.
  const std::vector<AreaLight> area = area_lights(run.scene);
  run.progress.begin_stage("direct light of the evaluation lights", lights.size() + 1);
  r.probe = IndirectLightProbe{};
  r.probe_lights_total = lights.size() + (area.empty() ? 0 : 1);
  for (const Patch& p : r.patches.patches) r.probe.area.push_back(p.area);
  // b as the run time makes it: seen-weighted over the samples when the
  // final gather gave the patches seen weights (runtime/seen_first_hit.h).
  const auto first_hit = [&run, &r](const std::vector<Light>& point,
                                    const std::vector<AreaLight>& emissive) {
    std::vector<glm::vec3> e(r.patches.size()), b(r.patches.size()),
        sample_e(r.patches.member_seen_weight.empty() ? 0 : r.samples.samples.size());
    direct_irradiance(*run.tracer, r.samples, r.patches, point, emissive, kAreaStrata, e, sample_e);
    seen_first_hit(r.samples, r.patches, e, sample_e, b);
    return b;
  };
  for (const Light& light : lights) {
    run.progress.check();
    r.probe.first_hit.push_back(first_hit({light}, {}));
    run.progress.advance();
  }
  if (!area.empty()) r.probe.first_hit.push_back(first_hit({}, area));
  run.progress.advance();
  run.progress.end_stage();
}

constexpr BakeStep kFormFactorSteps[] = {
    {"form factors", nullptr, form_factors_step},
    {nullptr, serves_the_root, serve_the_root_step},
    {"checks", nullptr, checks_step},
    {"closure", measures_closure, closure_step},
    {"balance", measures_closure, balance_step},
    {"final gather", gathers_vertices, final_gather_step},
    {"light probes", places_light_probes, light_probes_step},
    {nullptr, has_rows_above_one, warn_rows_above_one_step},
    {"evaluation lights", nullptr, evaluation_lights_step},
};

}  // namespace

std::span<const BakeStep> form_factor_steps() { return kFormFactorSteps; }

}  // namespace bounce
