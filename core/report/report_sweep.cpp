#include "report/report_sweep.h"

#include <optional>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "bake/bake.h"
#include "bake/matrix_storage.h"
#include "base/error.h"
#include "metrics/image_metrics.h"
#include "metrics/vertex_metrics.h"
#include "raytrace/ray_tracer.h"
#include "reference/reference_cache.h"
#include "report/baked_multiply.h"
#include "report/exact_patch_light.h"
#include "report/report_probes.h"
#include "runtime/camera_image.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_build.h"
#include "runtime/mesh_transfer.h"
#include "runtime/patch_lighting.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

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
    throw Error("bounces", "each value must be auto, inf or 1.." +
                               std::to_string(TransportSettings::kMaxBounces) + ", got '" + b +
                               "'");
  return k;
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

}  // namespace

std::string ReportCodec::label() const {
  if (!kept_fraction) return name == "ours" ? "ours (budget)" : name;
  char s[64];
  std::snprintf(s, sizeof s, "%s %.3g%%", name.c_str(), 100.0 * *kept_fraction);
  return s;
}

ReportCodec ReportCodec::parse(const std::string& spec) {
  ReportCodec c;
  const auto colon = spec.find(':');
  c.name = spec.substr(0, colon);
  if (c.name != "dense" && c.name != "paper" && c.name != "ours")
    throw Error(
        "codecs",
        "each codec must be dense, paper or ours (optionally NAME:FRACTION), got '" + spec + "'");
  if (colon != std::string::npos) {
    char* end = nullptr;
    const std::string f = spec.substr(colon + 1);
    const double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !(v > 0.0 && v <= 1.0) || c.name == "dense")
      throw Error("codecs", "'" + spec +
                                "': the kept fraction must be in (0, 1] and only "
                                "paper or ours take one");
    c.kept_fraction = v;
  }
  return c;
}

void ReportSweepSettings::fill_defaults(bool quick) {
  if (modes.empty()) modes = {"virtual", "voxel"};
  if (patches.empty())
    patches = quick ? std::vector<int>{60, 150} : std::vector<int>{150, 300, 600, 1000};
  if (bounces.empty()) bounces = {"1", "2", "3", "auto", "inf"};
  if (codecs.empty())
    codecs = quick ? std::vector<std::string>{"dense", "paper", "ours"}
                   : std::vector<std::string>{"dense", "paper", "ours", "ours:0.02", "ours:0.08"};
  if (reference_samples == 0) reference_samples = quick ? 128 : 512;
  if (width == 0) width = quick ? 64 : 160;
  if (height == 0) height = quick ? 48 : 120;
  if (eval_grid == 0) eval_grid = quick ? 8 : 16;
  if (transfer.empty()) transfer = "final-gather";
}

void ReportSweepSettings::validate() const {
  for (const std::string& m : modes)
    if (m != "virtual" && m != "voxel")
      throw Error("modes", "each mode must be virtual or voxel, got '" + m + "'");
  for (int p : patches)
    if (p < 8 || p > 100000) throw Error("patches", "each count must be in 8..100000");
  if (width < 16 || height < 16 || width > 4096 || height > 4096)
    throw Error("width/height", "must be between 16 and 4096 (SSIM needs 11 x 11 windows)");
  if (reference_samples < 1) throw Error("reference_samples", "must be at least 1");
  if (eval_grid < 1 || eval_grid > 1024) throw Error("eval_grid", "must be in 1..1024");
  if (transfer != "final-gather" && transfer != "nearest")
    throw Error("transfer", "must be final-gather or nearest, got '" + transfer + "'");
  for (const std::string& b : bounces) parse_bounces(b);
  for (const std::string& c : codecs) ReportCodec::parse(c);
}

ReportData run_report_sweep(const Scene& scene, const ReportSweepSettings& opt,
                            const ReferenceCache* cache, Progress& progress, Diagnostics& diag,
                            const std::function<void(const std::string&)>& log) {
  const auto start = Clock::now();
  opt.validate();
  std::vector<int> bounces;
  for (const std::string& b : opt.bounces) bounces.push_back(parse_bounces(b));
  std::vector<ReportCodec> codecs;
  for (const std::string& c : opt.codecs) codecs.push_back(ReportCodec::parse(c));

  const RayTracer tracer(scene);
  const std::vector<AreaLight> area = area_lights(scene);

  // The reference: camera pictures and vertices of a fixed evaluation mesh
  // (the scene refined on a grid), so every row is measured at the same points.
  ReferenceSettings rs;
  rs.samples = opt.reference_samples;
  const ReferencePathTracer pt(tracer, rs);
  auto t = Clock::now();
  bool images_cached = false, points_cached = false;
  const ReferenceImages ref =
      cached_reference_images(pt, opt.width, opt.height, cache, &progress, &images_cached);
  const std::vector<std::uint8_t> mask = mask_from_coverage(ref.coverage);
  LitMesh eval_mesh =
      build_transfer_mesh(scene, TransferGrid::from(VoxelGrid(scene.bounds(), opt.eval_grid)),
                          TransferSettings{}, &progress);
  // Each vertex is measured where the final gather gathers for it, a hair
  // (5% of the way to its face's centre) inside a face that uses it, not on
  // the vertex itself: a vertex lies on the edges where its face meets its
  // neighbours, and a path that starts exactly in a neighbouring wall's plane
  // can slip through that wall and bring back light from behind it. Inside the face
  // the light is that of the face, which is what the lit mesh shows there.
  const std::vector<glm::vec3> measured_at =
      gather_points_of_vertices(eval_mesh.positions, eval_mesh.triangles);
  std::vector<ReferencePoint> points;
  for (std::size_t v = 0; v < eval_mesh.positions.size(); ++v)
    points.push_back({measured_at[v], eval_mesh.normals[v], glm::vec3(0.0f), glm::vec3(0.0f)});
  // Albedo per vertex from a face that uses it.
  const std::vector<std::uint32_t> vertex_triangle = vertex_source_triangles(eval_mesh);
  for (std::size_t v = 0; v < points.size(); ++v)
    points[v].albedo = scene.flat_albedo_at(vertex_triangle[v], points[v].position);
  const PointReference ref_points =
      cached_reference_points(pt, points, cache, &progress, &points_cached);
  std::vector<glm::vec3> ref_vertex_indirect(points.size()), ref_vertex_variance(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    ref_vertex_indirect[v] = points[v].albedo * ref_points.indirect_irradiance[v];
    ref_vertex_variance[v] = points[v].albedo * points[v].albedo * ref_points.indirect_variance[v];
  }

  ReportData report;
  report.scene_name = scene.name;
  report.scene_path = scene.path;
  report.triangles = scene.triangle_count();
  ReportReference& rr = report.reference;
  rr.samples_per_pixel = ref.samples;
  rr.samples_per_vertex = ref_points.samples;
  rr.width = opt.width;
  rr.height = opt.height;
  rr.vertices = points.size();
  rr.images_from_cache = images_cached;
  rr.vertices_from_cache = points_cached;
  rr.cache = cache ? cache->dir().string() : std::string();
  rr.seconds = since(t);
  rr.noise_floor_full = noise_floor(ref.full, ref.full_variance, mask);
  rr.noise_floor_indirect = noise_floor(ref.indirect, ref.indirect_variance, mask);
  std::optional<ReportProbes> probe_column;
  if (opt.light_probes) {
    if (log) log("light probes: reference at the evaluation points");
    probe_column.emplace(tracer, pt, opt.eval_grid, cache, &progress);
    rr.probe_points = probe_column->points();
  }

  // The pictures' settings, and for the final gather the points it gathers
  // at: the camera's primary hits (with the direct image, the same for every
  // row) and the evaluation vertices, moved off edges into their faces.
  const bool final_gather = opt.transfer == "final-gather";
  CameraImageSettings camera;
  camera.width = opt.width;
  camera.height = opt.height;
  camera.samples_per_side = 2;  // the reference jitters over the pixel too
  std::vector<CameraHit> camera_hits;
  CameraImages direct_images;
  std::vector<glm::vec3> hit_positions, hit_normals, vertex_points, vertex_albedo;
  if (final_gather) {
    direct_images = render_camera_direct(tracer, camera, camera_hits, &progress);
    for (const CameraHit& h : camera_hits) {
      hit_positions.push_back(h.position);
      hit_normals.push_back(h.normal);
    }
    vertex_points = measured_at;
    for (const ReferencePoint& p : points) vertex_albedo.push_back(p.albedo);
  }
  const auto mean_ratio = [](const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                             const std::vector<std::uint8_t>* covered) {
    double sa = 0.0, sb = 0.0;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
      if (covered && !(*covered)[i]) continue;
      sa += a[i].r + a[i].g + a[i].b;
      sb += b[i].r + b[i].g + b[i].b;
    }
    return sb > 0.0 ? sa / sb : 0.0;
  };

  for (const std::string& mode : opt.modes)
    for (int target : opt.patches) {
      BakeSettings bs;
      bs.patches_total = target;
      bs.patch_mode = mode == "virtual" ? PatchMode::Virtual : PatchMode::Voxel;
      bs.codec = CodecChoice::Dense;
      bs.pictures = false;
      bs.seed = opt.seed;
      bs.light_probes = opt.light_probes ? ProbePlacementMode::On : ProbePlacementMode::Off;
      // OpenBLAS: no OpenCL kernel compile inside a timing sweep.
      bs.transport.backend = TransportSettings::Backend::OpenBLAS;
      bs.transport.bounces = bounces.front();
      if (log) log(mode + " patches, target " + std::to_string(target));
      const BakeResult bake = Baker(scene, bs, diag).run(progress);
      double shared = 0.0, transport_first = 0.0, probe_seconds = 0.0;
      for (const StageStats& s : bake.stages) {
        if (s.name == "transport")
          transport_first = s.seconds;
        else if (s.name == "evaluation lights")
          probe_seconds = s.seconds;
        else if (s.name != "compress" && s.name != "light probes")  // probes: off by default
          shared += s.seconds;
      }
      const TransferGrid grid = TransferGrid::from(bake.voxels.grid);
      // The final gather's form factors from the picture's and the
      // vertices' points to this bake's patches.
      FinalGather pixel_gather, vertex_gather;
      if (final_gather) {
        const SurfacePatchLookup lookup(bake.voxels, bake.samples, bake.patch_of_sample);
        FinalGatherSettings fg;
        fg.seed = opt.seed;
        pixel_gather = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                          hit_positions, hit_normals, fg, &progress);
        vertex_gather = build_final_gather(tracer, lookup, bake.patches.patches, bake.voxels.grid,
                                           vertex_points, eval_mesh.normals, fg, &progress);
      }
      // Patch values to errors against the reference: gathered to the
      // camera's pixels and the evaluation mesh's vertices. `indirect` is
      // each patch's T b (the nearest-patches transfer spreads it),
      // `reflected` its b + T b (what a final gather sums), `sample_light`
      // each sample's own b plus its patch's T b (what the gather's sample
      // sources read).
      struct Measured {
        ImageErrors full, indirect;
        VertexErrors vertex;
        double indirect_error = 0.0, vertex_error = 0.0;
        double indirect_level = 0.0, vertex_level = 0.0;
      };
      const auto measure = [&](const std::vector<glm::vec3>& patch_indirect,
                               const std::vector<glm::vec3>& patch_reflected,
                               const std::vector<glm::vec3>& sample_light,
                               const std::vector<glm::vec3>& pixel_near_light,
                               const std::vector<glm::vec3>& vertex_near_light) {
        Measured m;
        CameraImages images;
        std::vector<glm::vec3> vertex_light;
        if (final_gather) {
          images = direct_images;
          std::vector<glm::vec3> e;
          pixel_gather.irradiance(patch_reflected, sample_light, pixel_near_light, e);
          add_indirect(images, camera_hits, e);
          vertex_gather.irradiance(patch_reflected, sample_light, vertex_near_light, vertex_light);
          for (std::size_t v = 0; v < vertex_light.size(); ++v) vertex_light[v] *= vertex_albedo[v];
        } else {
          const PatchGather gather(bake.patches.patches, patch_indirect, grid, &tracer,
                                   GatherSettings{});
          images = render_camera(tracer, gather, camera, &progress);
          LitMesh lit = eval_mesh;
          relight(lit, gather, &progress);
          vertex_light = std::move(lit.radiosity);
        }
        m.full = image_errors(images.full, ref.full, mask);
        m.indirect = image_errors(images.indirect, ref.indirect, mask);
        m.vertex = vertex_errors(vertex_light, ref_vertex_indirect);
        m.indirect_error = noise_corrected_relative_rmse(images.indirect, ref.indirect,
                                                         ref.indirect_variance, mask);
        m.vertex_error =
            noise_corrected_relative_rmse(vertex_light, ref_vertex_indirect, ref_vertex_variance);
        m.indirect_level = mean_ratio(images.indirect.pixels, ref.indirect.pixels, &mask);
        m.vertex_level = mean_ratio(vertex_light, ref_vertex_indirect, nullptr);
        return m;
      };
      // The layout's own error: the same gather of exact patch values.
      if (log) log(mode + " patches, target " + std::to_string(target) + ": exact patch values");
      const ExactPatchLight exact =
          exact_patch_indirect(pt, bake.samples, bake.patches, cache, &progress);
      // The same gather with exact patch values: patch sources read their
      // patch's exact b + T b; sample and near sources, as in every row, their
      // own first-hit light (the same for every row, lit once here) plus
      // their patch's exact T b. So the two errors differ only by T b.
      const PatchLighting direct_once =
          light_patches(tracer, bake.samples, bake.patches, scene.lights, area,
                        [](const std::vector<glm::vec3>& b, std::vector<glm::vec3>& tb) {
                          tb.assign(b.size(), glm::vec3(0.0f));
                        });
      const Measured layout =
          measure(exact.indirect, exact.reflected,
                  sample_exitance(bake.samples, bake.patches, direct_once.sample_irradiance,
                                  exact.indirect),
                  near_exitance(pixel_gather.near, &tracer, scene.lights, area, exact.indirect),
                  near_exitance(vertex_gather.near, &tracer, scene.lights, area, exact.indirect));
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
        for (const ReportCodec& codec : codecs) {
          if (!codec_sweep && codec.name != "dense") continue;
          BakeSettings cs = bake.settings;
          cs.codec = codec.name == "dense"   ? CodecChoice::Dense
                     : codec.name == "paper" ? CodecChoice::LargestEntries
                                             : CodecChoice::LightWeighted;
          cs.kept_fraction = codec.kept_fraction;
          t = Clock::now();
          const MatrixStorage storage = store_transport(transport, bake.probe, cs, &progress, diag);
          const double store_seconds = since(t);
          ReportRow row;
          row.mode = mode;
          row.patches_target = target;
          row.patches = bake.patches.size();
          row.bounces = opt.bounces[bi];
          row.codec_name = codec.name;
          row.kept_fraction = codec.kept_fraction;
          row.seed = opt.seed;
          row.codec = codec.label();
          row.matrix_bytes = storage.stored_bytes;
          row.compression_light_error = storage.errors.indirect.rel_rms_max;
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
          std::vector<glm::vec3> reflected(light.indirect.size());
          for (std::size_t p = 0; p < reflected.size(); ++p)
            reflected[p] = light.first_hit[p] + light.indirect[p];
          const std::vector<glm::vec3> sample_light =
              sample_exitance(bake.samples, bake.patches, light.sample_irradiance, light.indirect);
          const Measured m = measure(
              light.indirect, reflected, sample_light,
              near_exitance(pixel_gather.near, &tracer, scene.lights, area, light.indirect),
              near_exitance(vertex_gather.near, &tracer, scene.lights, area, light.indirect));
          if (probe_column) {
            const ProbeReferenceError pe = probe_column->measure(bake, reflected, sample_light);
            row.probe_error = pe.noise_corrected_rmse;
            row.probe_level = pe.level;
            row.probes = bake.light_probes.size();
          }
          row.full = m.full;
          row.indirect = m.indirect;
          row.vertex = m.vertex;
          row.indirect_error = m.indirect_error;
          row.vertex_error = m.vertex_error;
          row.layout_indirect_error = layout.indirect_error;
          row.layout_vertex_error = layout.vertex_error;
          row.transfer = final_gather ? "final gather" : "nearest patches";
          row.indirect_level = m.indirect_level;
          row.vertex_level = m.vertex_level;
          row.layout_indirect_level = layout.indirect_level;
          row.layout_vertex_level = layout.vertex_level;
          report.rows.push_back(row);
        }
      }
    }
  mark_pareto(report.rows);
  report.seconds = since(start);
  return report;
}

}  // namespace bounce
