// `bounce report SCENE`: error against run time for every method and setting.
// Sweeps patch mode (virtual, voxel), patch count, bounces and codec; for
// each, the bake time, the run time of one light update, the bytes of the
// baked matrix and the error against the path-traced reference
// (core/reference) on the scene camera's pictures and on mesh vertices
// (core/metrics). Writes report.md and report.json, prints the table, and
// marks the Pareto front of error against run time.
//
// It runs the same core functions as `bounce bake` and `bounce solve`, and
// reuses what the settings allow: one Baker run (voxels, samples, patches,
// form factors) per patch setting, then compute_transport per bounce count
// on those form factors and store_transport per codec on that matrix. A
// row's bake time is what a standalone bake of that row would have spent:
// the shared stages plus its own transport and storage stages.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/bake.h"
#include "bake/matrix_storage.h"
#include "base/error.h"
#include "commands.h"
#include "console_progress.h"
#include "io/atomic_file.h"
#include "metrics/image_metrics.h"
#include "metrics/vertex_metrics.h"
#include "raytrace/ray_tracer.h"
#include "reference/reference_cache.h"
#include "reference_check.h"
#include "runtime/camera_image.h"
#include "runtime/mesh_transfer.h"
#include "runtime/patch_lighting.h"
#include "scene/scene_loader.h"

namespace bounce::cli {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct ReportOptions {
  std::string scene;
  std::string out;
  std::string cache;
  bool no_cache = false;
  bool quick = false;
  bool json = false;
  bool quiet = false;
  std::vector<std::string> modes;
  std::vector<int> patches;
  std::vector<std::string> bounces;
  std::vector<std::string> codecs;
  int reference_samples = 0;  // 0: 256, or 48 with --quick
  int width = 0, height = 0;  // 0: 160 x 120, or 64 x 48 with --quick
};

struct CodecSetting {
  std::string name;  // dense, paper, ours
  std::optional<double> kept_fraction;
  std::string label() const {
    if (!kept_fraction) return name == "ours" ? "ours (budget)" : name;
    char s[64];
    std::snprintf(s, sizeof s, "%s %.3g%%", name.c_str(), 100.0 * *kept_fraction);
    return s;
  }
};

struct Row {
  std::string mode;
  int patches_target = 0;
  std::size_t patches = 0;
  std::string bounces;
  std::string codec;
  double kept_fraction = 1.0;
  double bake_seconds = 0.0;
  double direct_ms = 0.0, multiply_ms = 0.0;
  std::size_t matrix_bytes = 0;
  double indirect_power = 0.0;  // area-weighted, R+G+B, of T b
  ImageErrors full, indirect;
  VertexErrors vertex;
  // Relative RMSE with the reference's own noise taken out (metrics): what
  // the table shows and the Pareto front uses.
  double indirect_error = 0.0, vertex_error = 0.0;
  bool pareto = false;
  double update_ms() const { return direct_ms + multiply_ms; }
};

int parse_bounces(const std::string& b) {
  if (b == "auto") return TransportSettings::kAutoBounces;
  if (b == "inf") return TransportSettings::kInfiniteBounces;
  std::size_t used = 0;
  int k = 0;
  try {
    k = std::stoi(b, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != b.size() || k < 1 || k > TransportSettings::kMaxBounces)
    throw Error("--bounces", "each value must be auto, inf or 1.." +
                                 std::to_string(TransportSettings::kMaxBounces) + ", got '" + b +
                                 "'");
  return k;
}

// "ours", "paper", "dense", optionally with ":FRACTION" (kept share, 0..1).
CodecSetting parse_codec(const std::string& spec) {
  CodecSetting c;
  const auto colon = spec.find(':');
  c.name = spec.substr(0, colon);
  if (c.name != "dense" && c.name != "paper" && c.name != "ours")
    throw Error("--codecs",
                "each codec must be dense, paper or ours (optionally NAME:FRACTION), "
                "got '" +
                    spec + "'");
  if (colon != std::string::npos) {
    char* end = nullptr;
    const std::string f = spec.substr(colon + 1);
    const double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !(v > 0.0 && v <= 1.0) || c.name == "dense")
      throw Error("--codecs", "'" + spec +
                                  "': the kept fraction must be in (0, 1] and only "
                                  "paper or ours take one");
    c.kept_fraction = v;
  }
  return c;
}

// Marks the rows no other row beats on both error and run time.
void mark_pareto(std::vector<Row>& rows) {
  for (Row& r : rows) {
    r.pareto = std::isfinite(r.indirect_error);
    for (const Row& o : rows) {
      if (&o == &r) continue;
      const bool no_worse = o.indirect_error <= r.indirect_error && o.update_ms() <= r.update_ms();
      const bool better = o.indirect_error < r.indirect_error || o.update_ms() < r.update_ms();
      if (no_worse && better) {
        r.pareto = false;
        break;
      }
    }
  }
}

std::string fixed(double v, int digits) {
  char s[64];
  std::snprintf(s, sizeof s, "%.*f", digits, v);
  return s;
}

std::string table(const std::vector<Row>& rows) {
  std::ostringstream t;
  t << "| mode | patches | bounces | codec | bake s | update ms (direct + T b) | matrix KiB | "
       "indirect rel. RMSE | full rel. RMSE | full PSNR dB | full SSIM | vertex rel. RMSE | "
       "Pareto |\n";
  t << "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
  for (const Row& r : rows) {
    t << "| " << r.mode << " | " << r.patches << " | " << r.bounces << " | " << r.codec << " | "
      << fixed(r.bake_seconds, 2) << " | " << fixed(r.update_ms(), 2) << " ("
      << fixed(r.direct_ms, 2) << " + " << fixed(r.multiply_ms, 3) << ") | "
      << fixed(static_cast<double>(r.matrix_bytes) / 1024.0, 1) << " | "
      << fixed(r.indirect_error, 4) << " | " << fixed(r.full.relative_rmse, 4) << " | "
      << fixed(r.full.psnr, 2) << " | " << fixed(r.full.ssim, 4) << " | "
      << fixed(r.vertex_error, 4) << " | " << (r.pareto ? "*" : "") << " |\n";
  }
  return t.str();
}

ordered_json errors_json(const ImageErrors& e) {
  return {{"mse", e.mse},   {"rmse", e.rmse}, {"relative_rmse", e.relative_rmse},
          {"psnr", e.psnr}, {"ssim", e.ssim}, {"pixels", e.pixels}};
}

// The reference's own noise, as a relative RMSE: sqrt(sum var / sum y^2) on
// the masked pixels. A method's measured error cannot go much below it.
double noise_floor(const RgbFloatImage& mean, const RgbFloatImage& variance,
                   const std::vector<std::uint8_t>& mask) {
  double var = 0.0, sq = 0.0;
  for (std::size_t i = 0; i < mean.pixels.size(); ++i) {
    if (!mask[i]) continue;
    for (int c = 0; c < 3; ++c) {
      var += variance.pixels[i][c];
      sq += static_cast<double>(mean.pixels[i][c]) * mean.pixels[i][c];
    }
  }
  return sq > 0.0 ? std::sqrt(var / sq) : 0.0;
}

void run_report(ReportOptions opt) {
  const auto start = Clock::now();
  if (opt.modes.empty()) opt.modes = {"virtual", "voxel"};
  if (opt.patches.empty())
    opt.patches = opt.quick ? std::vector<int>{60, 150} : std::vector<int>{150, 300, 600, 1000};
  if (opt.bounces.empty()) opt.bounces = {"1", "2", "3", "auto", "inf"};
  if (opt.codecs.empty())
    opt.codecs = opt.quick
                     ? std::vector<std::string>{"dense", "paper", "ours"}
                     : std::vector<std::string>{"dense", "paper", "ours", "ours:0.02", "ours:0.08"};
  if (opt.reference_samples == 0) opt.reference_samples = opt.quick ? 128 : 512;
  if (opt.width == 0) opt.width = opt.quick ? 64 : 160;
  if (opt.height == 0) opt.height = opt.quick ? 48 : 120;
  for (const std::string& m : opt.modes)
    if (m != "virtual" && m != "voxel")
      throw Error("--modes", "each mode must be virtual or voxel, got '" + m + "'");
  for (int p : opt.patches)
    if (p < 8 || p > 100000) throw Error("--patches", "each count must be in 8..100000");
  if (opt.width < 16 || opt.height < 16 || opt.width > 4096 || opt.height > 4096)
    throw Error("--width/--height", "must be between 16 and 4096 (SSIM needs 11 x 11 windows)");
  std::vector<int> bounces;
  for (const std::string& b : opt.bounces) bounces.push_back(parse_bounces(b));
  std::vector<CodecSetting> codecs;
  for (const std::string& c : opt.codecs) codecs.push_back(parse_codec(c));

  Diagnostics diag;
  diag.set_listener([&opt](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning && !opt.quiet && !opt.json)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(), d.message.c_str());
  });
  const Scene scene = SceneLoader(diag).load(opt.scene);
  const RayTracer tracer(scene);
  const std::vector<AreaLight> area = area_lights(scene);
  ConsoleProgress console(opt.quiet || opt.json);
  Progress& progress = console.progress();

  // The reference: camera pictures and vertices of a fixed evaluation mesh
  // (the scene refined on a 16-cell grid, 8 with --quick), so every row is
  // measured at the same points.
  std::unique_ptr<ReferenceCache> cache;
  if (!opt.no_cache)
    cache = std::make_unique<ReferenceCache>(opt.cache.empty() ? ReferenceCache::default_dir()
                                                               : fs::path(opt.cache));
  ReferenceSettings rs;
  rs.samples = opt.reference_samples;
  const ReferencePathTracer pt(tracer, rs);
  auto t = Clock::now();
  bool images_cached = false, points_cached = false;
  const ReferenceImages ref =
      cached_reference_images(pt, opt.width, opt.height, cache.get(), &progress, &images_cached);
  const std::vector<std::uint8_t> mask = mask_from_coverage(ref.coverage);
  LitMesh eval_mesh =
      build_transfer_mesh(scene, TransferGrid::from(VoxelGrid(scene.bounds(), opt.quick ? 8 : 16)),
                          TransferSettings{}, &progress);
  std::vector<ReferencePoint> points;
  for (std::size_t v = 0; v < eval_mesh.positions.size(); ++v)
    points.push_back(
        {eval_mesh.positions[v], eval_mesh.normals[v], glm::vec3(0.0f), glm::vec3(0.0f)});
  // Albedo per vertex from a face that uses it.
  for (std::size_t f = 0; f < eval_mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c)
      points[eval_mesh.triangles[f][c]].albedo =
          scene.material_of(eval_mesh.source_triangle[f]).albedo;
  const PointReference ref_points =
      cached_reference_points(pt, points, cache.get(), &progress, &points_cached);
  std::vector<glm::vec3> ref_vertex_indirect(points.size()), ref_vertex_variance(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    ref_vertex_indirect[v] = points[v].albedo * ref_points.indirect_irradiance[v];
    ref_vertex_variance[v] = points[v].albedo * points[v].albedo * ref_points.indirect_variance[v];
  }
  const double reference_seconds = since(t);

  std::vector<Row> rows;
  for (const std::string& mode : opt.modes)
    for (int target : opt.patches) {
      BakeSettings bs;
      bs.patches_total = target;
      bs.patch_mode = mode == "virtual" ? PatchMode::Virtual : PatchMode::Voxel;
      bs.codec = CodecChoice::Dense;
      bs.pictures = false;
      // OpenBLAS: no OpenCL kernel compile inside a timing sweep.
      bs.transport.backend = TransportSettings::Backend::OpenBLAS;
      bs.transport.bounces = bounces.front();
      if (!opt.quiet && !opt.json)
        std::fprintf(stderr, "report: %s patches, target %d\n", mode.c_str(), target);
      const BakeResult bake = Baker(scene, bs, diag).run(progress);
      double shared = 0.0, transport_first = 0.0, probe_seconds = 0.0;
      for (const StageStats& s : bake.stages) {
        if (s.name == "transport")
          transport_first = s.seconds;
        else if (s.name == "evaluation lights")
          probe_seconds = s.seconds;
        else if (s.name != "compress")
          shared += s.seconds;
      }
      const TransferGrid grid = TransferGrid::from(bake.voxels.grid);
      std::vector<glm::vec3> albedo;
      for (const Patch& p : bake.patches.patches) albedo.push_back(p.albedo);
      for (std::size_t bi = 0; bi < bounces.size(); ++bi) {
        TransportResult other;
        double transport_seconds = transport_first;
        if (bi > 0) {
          TransportSettings ts = bake.settings.transport;
          ts.bounces = bounces[bi];
          t = Clock::now();
          other = compute_transport(bake.form_factors, albedo, ts, &progress, diag);
          transport_seconds = since(t);
        }
        const TransportResult& transport = bi == 0 ? bake.transport : other;
        // Codecs on every bounce setting would multiply the table; the codec
        // sweep runs at auto bounces (the default bake), dense elsewhere.
        const bool codec_sweep = opt.bounces[bi] == "auto" || bounces.size() == 1;
        for (const CodecSetting& codec : codecs) {
          if (!codec_sweep && codec.name != "dense") continue;
          BakeSettings cs = bake.settings;
          cs.codec = codec.name == "dense"   ? CodecChoice::Dense
                     : codec.name == "paper" ? CodecChoice::Paper
                                             : CodecChoice::Ours;
          cs.kept_fraction = codec.kept_fraction;
          t = Clock::now();
          const MatrixStorage storage = store_transport(transport, bake.probe, cs, &progress, diag);
          const double store_seconds = since(t);
          Row row;
          row.mode = mode;
          row.patches_target = target;
          row.patches = bake.patches.size();
          row.bounces = opt.bounces[bi];
          row.codec = codec.label();
          row.matrix_bytes = storage.stored_bytes;
          row.bake_seconds = shared + transport_seconds + store_seconds +
                             (codec.name == "dense" ? 0.0 : probe_seconds);
          std::shared_ptr<void> keep;
          const IndirectMultiply multiply = baked_multiply(transport, storage, keep);
          // Best of five updates: the run time without first-touch costs.
          PatchLighting light;
          row.direct_ms = row.multiply_ms = std::numeric_limits<double>::infinity();
          for (int rep = 0; rep < 5; ++rep) {
            light = light_patches(tracer, bake.samples, bake.patches, scene.lights, area, multiply);
            row.direct_ms = std::min(row.direct_ms, 1e3 * light.seconds_direct);
            row.multiply_ms = std::min(row.multiply_ms, 1e3 * light.seconds_indirect);
          }
          for (std::size_t p = 0; p < light.indirect.size(); ++p)
            row.indirect_power += bake.patches.patches[p].area *
                                  (light.indirect[p].r + light.indirect[p].g + light.indirect[p].b);
          const PatchGather gather(bake.patches.patches, light.indirect, grid, &tracer,
                                   GatherSettings{});
          CameraImageSettings camera;
          camera.width = opt.width;
          camera.height = opt.height;
          camera.samples_per_side = 2;  // the reference jitters over the pixel too
          const CameraImages images = render_camera(tracer, gather, camera, &progress);
          row.full = image_errors(images.full, ref.full, mask);
          row.indirect = image_errors(images.indirect, ref.indirect, mask);
          LitMesh lit = eval_mesh;
          relight(lit, gather, &progress);
          row.vertex = vertex_errors(lit.radiosity, ref_vertex_indirect);
          row.indirect_error = noise_corrected_relative_rmse(images.indirect, ref.indirect,
                                                             ref.indirect_variance, mask);
          row.vertex_error = noise_corrected_relative_rmse(lit.radiosity, ref_vertex_indirect,
                                                           ref_vertex_variance);
          rows.push_back(row);
        }
      }
    }
  mark_pareto(rows);

  ordered_json report;
  report["scene"] = {
      {"name", scene.name}, {"path", scene.path}, {"triangles", scene.triangle_count()}};
  report["reference"] = {
      {"samples_per_pixel", ref.samples},
      {"samples_per_vertex", ref_points.samples},
      {"width", opt.width},
      {"height", opt.height},
      {"vertices", points.size()},
      {"images_from_cache", images_cached},
      {"vertices_from_cache", points_cached},
      {"cache", cache ? cache->dir().string() : std::string()},
      {"seconds", reference_seconds},
      {"noise_floor_full_relative_rmse", noise_floor(ref.full, ref.full_variance, mask)},
      {"noise_floor_indirect_relative_rmse",
       noise_floor(ref.indirect, ref.indirect_variance, mask)}};
  ordered_json jrows = ordered_json::array();
  for (const Row& r : rows)
    jrows.push_back({{"mode", r.mode},
                     {"patches_target", r.patches_target},
                     {"patches", r.patches},
                     {"bounces", r.bounces},
                     {"codec", r.codec},
                     {"bake_seconds", r.bake_seconds},
                     {"update_ms", r.update_ms()},
                     {"direct_ms", r.direct_ms},
                     {"multiply_ms", r.multiply_ms},
                     {"matrix_bytes", r.matrix_bytes},
                     {"indirect_power", r.indirect_power},
                     {"image_full", errors_json(r.full)},
                     {"image_indirect", errors_json(r.indirect)},
                     {"image_indirect_noise_corrected_relative_rmse", r.indirect_error},
                     {"vertex_indirect_noise_corrected_relative_rmse", r.vertex_error},
                     {"vertex_indirect",
                      {{"relative_rmse", r.vertex.relative_rmse},
                       {"mean_relative", r.vertex.mean_relative},
                       {"max_relative", r.vertex.max_relative},
                       {"vertices", r.vertex.vertices}}},
                     {"pareto", r.pareto}});
  report["rows"] = jrows;
  report["seconds"] = since(start);

  const fs::path out = opt.out.empty() ? fs::path("reports") / scene.name : fs::path(opt.out);
  fs::create_directories(out);
  {
    AtomicFile f(out / "report.json");
    f.stream() << report.dump(2) << '\n';
    f.commit();
  }
  const std::string md_table = table(rows);
  {
    AtomicFile f(out / "report.md");
    auto& s = f.stream();
    s << "# Error against run time: " << scene.name << "\n\n";
    s << "Reference: diffuse path tracer (docs/reference.md), " << ref.samples
      << " paths per pixel at " << opt.width << "x" << opt.height << ", " << ref_points.samples
      << " per vertex on " << points.size() << " evaluation vertices"
      << (images_cached && points_cached ? " (from the cache)" : "") << ". Its own noise, as a "
      << "relative RMSE: full "
      << fixed(report["reference"]["noise_floor_full_relative_rmse"].get<double>(), 4)
      << ", indirect "
      << fixed(report["reference"]["noise_floor_indirect_relative_rmse"].get<double>(), 4)
      << " -- errors near these are at the reference's noise.\n\n";
    s << "Columns: bake s = the stages a standalone bake of the row runs; update ms = best of "
         "five light updates (direct light on the patches + the product T b); matrix KiB = "
         "the stored multi-bounce matrix; errors against the reference on the scene camera's "
         "pictures (background masked): indirect rel. RMSE with the reference's noise removed "
         "(docs/reference.md), full-picture relative RMSE, PSNR and SSIM as measured; vertex "
         "rel. RMSE = the indirect light at the evaluation vertices, noise removed. "
         "Pareto * = no other row has both lower indirect-image error and lower update time. "
         "Codecs are swept at `auto` bounces, other bounce counts use the dense matrix.\n\n";
    s << md_table << '\n';
    s << "Plots (error against run time, error against memory, virtual against voxel) are "
         "produced by the studio/plots step from report.json; this file holds the numbers.\n";
    f.commit();
  }
  if (opt.json) {
    std::cout << report.dump(2) << '\n';
    return;
  }
  std::printf("%s\nReport of %zu settings in %.1f s: %s, %s\n", md_table.c_str(), rows.size(),
              since(start), (out / "report.md").string().c_str(),
              (out / "report.json").string().c_str());
}

}  // namespace

void register_report(CLI::App& app) {
  auto opt = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Error against run time: bake the scene over a sweep of settings (patch mode, patch count, "
      "bounces, codec) and measure each against a path-traced reference; writes report.md and "
      "report.json and marks the Pareto front");
  cmd->add_option("scene", opt->scene, "Scene folder, scene.json or mesh file")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder (default: reports/SCENE_NAME)");
  cmd->add_flag("--quick", opt->quick,
                "A small sweep (2 patch counts, small pictures, a noisier reference) for tests");
  cmd->add_option("--modes", opt->modes, "Patch modes: virtual, voxel (default both)");
  cmd->add_option("--patches", opt->patches,
                  "Target patch counts (default 150 300 600 1000; --quick: 60 150)");
  cmd->add_option("--bounces", opt->bounces, "Bounce settings (default 1 2 3 auto inf)");
  cmd->add_option("--codecs", opt->codecs,
                  "Codecs at auto bounces: dense, paper, ours, or NAME:KEPT_FRACTION (default "
                  "dense paper ours ours:0.02 ours:0.08)");
  cmd->add_option("--reference-samples", opt->reference_samples,
                  "Reference paths per pixel and per vertex (default 512; --quick: 128)");
  cmd->add_option("--width", opt->width, "Picture width (default 160; --quick: 64)");
  cmd->add_option("--height", opt->height, "Picture height (default 120; --quick: 48)");
  cmd->add_option("--cache", opt->cache,
                  "Reference cache folder (default $XDG_CACHE_HOME/bounce/reference)");
  cmd->add_flag("--no-cache", opt->no_cache, "Always render the reference, store nothing");
  cmd->add_flag("--json", opt->json, "Print report.json to stdout instead of the table");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress bars");
  cmd->callback([opt]() { run_report(*opt); });
}

}  // namespace bounce::cli
