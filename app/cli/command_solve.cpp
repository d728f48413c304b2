// `bounce solve BAKE`: one frame of the runtime on a baked scene, written out
// for people to look at: the light on the patches (direct, first hit,
// indirect), the lit mesh as a PLY and a binary glTF (lit.glb, for Blender and web viewers) with
// vertex colours, and the scene camera's pictures (direct, indirect, full) as PNG and EXR. The
// frame on the patches runs through the runtime's frame graph (runtime/runtime_frame.h). With
// --compare-exact, the same frame through the exact matrix too, and what the compression changes:
// per patch, per vertex (in the PLY) and per pixel of the camera's indirect picture (an error
// picture).
#include <algorithm>
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
#include "flag_spelling.h"

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

// "NAME:x,y,z": the light NAME and where it moves to.
std::pair<std::string, glm::vec3> parse_light_move(const std::string& spec) {
  const auto colon = spec.rfind(':');
  const std::string name = colon == std::string::npos ? "" : spec.substr(0, colon);
  glm::vec3 p{0.0f};
  char tail = 0;
  const std::string coords = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (name.empty() || std::sscanf(coords.c_str(), "%f,%f,%f%c", &p.x, &p.y, &p.z, &tail) != 3 ||
      !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw Error("--light", "expected NAME:x,y,z (e.g. ceiling-point:0,1.5,0), got '" + spec + "'");
  return {name, p};
}

void check_options(const SolveOptions& opt) {
  if (opt.width < 1 || opt.width > 16384 || opt.height < 1 || opt.height > 16384)
    throw Error("--size", "width and height must be between 1 and 16384");
  if (opt.samples < 1 || opt.samples > 16)
    throw Error("--samples", "must be between 1 and 16 (n x n rays per pixel)");
  if (opt.camera_gather_rays < 0 || opt.camera_gather_rays > 65536)
    throw Error("--camera-gather-rays",
                "must be between 0 and 65536, got " + std::to_string(opt.camera_gather_rays));
  if (opt.compare_exact && opt.multiply == "dense")
    throw Error("--compare-exact",
                "compares the compressed product with the exact one; --multiply dense would "
                "compare the exact one with itself");
}

LightingSessionSettings session_settings(const SolveOptions& opt) {
  LightingSessionSettings s;
  s.scene = opt.scene;
  // auto multiplies a dense bake (T.npy, no T.dds) with its dense matrix, so
  // T.npy is read then; a compressed bake's T.npy (--dump-matrices) is only
  // read when --multiply dense asks for it: it can be large.
  s.dense = opt.multiply == "dense" || opt.compare_exact ? BakeReader::Dense::kRead
            : opt.multiply == "auto"                     ? BakeReader::Dense::kIfNotCompressed
                                                         : BakeReader::Dense::kSkip;
  // b and T b are read from the record after the frame (it is written out
  // anyway), so the frame keeps no published copies of them. --float32 opts
  // out of the measured choice of the C++ loop.
  s.relighter.multiply = multiply_choice_from_name(opt.multiply).value_or(MultiplyChoice::kAuto);
  s.relighter.loop = opt.float32 ? CppLoop::kFloat32 : CppLoop::kMeasured;
  s.relighter.frame.publish = false;
  return s;
}

// A bake folder that cannot answer --compare-exact.
void check_compare_exact(const SolveOptions& opt, const LoadedBake& bake) {
  if (!opt.compare_exact) return;
  if (!bake.compressed)
    throw Error(opt.bake,
                "stores the exact matrix (dense): --compare-exact has no compression "
                "error to show");
  if (bake.dense.empty())
    throw Error(opt.bake, "holds no exact T.npy for --compare-exact (bake with --dump-matrices)");
}

// What `bounce solve` measures and writes, gathered for its summary.
struct SolveRecord {
  nlohmann::ordered_json timings;
  json passes = json::array();
  json files = json::array();
  nlohmann::ordered_json comparison;
  std::string camera_transfer = "none";
};

// Pass times, grouped: direct light + first hit (and recording them), then
// the product (applying it and recording it).
void record_passes(const RuntimeFrame& frame, SolveRecord& r) {
  double seconds_direct = 0.0, seconds_indirect = 0.0;
  bool after_product = false;
  for (std::size_t i = 0; i < frame.graph().passes().size(); ++i) {
    const std::string& name = frame.graph().passes()[i].name;
    after_product = after_product || name == "indirect product";
    (after_product ? seconds_indirect : seconds_direct) += frame.pass_seconds()[i];
    r.passes.push_back({{"name", name}, {"seconds", frame.pass_seconds()[i]}});
  }
  r.timings["direct_light"] = seconds_direct;
  r.timings["indirect_multiply"] = seconds_indirect;
}

// The product of the frame's first hit through the exact matrix.
std::vector<glm::vec3> exact_indirect(const LightingSession& session) {
  const LoadedBake& bake = session.bake();
  std::vector<glm::vec3> first_hit, indirect, exact(bake.size());
  session.relighter().first_hit_and_indirect(first_hit, indirect);
  std::vector<const float*> matrices;
  for (const auto& m : bake.dense) matrices.push_back(m.data());
  dense_indirect(matrices, bake.size(), bake.channel_of_rgb, first_hit, exact);
  return exact;
}

// The final gather's per-frame cost: the product alone, best of five, and
// the lighting of its near sources in the first gather, which traces every
// shadow ray (later gathers of the same lights keep their visibility).
void time_final_gather(const LightingSession& session, SolveRecord& r) {
  double best_product = 1e30, first_near = 0.0;
  std::vector<glm::vec3> gathered;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = Clock::now();
    session.relighter().gather(*session.final_gather(), gathered);
    const double near = session.relighter().near_seconds();
    best_product = std::min(best_product, since(t0) - near);
    if (rep == 0) first_near = near;
  }
  r.timings["final_gather_product"] = best_product;
  r.timings["final_gather_near_sources"] = first_near;
}

void write_mesh(const SolveOptions& opt, LightingSession& session,
                const std::vector<glm::vec3>* exact, Progress& progress, const fs::path& out,
                SolveRecord& r) {
  const auto t = Clock::now();
  if (session.final_gather()) time_final_gather(session, r);
  const LitMesh mesh = session.lit_mesh(&progress);
  std::vector<float> error_abs, error_rel;
  std::vector<PlyScalar> scalars;
  if (exact != nullptr) {
    // The same mesh lit through the exact matrix.
    const LitMesh exact_mesh = session.lit_mesh(*exact, &progress);
    error_rel = vertex_relative_errors(mesh.radiosity, exact_mesh.radiosity);
    for (std::size_t v = 0; v < mesh.radiosity.size(); ++v)
      error_abs.push_back(glm::length(mesh.radiosity[v] - exact_mesh.radiosity[v]));
    scalars = {{"error_abs", &error_abs}, {"error_rel", &error_rel}};
    const VertexErrors ve = vertex_errors(mesh.radiosity, exact_mesh.radiosity);
    r.comparison["vertices"] = ve.vertices;
    r.comparison["vertex_rel_rms"] = ve.relative_rmse;
    r.comparison["vertex_mean_relative"] = ve.mean_relative;
    r.comparison["vertex_max_relative"] = ve.max_relative;
  }
  write_lit_ply(out / "lit.ply", {mesh.positions, mesh.normals, mesh.radiosity, mesh.triangles},
                scalars);
  r.files.push_back("lit.ply");
  // The same light for Blender and web viewers, without the error columns.
  write_lit_scene_glb(out / "lit.glb", session.scene(), mesh, bake_display_name(opt.bake));
  r.files.push_back("lit.glb");
  r.timings["mesh_transfer"] = since(t);
}

void write_camera(const SolveOptions& opt, const LightingSession& session,
                  const std::vector<glm::vec3>* exact, Progress& progress, const fs::path& out,
                  SolveRecord& r) {
  const auto t = Clock::now();
  CameraImageSettings cs;
  cs.width = opt.width;
  cs.height = opt.height;
  cs.samples_per_side = opt.samples;
  const SessionCamera camera = session.camera(cs, opt.camera_gather_rays, &progress);
  r.camera_transfer = camera.transfer_name();
  const CameraImages images = camera.images();
  write_camera_images(images, out, "camera");
  for (const char* part : {"direct", "indirect", "full"})
    for (const char* ext : {".png", ".exr"}) r.files.push_back(std::string("camera_") + part + ext);
  if (exact != nullptr) {
    const CameraImages exact_images = camera.images(*exact);
    write_exr(out / "camera_indirect_error.exr",
              absolute_difference(images.indirect, exact_images.indirect));
    write_png(out / "camera_indirect_error.png",
              relative_error_heat_map(images.indirect, exact_images.indirect, images.coverage,
                                      kErrorPictureFullScale));
    r.files.push_back("camera_indirect_error.exr");
    r.files.push_back("camera_indirect_error.png");
    const ImageErrors ie =
        image_errors(images.indirect, exact_images.indirect, mask_from_coverage(images.coverage));
    r.comparison["image_indirect_rel_rms"] = ie.relative_rmse;
    r.comparison["image_pixels"] = ie.pixels;
    r.comparison["error_picture_full_scale"] = kErrorPictureFullScale;
  }
  r.timings["camera_images"] = since(t);
}

// The area-weighted light leaving the patches, summed over R, G, B: first
// hit and indirect.
std::pair<double, double> patch_power(const LightingSession& session) {
  std::vector<glm::vec3> first_hit, indirect;
  session.relighter().first_hit_and_indirect(first_hit, indirect);
  double direct_sum = 0.0, indirect_sum = 0.0;
  for (std::size_t p = 0; p < first_hit.size(); ++p) {
    const float a = session.bake().patches.patches[p].area;
    const glm::vec3 b = first_hit[p], tb = indirect[p];
    direct_sum += a * (b.r + b.g + b.b);
    indirect_sum += a * (tb.r + tb.g + tb.b);
  }
  return {direct_sum, indirect_sum};
}

nlohmann::ordered_json solve_summary(const SolveOptions& opt, const LightingSession& session,
                                     const fs::path& out, const SolveRecord& r) {
  json lights = json::array();
  for (const Light& l : session.lights())
    lights.push_back({{"name", l.name},
                      {"type", light_type_name(l.type)},
                      {"position", {l.position.x, l.position.y, l.position.z}}});
  const auto [direct_sum, indirect_sum] = patch_power(session);
  const RuntimeFrame& frame = session.frame();
  return {{"bake", opt.bake},
          {"scene", session.scene().name},
          {"patches", session.bake().size()},
          {"multiply", session.relighter().multiply_name()},
          {"transfer", session.transfer_name()},
          {"camera_transfer", r.camera_transfer},
          {"lights", lights},
          {"area_light_triangles", session.area_lights().size()},
          {"first_hit_power", direct_sum},
          {"indirect_power", indirect_sum},
          {"out", out.string()},
          {"files", r.files},
          {"compare_exact", r.comparison.empty() ? nlohmann::ordered_json() : r.comparison},
          {"frame_graph",
           {{"passes", r.passes},
            {"transient_bytes", frame.transient_bytes()},
            {"unaliased_transient_bytes", frame.unaliased_transient_bytes()},
            {"imported_bytes", frame.imported_bytes()}}},
          {"seconds", r.timings}};
}

void print_comparison(const nlohmann::ordered_json& comparison) {
  std::printf(
      "  compressed against the exact matrix: indirect light relative RMS %.4g per "
      "patch (area-weighted)",
      comparison["patch_indirect_rel_rms"].get<double>());
  if (comparison.contains("vertex_rel_rms"))
    std::printf(", %.4g per vertex (max relative %.4g)", comparison["vertex_rel_rms"].get<double>(),
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

void print_summary(const nlohmann::ordered_json& summary) {
  const double direct_sum = summary["first_hit_power"].get<double>();
  const double indirect_sum = summary["indirect_power"].get<double>();
  std::printf("\nSolve of '%s' (%zu patches) with %s\n",
              summary["scene"].get<std::string>().c_str(), summary["patches"].get<std::size_t>(),
              summary["multiply"].get<std::string>().c_str());
  std::printf(
      "  light leaving the patches (area-weighted sum over R, G, B): first hit %.4g, "
      "indirect %.4g (%.1f%% of the first hit)\n",
      direct_sum, indirect_sum, direct_sum > 0 ? 100.0 * indirect_sum / direct_sum : 0.0);
  const auto& graph = summary["frame_graph"];
  std::printf(
      "  frame graph: %zu passes, transient memory %zu bytes aliased (%zu unaliased), "
      "%zu bytes of persistent per-patch buffers\n",
      graph["passes"].size(), graph["transient_bytes"].get<std::size_t>(),
      graph["unaliased_transient_bytes"].get<std::size_t>(),
      graph["imported_bytes"].get<std::size_t>());
  if (!summary["compare_exact"].is_null()) print_comparison(summary["compare_exact"]);
  std::printf("  %-22s %10s\n", "step", "time (ms)");
  for (const auto& [k, v] : summary["seconds"].items())
    std::printf("  %-22s %10.2f\n", k.c_str(), 1e3 * v.get<double>());
  std::printf("  written to %s:", summary["out"].get<std::string>().c_str());
  for (const auto& f : summary["files"]) std::printf(" %s", f.get<std::string>().c_str());
  std::printf("\n");
}

void run_solve(const SolveOptions& opt) {
  const auto start = Clock::now();
  check_options(opt);
  Diagnostics diag;
  diag.set_listener([](const Diagnostic& d) {
    if (d.kind == Diagnostic::Kind::Warning)
      std::fprintf(stderr, "bounce: warning: %s: %s\n", d.where.c_str(),
                   with_flag_spellings(d.message).c_str());
  });
  SolveRecord r;
  auto t = Clock::now();
  LightingSession session(opt.bake, session_settings(opt), &diag);
  check_compare_exact(opt, session.bake());
  r.timings["open"] = since(t);
  r.timings["prepare_multiply"] = session.relighter().multiply_seconds();
  r.timings["compile_frame_graph"] = session.relighter().compile_seconds();
  for (const std::string& spec : opt.lights) {
    const auto [name, position] = parse_light_move(spec);
    try {
      session.move_light(name, position);
    } catch (const Error& e) {
      // The core names the setting; here it is the flag.
      throw Error("--light", std::string(e.what()).substr(e.where().size() + 2));
    }
  }
  session.light();
  record_passes(session.frame(), r);

  const fs::path out = opt.out.empty() ? fs::path(opt.bake) / "solve" : fs::path(opt.out);
  fs::create_directories(out);
  const std::size_t n = session.bake().size();
  // The graph recorded E, b and T b per patch in this layout.
  write_npy(out / "patch_light.npy", session.frame().record(), {n, 3, 3});
  r.files.push_back("patch_light.npy");
  if (session.light_probes()) {
    // The probes' irradiance SH of this light setting, for an engine's own
    // moving objects (docs/bake-format.md, "Light probes").
    std::vector<glm::vec3> sh;
    session.probe_sh(sh);
    write_npy(out / "probe_sh.npy",
              std::span<const float>(reinterpret_cast<const float*>(sh.data()), 3 * sh.size()),
              {sh.size() / kShCoefficients, kShCoefficients, 3});
    r.files.push_back("probe_sh.npy");
  }

  std::optional<std::vector<glm::vec3>> exact;
  if (opt.compare_exact) {
    exact = exact_indirect(session);
    std::vector<glm::vec3> first_hit, indirect;
    session.relighter().first_hit_and_indirect(first_hit, indirect);
    std::vector<float> patch_area;
    for (const Patch& p : session.bake().patches.patches) patch_area.push_back(p.area);
    r.comparison["patch_indirect_rel_rms"] =
        area_weighted_relative_rms(patch_area, indirect, *exact);
  }
  ConsoleProgress console(opt.quiet || opt.json);
  const std::vector<glm::vec3>* exact_light = exact ? &*exact : nullptr;
  if (!opt.no_mesh) write_mesh(opt, session, exact_light, console.progress(), out, r);
  if (!opt.no_images) write_camera(opt, session, exact_light, console.progress(), out, r);
  r.timings["total"] = since(start);
  const nlohmann::ordered_json summary = solve_summary(opt, session, out, r);
  if (opt.json)
    std::cout << summary.dump(2) << '\n';
  else
    print_summary(summary);
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
