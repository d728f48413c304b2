#include "relight/lighting_session.h"

#include <algorithm>

#include "bake/stored_transport.h"
#include "base/error.h"
#include "folder/final_gather_files.h"
#include "folder/light_probe_files.h"
#include "scene/scene_loader.h"

namespace fs = std::filesystem;

namespace bounce {

namespace {

// The session's own bake or scene, held the same way as one a caller shares.
template <typename T>
std::shared_ptr<const T> owned(T&& value) {
  return std::make_shared<const T>(std::forward<T>(value));
}

std::vector<glm::vec3> sum(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  std::vector<glm::vec3> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] + b[i];
  return out;
}

}  // namespace

Scene load_baked_scene(const LoadedBake& bake, const fs::path& given, Diagnostics& diagnostics) {
  const fs::path path = given.empty() ? bake.description.scene_path : given;
  if (!fs::exists(path))
    throw Error(path.string(),
                "the scene the bake was made from is not there any more: give its new path");
  Scene scene = SceneLoader(diagnostics).load(path);
  check_baked_scene(bake, scene);
  return scene;
}

void check_baked_scene(const LoadedBake& bake, const Scene& scene) {
  const std::size_t baked = bake.description.scene_triangles;
  if (scene.triangle_count() != baked)
    throw Error(scene.path, "has " + std::to_string(scene.triangle_count()) +
                                " triangles, the bake was made from " + std::to_string(baked) +
                                ": not the same scene");
}

void move_named_light(std::vector<Light>& lights, const std::string& name,
                      const glm::vec3& position) {
  std::string names;
  for (Light& l : lights) {
    if (l.name == name) {
      if (l.type == Light::Type::Directional)
        throw Error("lights", "'" + name + "' is a directional light: it has no position");
      l.position = position;
      return;
    }
    names += (names.empty() ? "" : ", ") + l.name;
  }
  throw Error("lights", "the scene has no light named '" + name +
                            "' (its lights: " + (names.empty() ? "none" : names) + ")");
}

LightingSession::LightingSession(const fs::path& folder, const LightingSessionSettings& settings,
                                 Diagnostics* diagnostics)
    : bake_(owned(BakeReader::read(folder, settings.dense))) {
  Diagnostics quiet;
  scene_ = owned(load_baked_scene(*bake_, settings.scene, diagnostics ? *diagnostics : quiet));
  start(settings, diagnostics);
}

LightingSession::LightingSession(std::shared_ptr<const LoadedBake> bake,
                                 std::shared_ptr<const Scene> scene,
                                 const LightingSessionSettings& settings, Diagnostics* diagnostics)
    : bake_(std::move(bake)), scene_(std::move(scene)) {
  if (!bake_) throw Error("lighting session", "no bake");
  if (!scene_)
    throw Error(bake_->dir.string(), "the scene it was baked from is not loaded: give its path");
  check_baked_scene(*bake_, *scene_);
  start(settings, diagnostics);
}

LightingSession::~LightingSession() = default;

void LightingSession::start(const LightingSessionSettings& settings, Diagnostics* diagnostics) {
  tracer_ = std::make_unique<RayTracer>(*scene_);
  gather_ = read_final_gather(bake_->dir, bake_->size(), bake_->samples.samples.size());
  probes_ = read_light_probes(bake_->dir, bake_->size(), bake_->samples.samples.size());
  with_probe_emission_ = settings.probe_emission;
  relighter_ =
      std::make_unique<Relighter>(*tracer_, bake_->samples, bake_->patches,
                                  stored_transport(*bake_), settings.relighter, diagnostics);
  reset_lights();
}

const char* LightingSession::transfer_name() const {
  return gather_ ? "final gather" : "nearest patches";
}

void LightingSession::move_light(const std::string& name, const glm::vec3& position) {
  move_named_light(lights_, name, position);
}

void LightingSession::set_light(const Light& light) {
  for (Light& l : lights_)
    if (l.name == light.name) {
      l = light;
      return;
    }
  move_named_light(lights_, light.name, light.position);  // throws, naming the lights
}

void LightingSession::reset_lights() {
  lights_ = scene_->lights;
  area_ = bounce::area_lights(*scene_);
}

void LightingSession::use_lights(std::vector<Light> lights) {
  lights_ = std::move(lights);
  area_.clear();
}

void LightingSession::light() {
  relighter_->light(lights_, area_);
  frame_probe_sh_stale_ = true;
}

const LitMesh& LightingSession::mesh(Progress* progress) {
  if (mesh_) return *mesh_;
  LitMesh mesh =
      build_transfer_mesh(*scene_, bake_->description.grid, TransferSettings{}, progress);
  if (gather_ && mesh.positions.size() != gather_->points())
    throw Error((bake_->dir / bake_file::kGatherFirst).string(),
                "holds " + std::to_string(gather_->points()) +
                    " vertices, the scene's lit mesh has " + std::to_string(mesh.positions.size()) +
                    ": not this scene");
  if (!gather_) {
    const std::vector<std::uint32_t> source = vertex_source_triangles(mesh);
    vertex_inverse_albedo_.resize(source.size());
    for (std::size_t v = 0; v < source.size(); ++v) {
      const glm::vec3 albedo = scene_->flat_albedo_at(source[v], mesh.positions[v]);
      for (int c = 0; c < 3; ++c)
        vertex_inverse_albedo_[v][c] = albedo[c] > 1e-4f ? 1.0f / albedo[c] : 0.0f;
    }
  }
  mesh_ = std::move(mesh);
  return *mesh_;
}

LitMesh LightingSession::lit_mesh(Progress* progress) {
  if (!gather_) return lit_from_nearest(frame().exitance(), progress);
  mesh(progress);
  std::vector<glm::vec3> gathered;
  relighter_->gather(*gather_, gathered);
  return lit_from_gathered(gathered, progress);
}

LitMesh LightingSession::lit_mesh(const std::vector<glm::vec3>& patch_indirect,
                                  Progress* progress) {
  if (patch_indirect.size() != bake_->size())
    throw Error("lighting session", "T b has " + std::to_string(patch_indirect.size()) +
                                        " patches, the bake " + std::to_string(bake_->size()));
  std::vector<glm::vec3> first_hit, unused;
  relighter_->first_hit_and_indirect(first_hit, unused);
  if (!gather_) {
    // Everything the patches send out: emission + b + T b.
    std::vector<glm::vec3> exitance = sum(first_hit, patch_indirect);
    const std::vector<Patch>& patches = bake_->patches.patches;
    for (std::size_t p = 0; p < exitance.size(); ++p)
      exitance[p] = patches[p].emission + exitance[p];
    return lit_from_nearest(exitance, progress);
  }
  std::vector<glm::vec3> sample_light;
  if (gather_->samples > 0)
    sample_light = sample_exitance(bake_->samples, bake_->patches, frame().sample_irradiance(),
                                   patch_indirect);
  std::vector<glm::vec3> gathered;
  gather_->irradiance(sum(first_hit, patch_indirect), sample_light,
                      near_exitance(gather_->near, tracer_.get(), lights_, area_, patch_indirect),
                      gathered);
  mesh(progress);
  return lit_from_gathered(gathered, progress);
}

LitMesh LightingSession::lit_from_gathered(const std::vector<glm::vec3>& gathered,
                                           Progress* progress) {
  LitMesh lit = mesh(progress);
  light_vertices(*tracer_, lights_, area_, gathered, lit);
  return lit;
}

LitMesh LightingSession::lit_from_nearest(const std::vector<glm::vec3>& patch_exitance,
                                          Progress* progress) {
  LitMesh lit = mesh(progress);
  const PatchGather nearest(bake_->patches.patches, patch_exitance, bake_->description.grid,
                            tracer_.get(), GatherSettings{});
  relight(lit, nearest, progress);
  return lit;
}

void LightingSession::vertex_irradiance(std::vector<glm::vec3>& out) {
  if (gather_) {
    relighter_->gather(*gather_, out);
    return;
  }
  std::vector<glm::vec3> first_hit, indirect;
  relighter_->first_hit_and_indirect(first_hit, indirect);
  LitMesh lit = mesh();
  const PatchGather nearest(bake_->patches.patches, indirect, bake_->description.grid,
                            tracer_.get(), GatherSettings{});
  relight(lit, nearest);
  out = std::move(lit.radiosity);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] *= vertex_inverse_albedo_[v];
}

void LightingSession::probe_sh(std::vector<glm::vec3>& sh) {
  if (!probes_) {
    sh.clear();
    return;
  }
  refresh_probe_sh();
  sh = frame_probe_sh_;
}

// The probes' gather is the frame's cost of its probes; the frame changes
// only in light(), so one gather serves every call until the next.
void LightingSession::refresh_probe_sh() {
  if (!frame_probe_sh_stale_) return;
  relighter_->gather_far(probes_->gather, probe_irradiance_);
  if (with_probe_emission_) add_probe_emission(probe_irradiance_);
  fit_probe_sh(probe_irradiance_, frame_probe_sh_);
  frame_probe_sh_stale_ = false;
}

// The emissive surfaces do not change with the lights: their light at the
// probes is gathered once, through the probes' own gather, from each patch's
// emission (the exitance the frame adds to b + T b). A sample source takes
// its patch's: the bake folder keeps emission per patch only.
void LightingSession::add_probe_emission(std::vector<glm::vec3>& direction_irradiance) {
  if (!probe_emission_) {
    std::vector<glm::vec3> patch_emission;
    for (const Patch& p : bake_->patches.patches) patch_emission.push_back(p.emission);
    std::vector<glm::vec3> sample_emission;
    for (const std::int32_t p : bake_->patch_of_sample)
      sample_emission.push_back(p >= 0 ? patch_emission[static_cast<std::size_t>(p)]
                                       : glm::vec3(0.0f));
    probe_emission_.emplace();
    if (std::any_of(patch_emission.begin(), patch_emission.end(),
                    [](const glm::vec3& e) { return e != glm::vec3(0.0f); }))
      probes_->gather.irradiance(patch_emission, sample_emission, *probe_emission_);
  }
  if (probe_emission_->empty()) return;  // nothing emits
  for (std::size_t i = 0; i < direction_irradiance.size(); ++i)
    direction_irradiance[i] += (*probe_emission_)[i];
}

ProbeBlend LightingSession::probe_sh_at(const glm::vec3& point,
                                        std::array<glm::vec3, kShCoefficients>& sh,
                                        ProbeVisibility visibility) {
  if (!probes_)
    throw Error(bake_->dir.string(), "has no light probes (bake with the setting light_probes on)");
  // Built on first use: a session that never asks still opens a bake whose
  // probes the index would refuse (not at the grid's cell centres).
  if (!probe_interpolator_)
    probe_interpolator_ = std::make_unique<ProbeInterpolator>(
        probes_->position, bake_->description.grid, *tracer_, probes_->volumes);
  refresh_probe_sh();
  return probe_interpolator_->sh_at(point, frame_probe_sh_, sh, visibility);
}

SessionCamera LightingSession::camera(const CameraImageSettings& settings, int gather_rays,
                                      Progress* progress) const {
  if (gather_rays < 0 || gather_rays > 65536)
    throw Error("camera_gather_rays",
                "must be between 0 and 65536, got " + std::to_string(gather_rays));
  return SessionCamera(*this, settings, gather_rays, progress);
}

SessionCamera::SessionCamera(const LightingSession& session, const CameraImageSettings& settings,
                             int gather_rays, Progress* progress)
    : session_(session), settings_(settings), progress_(progress) {
  settings_.lights = session.lights();
  if (gather_rays > 0 && camera_gather_possible(session.bake()))
    pixels_ = std::make_unique<CameraGather>(session.tracer(), session.bake(), settings_,
                                             gather_rays, progress);
}

CameraImages SessionCamera::images() const {
  std::vector<glm::vec3> first_hit, indirect;
  session_.relighter().first_hit_and_indirect(first_hit, indirect);
  return images(indirect);
}

CameraImages SessionCamera::images(const std::vector<glm::vec3>& patch_indirect) const {
  if (pixels_) {
    std::vector<glm::vec3> first_hit, unused;
    session_.relighter().first_hit_and_indirect(first_hit, unused);
    return pixels_->images(first_hit, patch_indirect, session_.frame().sample_irradiance(),
                           session_.lights(), session_.area_lights());
  }
  const PatchGather nearest(session_.bake().patches.patches, patch_indirect,
                            session_.description().grid, &session_.tracer(), GatherSettings{});
  return render_camera(session_.tracer(), nearest, settings_, progress_);
}

}  // namespace bounce
