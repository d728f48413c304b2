// `bounce bench dynamic BAKE`: the dynamic variants (local
// matrix, temporal radiosity, frame graph with transient-memory aliasing)
// against the full multi-bounce product and classic radiosity, as one table
// like the paper's Table 2, then the local-matrix update against LU
// recomputation and the transient memory with and without aliasing (the
// paper's Table 1). Needs the exact matrices: bake with --dump-matrices.
// With the scene (the manifest's path, or --scene) it also renders the scene
// camera's indirect picture of every method the way `bounce solve` does
// (runtime/camera_image.h) and compares it with the full product's (SSIM,
// relative RMSE) and with the path-traced reference (core/reference, cached).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "bench_commands.h"
#include "bounce/bake_folder.h"
#include "bounce/diagnostics.h"
#include "bounce/error.h"
#include "bounce/metrics.h"
#include "bounce/relight.h"
#include "bounce/report.h"
#include "bounce/scene.h"
#include "console_progress.h"
#include "dynamic_bench.h"

namespace bounce::cli {

namespace {

struct DynamicBenchOptions {
  std::string bake;
  int samples = 64;
  float weight = 0.9f;
  int repeats = 10;
  int light = 0, jump_to = 1;
  int bounces = 16;
  bool no_local = false;
  bool no_classic = false;
  bool json = false;
  std::string scene;  // empty: the manifest's scene path
  int width = 96, height = 72;
  bool no_images = false;
  int reference_samples = 256;  // 0: no reference
  bool quiet = false;
  // Temporal radiosity with importance on the light (needs the bake's
  // compressed matrix).
  int block_columns = 12;
  double change_scale = 0.25;
  int max_history = 64;
  int moving_frames = 32;  // 0: no moving light
};

// The point light that moves: the bake's first point light, else the
// scene's, else one at the top of the middle of the scene; it circles in the
// horizontal plane (y up) with a radius of 0.15 of the bounds' diagonal, one
// turn over the path.
std::vector<std::vector<glm::vec3>> moving_point_light(const LoadedBake& b, const Scene& scene,
                                                       const RayTracer& tracer, int frames) {
  Light light;
  bool found = false;
  for (const Light& l : b.description.scene_lights)
    if (l.type == Light::Type::Point) {
      light = l;
      found = true;
      break;
    }
  const Bounds bounds = scene.bounds();
  if (!found)
    for (const Light& l : scene.lights)
      if (l.type == Light::Type::Point) {
        light = l;
        found = true;
        break;
      }
  if (!found) {
    light.position = 0.5f * (bounds.lo + bounds.hi);
    light.position.y = bounds.lo.y + 0.8f * (bounds.hi.y - bounds.lo.y);
    light.intensity = glm::dot(bounds.hi - bounds.lo, bounds.hi - bounds.lo);
  }
  light.type = Light::Type::Point;
  light.name = "moving";
  const float radius = 0.15f * glm::length(bounds.hi - bounds.lo);
  std::vector<std::vector<glm::vec3>> path;
  for (int f = 0; f < frames; ++f) {
    const float angle = 6.28318530718f * static_cast<float>(f) / static_cast<float>(frames);
    Light moved = light;
    moved.position += radius * glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
    path.push_back(
        first_bounce(b.patches, direct_irradiance(tracer, b.samples, b.patches, {moved})));
  }
  return path;
}

void run(const DynamicBenchOptions& opt) {
  if (opt.samples < 1 || opt.samples > 1 << 20)
    throw Error("--samples", "must be between 1 and 1048576");
  if (!(opt.weight >= 0.0f && opt.weight < 1.0f)) throw Error("--weight", "must be in [0, 1)");
  if (opt.repeats < 1 || opt.repeats > 10000)
    throw Error("--repeats", "must be between 1 and 10000");
  if (opt.bounces < 1 || opt.bounces > 1000) throw Error("--bounces", "must be between 1 and 1000");
  if (opt.width < 16 || opt.width > 4096 || opt.height < 16 || opt.height > 4096)
    throw Error("--width/--height",
                "must be between 16 and 4096 (SSIM compares pixels at least 5 from the border)");
  if (opt.reference_samples < 0 || opt.reference_samples > 1 << 16)
    throw Error("--reference-samples", "must be between 0 and 65536");
  if (opt.block_columns < 1 || opt.block_columns > 1 << 20)
    throw Error("--block-columns", "must be between 1 and 1048576");
  if (!(opt.change_scale > 0.0 && opt.change_scale <= 1e6))
    throw Error("--change-scale", "must be positive and at most 1e6");
  if (opt.max_history < 0 || opt.max_history > 1 << 20)
    throw Error("--max-history", "must be between 0 and 1048576");
  if (opt.moving_frames < 0 || opt.moving_frames > 4096)
    throw Error("--moving-frames", "must be between 0 and 4096");
  const LoadedBake b = BakeReader::read(opt.bake, true);
  if (b.dense.empty())
    throw Error(opt.bake, "holds no exact transport matrix T.npy: bake with --dump-matrices");
  const auto lights = static_cast<int>(b.probe.first_hit.size());
  for (const auto& [name, index] : {std::pair{"--light", opt.light}, {"--jump-to", opt.jump_to}})
    if (index < 0 || index >= lights)
      throw Error(name, "light " + std::to_string(index) + " does not exist (the bake has " +
                            std::to_string(lights) + " evaluation lights)");
  if (opt.light == opt.jump_to) throw Error("--jump-to", "must differ from --light");

  DynamicBenchInput in;
  in.n = b.size();
  for (const auto& t : b.dense) in.transport.push_back(t.data());
  in.channel_of_rgb = b.channel_of_rgb;
  for (const Patch& p : b.patches.patches) in.albedo.push_back(p.albedo);
  in.area = b.probe.area;
  in.light = b.probe.first_hit[static_cast<std::size_t>(opt.light)];
  in.jumped_light = b.probe.first_hit[static_cast<std::size_t>(opt.jump_to)];
  in.classic_bounces = opt.bounces;
  const std::optional<std::vector<float>> f = read_form_factors(opt.bake, in.n);
  if (f) in.form_factors = f->data();
  // The pictures: the scene as baked, its camera, the gather `bounce solve`
  // uses; the reference under the scene's own lights.
  std::unique_ptr<Scene> scene;
  std::unique_ptr<RayTracer> tracer;
  ConsoleProgress console(opt.quiet || opt.json);
  bool reference_cached = false;
  if (!opt.no_images) {
    Diagnostics diag;
    scene = std::make_unique<Scene>(load_baked_scene(b, opt.scene, diag));
    tracer = std::make_unique<RayTracer>(*scene);
    const TransferGrid grid = b.description.grid;
    CameraImageSettings cs;
    cs.width = opt.width;
    cs.height = opt.height;
    cs.samples_per_side = 1;
    const RayTracer* t = tracer.get();
    const std::vector<Patch>* patches = &b.patches.patches;
    in.render_indirect = [t, patches, grid, cs](const std::vector<glm::vec3>& indirect) {
      const PatchGather gather(*patches, indirect, grid, t, GatherSettings{});
      return render_camera(*t, gather, cs).indirect;
    };
    if (opt.moving_frames > 0)
      in.moving_light = moving_point_light(b, *scene, *tracer, opt.moving_frames);
    const std::vector<AreaLight> area = area_lights(*scene);
    in.scene_light = first_bounce(
        b.patches, direct_irradiance(*tracer, b.samples, b.patches, scene->lights, area));
    // A scene without lights has a black reference: nothing to compare.
    const bool lit = !scene->lights.empty() || !area.empty();
    if (opt.reference_samples > 0 && lit) {
      ReferenceSettings rs;
      rs.samples = opt.reference_samples;
      const ReferencePathTracer pt(*tracer, rs);
      const ReferenceCache cache(ReferenceCache::default_dir());
      const ReferenceImages ref = cached_reference_images(pt, opt.width, opt.height, &cache,
                                                          &console.progress(), &reference_cached);
      in.reference_indirect = ref.indirect;
      in.reference_variance = ref.indirect_variance;
      in.image_mask = mask_from_coverage(ref.coverage);
    } else {
      const PatchGather none(b.patches.patches, std::vector<glm::vec3>(in.n, glm::vec3(0.0f)), grid,
                             tracer.get(), GatherSettings{});
      in.image_mask = mask_from_coverage(render_camera(*tracer, none, cs).coverage);
    }
    if (!lit) in.scene_light.clear();
    if (std::none_of(in.image_mask.begin(), in.image_mask.end(), [](std::uint8_t m) { return m; }))
      throw Error(scene->path,
                  "the scene camera sees no geometry: nothing to compare "
                  "(use --no-images)");
  }

  const std::unique_ptr<CompressedTransport> compressed =
      compressed_product(b.compressed, b.channel_of_rgb);
  in.compressed = compressed.get();

  DynamicBenchSettings settings;
  settings.light_temporal.block_columns = opt.block_columns;
  settings.light_temporal.history.change_scale = opt.change_scale;
  settings.light_temporal.history.max_frames = opt.max_history;
  settings.temporal.samples_per_patch = opt.samples;
  settings.temporal.history_weight = opt.weight;
  settings.repeats = opt.repeats;
  settings.local_matrix = !opt.no_local;
  settings.classic = !opt.no_classic;
  const DynamicBench bench = run_dynamic_bench(in, settings);

  if (opt.json) {
    nlohmann::json methods = nlohmann::json::array();
    for (const DynamicMethodRow& r : bench.methods)
      methods.push_back({{"method", r.method},
                         {"available", r.available},
                         {"note", r.note},
                         {"ms_per_frame", r.ms_per_frame},
                         {"error_after_1_4_16_64", r.error},
                         {"ghosting_frames", r.ghosting_frames},
                         {"persistent_bytes", r.persistent_bytes},
                         {"transient_bytes", r.transient_bytes},
                         {"bytes_per_frame", r.bytes_per_frame}});
    for (std::size_t i = 0; i < bench.methods.size(); ++i) {
      const DynamicMethodRow& r = bench.methods[i];
      if (r.images) {
        methods[i]["image_ssim_after_1_4_16_64"] = r.image_ssim;
        methods[i]["image_relative_rmse_after_1_4_16_64"] = r.image_error;
        methods[i]["image_ssim_after_jump_1_4"] = r.jump_ssim;
      }
      if (r.moving)
        methods[i]["moving_light"] = {{"ms_per_frame", r.moving_ms},
                                      {"mean_error", r.moving_error},
                                      {"last_image_ssim", r.moving_ssim}};
      if (r.against_reference) {
        methods[i]["reference_relative_rmse"] = r.reference_error;
        methods[i]["reference_ssim"] = r.reference_ssim;
      }
    }
    nlohmann::json local = nlohmann::json::array();
    for (const LocalMatrixRow& r : bench.local)
      local.push_back({{"patch", r.patch},
                       {"sigma", r.sigma},
                       {"remove_ms", r.remove_ms},
                       {"add_ms", r.add_ms},
                       {"recompute_ms", r.recompute_ms},
                       {"remove_vs_recompute", r.remove_vs_recompute},
                       {"round_trip", r.round_trip}});
    nlohmann::json memory = nlohmann::json::array();
    for (const TransientMemoryRow& r : bench.memory)
      memory.push_back({{"scene", r.scene},
                        {"patches", r.patches},
                        {"unaliased_bytes", r.unaliased_bytes},
                        {"aliased_bytes", r.aliased_bytes}});
    nlohmann::json summary{{"bake", opt.bake},          {"patches", bench.n},
                           {"samples", opt.samples},    {"weight", opt.weight},
                           {"methods", methods},        {"local_matrix", local},
                           {"transient_memory", memory}};
    if (bench.image_width > 0)
      summary["pictures"] = {{"width", bench.image_width},
                             {"height", bench.image_height},
                             {"reference_samples", opt.reference_samples},
                             {"reference_cached", reference_cached},
                             {"reference_noise", bench.reference_noise}};
    std::cout << summary.dump(2) << '\n';
    return;
  }
  std::printf(
      "\nbench dynamic: %s (%s), %zu patches, %d samples per patch, w = %.3g, light %d "
      "-> %d\n",
      opt.bake.c_str(), b.description.scene_name.c_str(), bench.n, opt.samples,
      static_cast<double>(opt.weight), opt.light, opt.jump_to);
  std::printf("%s", dynamic_bench_table(bench).c_str());
  std::printf(
      "err@f: area-weighted relative RMS of the indirect light against the full product after f "
      "frames of one light; ghost: frames after the light jumps until the error is back under "
      "1.5x its err@64 (at least 1e-3); persist: matrices/tables and the history; transient: "
      "the frame graph's per-frame buffers incl. a local-matrix update, without aliasing except "
      "in the aliasing row.\n");
  if (bench.image_width > 0 && bench.reference_noise > 0.0)
    std::printf("reference: %d paths per pixel%s, under the scene's own lights\n",
                opt.reference_samples, reference_cached ? " (cached)" : "");
}

}  // namespace

void register_bench_dynamic(CLI::App& bench) {
  auto opt = std::make_shared<DynamicBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "dynamic",
      "Dynamic radiosity: full multi-bounce product vs temporal radiosity (alias "
      "tables, C++ and OpenCL, with and without frame-graph memory aliasing) vs classic; ms per "
      "frame, error after 1/4/16/64 frames (per patch, and SSIM / relative RMSE of the scene "
      "camera's picture), ghosting after a light jump, error and SSIM against the path-traced "
      "reference, memory; local-matrix rank-1 updates vs LU. Needs a bake made with "
      "--dump-matrices");
  cmd->add_option("bake", opt->bake, "Bake folder with T.npy (and F.npy)")->required();
  cmd->add_option("--samples", opt->samples, "Temporal radiosity: samples per patch and frame")
      ->capture_default_str();
  cmd->add_option("--weight", opt->weight, "Temporal radiosity: history weight w")
      ->capture_default_str();
  cmd->add_option("--repeats", opt->repeats, "Timed frames per method (after one warm-up)")
      ->capture_default_str();
  cmd->add_option("--light", opt->light, "Evaluation light before the jump")->capture_default_str();
  cmd->add_option("--jump-to", opt->jump_to, "Evaluation light after the jump")
      ->capture_default_str();
  cmd->add_option("--bounces", opt->bounces, "K of the classic baseline")->capture_default_str();
  cmd->add_flag("--no-local", opt->no_local,
                "Skip the local-matrix rows (they factorise T twice by LU)");
  cmd->add_flag("--no-classic", opt->no_classic,
                "Skip the classic row (K products with F per frame, the slowest row)");
  cmd->add_option("--scene", opt->scene,
                  "The scene the bake was made from, if it moved (default: the path in the "
                  "bake's manifest)");
  cmd->add_option("--width", opt->width, "Width of the compared camera pictures")
      ->capture_default_str();
  cmd->add_option("--height", opt->height, "Height of the compared camera pictures")
      ->capture_default_str();
  cmd->add_option("--reference-samples", opt->reference_samples,
                  "Paths per pixel of the path-traced reference (cached; 0: none)")
      ->capture_default_str();
  cmd->add_flag("--no-images", opt->no_images,
                "Compare per-patch light only: no camera pictures, no reference");
  cmd->add_option("--block-columns", opt->block_columns,
                  "Light-importance temporal radiosity: block columns (4 patches each) drawn "
                  "per frame")
      ->capture_default_str();
  cmd->add_option("--change-scale", opt->change_scale,
                  "Light-importance temporal radiosity: a relative light change this large "
                  "drops the history")
      ->capture_default_str();
  cmd->add_option("--max-history", opt->max_history,
                  "Light-importance temporal radiosity: most frames the history averages")
      ->capture_default_str();
  cmd->add_option("--moving-frames", opt->moving_frames,
                  "Frames of the moving point light's path (one circle; 0: none; needs the "
                  "scene)")
      ->capture_default_str();
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress bars");
  cmd->add_flag("--json", opt->json, "Machine-readable output");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace bounce::cli
