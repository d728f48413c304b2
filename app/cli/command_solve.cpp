// `bounce solve BAKE`: one frame of the runtime on a baked scene, written out
// for people to look at: the light on the patches (direct, first hit,
// indirect), the lit mesh as a PLY and a binary glTF (lit.glb, for Blender and web viewers) with
// vertex colours, and the scene camera's pictures (direct, indirect, full) as PNG and EXR. The
// frame on the patches runs through the runtime's frame graph (runtime/runtime_frame.h). With
// --compare-exact, the same frame through the exact matrix too, and what the compression changes:
// per patch, per vertex (in the PLY) and per pixel of the camera's indirect picture (an error
// picture).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>

#include "bounce/bake_folder.h"
#include "bounce/export.h"
#include "bounce/metrics.h"
#include "bounce/relight.h"
#include "bounce/scene.h"
#include "commands.h"
#include "console_progress.h"
#include "lit_bake_mesh.h"

namespace bounce::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The bake folder's own name ("bakes/sponza/" -> "sponza"): what a viewer
// lists the exported mesh as.
std::string bake_display_name(const std::string& folder) {
  fs::path p = fs::path(folder).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  const std::string name = p.filename().string();
  return name.empty() || name == "." ? "lit" : name;
}

struct SolveOptions {
  std::string bake;
  std::string scene;  // empty: the manifest's scene path
  std::vector<std::string> lights;
  std::string out;
  std::string multiply = "auto";
  int width = 640, height = 480, samples = 1;
  int camera_gather_rays = 256;  // 0: the nearest patches' light
  bool no_images = false, no_mesh = false;
  bool json = false, quiet = false;
  bool float32 = false;  // the C++ product in float32 instead of the measured choice of loop
  bool compare_exact = false;
};

// The error picture's colour map runs from 0 to this relative error.
constexpr double kErrorPictureFullScale = 0.1;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// "NAME:x,y,z" moves the scene light NAME to (x, y, z).
void move_light(Scene& scene, const std::string& spec) {
  const auto colon = spec.rfind(':');
  const std::string name = colon == std::string::npos ? "" : spec.substr(0, colon);
  glm::vec3 p{0.0f};
  char tail = 0;
  const std::string coords = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (name.empty() || std::sscanf(coords.c_str(), "%f,%f,%f%c", &p.x, &p.y, &p.z, &tail) != 3 ||
      !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw Error("--light", "expected NAME:x,y,z (e.g. ceiling-point:0,1.5,0), got '" + spec + "'");
  std::string names;
  for (Light& l : scene.lights) {
    if (l.name == name) {
      if (l.type == Light::Type::Directional)
        throw Error("--light", "'" + name + "' is a directional light: it has no position");
      l.position = p;
      return;
    }
    names += (names.empty() ? "" : ", ") + l.name;
  }
  throw Error("--light", "the scene has no light named '" + name +
                             "' (its lights: " + (names.empty() ? "none" : names) + ")");
}

void run_solve(const SolveOptions& opt) {
  const auto start = Clock::now();
  Diagnostics diag;
  diag.set_listener([](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(), d.message.c_str());
  });
  if (opt.width < 1 || opt.width > 16384 || opt.height < 1 || opt.height > 16384)
    throw Error("--size", "width and height must be between 1 and 16384");
  if (opt.samples < 1 || opt.samples > 16)
    throw Error("--samples", "must be between 1 and 16 (n x n rays per pixel)");
  if (opt.camera_gather_rays < 0 || opt.camera_gather_rays > 65536)
    throw Error("--camera-gather-rays",
                "must be between 0 and 65536, got " + std::to_string(opt.camera_gather_rays));
  nlohmann::ordered_json timings;
  auto t = Clock::now();
  // auto multiplies a dense bake (T.npy, no T.dds) with its dense matrix, so
  // T.npy is read then; a compressed bake's T.npy (--dump-matrices) is only
  // read when --multiply dense asks for it: it can be large.
  if (opt.compare_exact && opt.multiply == "dense")
    throw Error("--compare-exact",
                "compares the compressed product with the exact one; --multiply dense would "
                "compare the exact one with itself");
  const BakeReader::Dense dense = opt.multiply == "dense" || opt.compare_exact
                                      ? BakeReader::Dense::kRead
                                  : opt.multiply == "auto" ? BakeReader::Dense::kIfNotCompressed
                                                           : BakeReader::Dense::kSkip;
  const LoadedBake bake = BakeReader::read(opt.bake, dense);
  if (opt.compare_exact && !bake.compressed)
    throw Error(opt.bake,
                "stores the exact matrix (dense): --compare-exact has no compression "
                "error to show");
  if (opt.compare_exact && bake.dense.empty())
    throw Error(opt.bake, "holds no exact T.npy for --compare-exact (bake with --dump-matrices)");
  timings["read_bake"] = since(t);

  t = Clock::now();
  const fs::path scene_path =
      opt.scene.empty() ? fs::path(bake.manifest.at("scene").at("path").get<std::string>())
                        : fs::path(opt.scene);
  if (!fs::exists(scene_path))
    throw Error(scene_path.string(),
                "the baked scene is not there any more (give it with --scene PATH)");
  Scene scene = SceneLoader(diag).load(scene_path);
  const auto baked_triangles = bake.manifest.at("scene").at("triangles").get<std::size_t>();
  if (scene.triangle_count() != baked_triangles)
    throw Error(scene_path.string(), "has " + std::to_string(scene.triangle_count()) +
                                         " triangles, the bake was made from " +
                                         std::to_string(baked_triangles) + ": not the same scene");
  for (const std::string& spec : opt.lights) move_light(scene, spec);
  const RayTracer tracer(scene);
  timings["load_scene"] = since(t);

  const std::vector<AreaLight> area = area_lights(scene);
  // b and T b are read from the record after the frame (it is written out
  // anyway), so the frame keeps no published copies of them: its only
  // persistent buffers are the record and the exitance. --float32 opts out
  // of the measured choice of the C++ loop.
  RelighterSettings relight;
  relight.multiply = multiply_choice_from_name(opt.multiply).value_or(MultiplyChoice::kAuto);
  relight.loop = opt.float32 ? CppLoop::kFloat32 : CppLoop::kMeasured;
  relight.frame.publish = false;
  Relighter relighter(tracer, bake.samples, bake.patches, stored_transport(bake), relight, &diag);
  timings["prepare_multiply"] = relighter.multiply_seconds();
  timings["compile_frame_graph"] = relighter.compile_seconds();
  relighter.light(scene.lights, area);
  const RuntimeFrame& frame = relighter.frame();
  // The bake's final gather, when it made one.
  const std::optional<FinalGather> gather =
      read_final_gather(opt.bake, bake.size(), bake.samples.samples.size());
  // Pass times, grouped as before the graph: direct light + first hit (and
  // recording them), then the product (applying it and recording it).
  double seconds_direct = 0.0, seconds_indirect = 0.0;
  json passes = json::array();
  bool after_product = false;
  for (std::size_t i = 0; i < frame.graph().passes().size(); ++i) {
    const std::string& name = frame.graph().passes()[i].name;
    after_product = after_product || name == "indirect product";
    (after_product ? seconds_indirect : seconds_direct) += frame.pass_seconds()[i];
    passes.push_back({{"name", name}, {"seconds", frame.pass_seconds()[i]}});
  }
  timings["direct_light"] = seconds_direct;
  timings["indirect_multiply"] = seconds_indirect;

  const fs::path out = opt.out.empty() ? fs::path(opt.bake) / "solve" : fs::path(opt.out);
  fs::create_directories(out);
  t = Clock::now();
  const std::size_t n = bake.size();
  // The graph recorded E, b and T b per patch in this layout.
  write_npy(out / "patch_light.npy", frame.record(), {n, 3, 3});
  const auto recorded = [&frame](std::size_t p, std::size_t slot) {
    const float* r = frame.record().data() + 9 * p + 3 * slot;
    return glm::vec3(r[0], r[1], r[2]);
  };
  json files = json::array({"patch_light.npy"});

  // The exact product of the same first-hit light, for --compare-exact.
  std::vector<glm::vec3> first_hit(n), indirect(n), exact_indirect;
  for (std::size_t p = 0; p < n; ++p) {
    first_hit[p] = recorded(p, 1);
    indirect[p] = recorded(p, 2);
  }
  nlohmann::ordered_json comparison;
  if (opt.compare_exact) {
    std::vector<const float*> exact_matrices;
    for (const auto& m : bake.dense) exact_matrices.push_back(m.data());
    exact_indirect.resize(n);
    dense_indirect(exact_matrices, n, bake.channel_of_rgb, first_hit, exact_indirect);
    std::vector<float> patch_area;
    for (const Patch& p : bake.patches.patches) patch_area.push_back(p.area);
    comparison["patch_indirect_rel_rms"] =
        area_weighted_relative_rms(patch_area, indirect, exact_indirect);
  }

  const TransferGrid grid = TransferGrid::from_manifest(bake.manifest);
  ConsoleProgress console(opt.quiet || opt.json);
  if (!opt.no_mesh) {
    double product = 0.0, near = 0.0;
    const LitMesh mesh =
        light_bake_mesh(tracer, bake, opt.bake, relighter, area, gather, console.progress(),
                        gather ? &product : nullptr, gather ? &near : nullptr);
    if (gather) {
      timings["final_gather_product"] = product;
      timings["final_gather_near_sources"] = near;
    }
    std::vector<float> error_abs, error_rel;
    std::vector<PlyScalar> scalars;
    if (opt.compare_exact) {
      // The same mesh lit through the exact matrix.
      LitMesh exact_mesh = mesh;
      std::vector<glm::vec3> reflected(n);
      for (std::size_t p = 0; p < n; ++p) reflected[p] = first_hit[p] + exact_indirect[p];
      if (gather) {
        std::vector<glm::vec3> gathered, sample_light;
        if (gather->samples > 0)
          sample_light = sample_exitance(bake.samples, bake.patches, frame.sample_irradiance(),
                                         exact_indirect);
        gather->irradiance(reflected, sample_light,
                           near_exitance(gather->near, &tracer, scene.lights, area, exact_indirect),
                           gathered);
        light_vertices(tracer, scene.lights, area, gathered, exact_mesh);
      } else {
        std::vector<glm::vec3> exitance(n);
        for (std::size_t p = 0; p < n; ++p)
          exitance[p] = bake.patches.patches[p].emission + reflected[p];
        exact_mesh = transfer_to_mesh(tracer, bake.patches.patches, grid, exitance,
                                      TransferSettings{}, &console.progress());
      }
      error_rel = vertex_relative_errors(mesh.radiosity, exact_mesh.radiosity);
      for (std::size_t v = 0; v < mesh.radiosity.size(); ++v)
        error_abs.push_back(glm::length(mesh.radiosity[v] - exact_mesh.radiosity[v]));
      scalars = {{"error_abs", &error_abs}, {"error_rel", &error_rel}};
      const VertexErrors ve = vertex_errors(mesh.radiosity, exact_mesh.radiosity);
      comparison["vertices"] = ve.vertices;
      comparison["vertex_rel_rms"] = ve.relative_rmse;
      comparison["vertex_mean_relative"] = ve.mean_relative;
      comparison["vertex_max_relative"] = ve.max_relative;
    }
    write_lit_ply(out / "lit.ply", {mesh.positions, mesh.normals, mesh.radiosity, mesh.triangles},
                  scalars);
    files.push_back("lit.ply");
    // The same light for Blender and web viewers, without the error columns.
    write_lit_scene_glb(out / "lit.glb", scene, mesh, bake_display_name(opt.bake));
    files.push_back("lit.glb");
    timings["mesh_transfer"] = since(t);
  }
  std::string camera_transfer = "none";
  if (!opt.no_images) {
    t = Clock::now();
    CameraImageSettings cs;
    cs.width = opt.width;
    cs.height = opt.height;
    cs.samples_per_side = opt.samples;
    // Each pixel gathers from the patches it sees (as the bake's vertices
    // do), when the bake says which triangle its surface lies on; otherwise
    // the camera blends the nearest patches' T b.
    std::optional<CameraGather> pixels;
    if (opt.camera_gather_rays > 0 && camera_gather_possible(bake))
      pixels.emplace(tracer, bake, cs, opt.camera_gather_rays, &console.progress());
    camera_transfer = pixels ? "final gather" : "nearest patches";
    const auto render = [&](const std::vector<glm::vec3>& patch_indirect) {
      if (pixels)
        return pixels->images(first_hit, patch_indirect, frame.sample_irradiance(), scene.lights,
                              area);
      const PatchGather nearest(bake.patches.patches, patch_indirect, grid, &tracer,
                                GatherSettings{});
      return render_camera(tracer, nearest, cs, &console.progress());
    };
    const CameraImages images = render(indirect);
    write_camera_images(images, out, "camera");
    for (const char* part : {"direct", "indirect", "full"})
      for (const char* ext : {".png", ".exr"}) files.push_back(std::string("camera_") + part + ext);
    if (opt.compare_exact) {
      const CameraImages exact = render(exact_indirect);
      write_exr(out / "camera_indirect_error.exr",
                absolute_difference(images.indirect, exact.indirect));
      write_png(out / "camera_indirect_error.png",
                relative_error_heat_map(images.indirect, exact.indirect, images.coverage,
                                        kErrorPictureFullScale));
      files.push_back("camera_indirect_error.exr");
      files.push_back("camera_indirect_error.png");
      const ImageErrors ie =
          image_errors(images.indirect, exact.indirect, mask_from_coverage(images.coverage));
      comparison["image_indirect_rel_rms"] = ie.relative_rmse;
      comparison["image_pixels"] = ie.pixels;
      comparison["error_picture_full_scale"] = kErrorPictureFullScale;
    }
    timings["camera_images"] = since(t);
  }
  timings["total"] = since(start);

  json lights = json::array();
  for (const Light& l : scene.lights)
    lights.push_back({{"name", l.name},
                      {"type", light_type_name(l.type)},
                      {"position", {l.position.x, l.position.y, l.position.z}}});
  double direct_sum = 0.0, indirect_sum = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const float a = bake.patches.patches[p].area;
    const glm::vec3 b = recorded(p, 1), tb = recorded(p, 2);
    direct_sum += a * (b.r + b.g + b.b);
    indirect_sum += a * (tb.r + tb.g + tb.b);
  }
  const nlohmann::ordered_json summary = {
      {"bake", opt.bake},
      {"scene", scene.name},
      {"patches", n},
      {"multiply", relighter.multiply_name()},
      {"transfer", gather ? "final gather" : "nearest patches"},
      {"camera_transfer", camera_transfer},
      {"lights", lights},
      {"area_light_triangles", area.size()},
      {"first_hit_power", direct_sum},
      {"indirect_power", indirect_sum},
      {"out", out.string()},
      {"files", files},
      {"compare_exact", comparison.empty() ? nlohmann::ordered_json() : comparison},
      {"frame_graph",
       {{"passes", passes},
        {"transient_bytes", frame.transient_bytes()},
        {"unaliased_transient_bytes", frame.unaliased_transient_bytes()},
        {"imported_bytes", frame.imported_bytes()}}},
      {"seconds", timings}};
  if (opt.json) {
    std::cout << summary.dump(2) << '\n';
    return;
  }
  std::printf("\nSolve of '%s' (%zu patches) with %s\n", scene.name.c_str(), n,
              relighter.multiply_name().c_str());
  std::printf(
      "  light leaving the patches (area-weighted sum over R, G, B): first hit %.4g, "
      "indirect %.4g (%.1f%% of the first hit)\n",
      direct_sum, indirect_sum, direct_sum > 0 ? 100.0 * indirect_sum / direct_sum : 0.0);
  std::printf(
      "  frame graph: %zu passes, transient memory %zu bytes aliased (%zu unaliased), "
      "%zu bytes of persistent per-patch buffers\n",
      frame.graph().passes().size(), frame.transient_bytes(), frame.unaliased_transient_bytes(),
      frame.imported_bytes());
  if (!comparison.empty()) {
    std::printf(
        "  compressed against the exact matrix: indirect light relative RMS %.4g per "
        "patch (area-weighted)",
        comparison["patch_indirect_rel_rms"].get<double>());
    if (comparison.contains("vertex_rel_rms"))
      std::printf(", %.4g per vertex (max relative %.4g)",
                  comparison["vertex_rel_rms"].get<double>(),
                  comparison["vertex_max_relative"].get<double>());
    if (comparison.contains("image_indirect_rel_rms")) {
      // JSON keeps an infinite ratio as null: the exact picture is black.
      const auto& image = comparison["image_indirect_rel_rms"];
      if (image.is_number() && std::isfinite(image.get<double>()))
        std::printf(", %.4g over the camera's indirect picture", image.get<double>());
      else
        std::printf(", none over the camera's indirect picture (black through the exact matrix)");
    }
    std::printf("\n");
  }
  std::printf("  %-22s %10s\n", "step", "time (ms)");
  for (const auto& [k, v] : timings.items())
    std::printf("  %-22s %10.2f\n", k.c_str(), 1e3 * v.get<double>());
  std::printf("  written to %s:", out.string().c_str());
  for (const json& f : files) std::printf(" %s", f.get<std::string>().c_str());
  std::printf("\n");
}

}  // namespace

void register_solve(CLI::App& app) {
  auto opt = std::make_shared<SolveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Light a baked scene: direct light on the patches from the scene's lights (moved with "
      "--light), indirect light through the baked matrix, the lit mesh as a PLY and a binary "
      "glTF (lit.glb, for Blender and web viewers) with vertex colours and the scene camera's "
      "pictures (direct, indirect, full) as PNG and EXR");
  cmd->add_option("bake", opt->bake, "Bake folder written by `bounce bake`")->required();
  cmd->add_option("--light", opt->lights,
                  "Move a scene light: NAME:x,y,z (repeat for several lights; `bounce info "
                  "SCENE` lists their names)");
  cmd->add_option("--scene", opt->scene,
                  "The scene the bake was made from, if it moved (default: the path in the "
                  "bake's manifest)");
  cmd->add_option("--out,-o", opt->out, "Output folder (default: BAKE/solve)");
  cmd->add_option("--multiply", opt->multiply,
                  "How T b is computed: auto (compressed: OpenCL on a GPU, else C++; dense for a "
                  "dense bake), opencl, cpp (compressed, C++), dense (needs T.npy)")
      ->check(CLI::IsMember({"auto", "opencl", "cpp", "dense"}))
      ->capture_default_str();
  cmd->add_option("--width", opt->width, "Camera image width in pixels")->capture_default_str();
  cmd->add_option("--height", opt->height, "Camera image height in pixels")->capture_default_str();
  cmd->add_option("--samples", opt->samples, "n x n camera rays per pixel (anti-aliasing)")
      ->capture_default_str();
  cmd->add_option("--camera-gather-rays", opt->camera_gather_rays,
                  "Rays per camera pixel gathering its indirect light from the patches it "
                  "sees, as the bake's vertices do (sharp where patches are coarse: the foot of a "
                  "sunlit pillar, the dark under an arch). 0: blend the nearest patches' light "
                  "instead (faster, blurred over a voxel; also what bakes made before folders "
                  "kept their surface triangles get)")
      ->capture_default_str();
  cmd->add_flag("--float32", opt->float32,
                "Compressed C++ product in float32 (default: bfloat16 products with float32 "
                "sums where the CPU has AVX-512 BF16 and a short measurement at load finds "
                "them faster, ~1e-3 of the largest entry off float32)");
  cmd->add_flag("--compare-exact", opt->compare_exact,
                "Also light the frame through the exact matrix (T.npy: bake with "
                "--dump-matrices) and write what compression changes: per-vertex error_abs "
                "(|L~ - L|, RGB) and error_rel (relative, largest channel) in lit.ply, "
                "camera_indirect_error.exr (|I~ - I|) and .png (relative error of the indirect "
                "picture, colour map 0..10%), and the figures in the summary");
  cmd->add_flag("--no-images", opt->no_images, "Skip the camera pictures");
  cmd->add_flag("--no-mesh", opt->no_mesh, "Skip the lit mesh (lit.ply and lit.glb)");
  cmd->add_flag("--json", opt->json, "Print a machine-readable summary with timings per step");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress bars");
  cmd->callback([opt]() { run_solve(*opt); });
}

}  // namespace bounce::cli
