#pragma once
// A bake folder opened for relighting, the one sequence every front end
// runs (`bounce solve`, the studio's preview, the Python module, the
// benchmarks):
//
//   open and check the folder      BakeReader, its typed BakeDescription
//   load the scene it was made of  load_baked_scene: the same scene, or an error
//   build the tracer and product   RayTracer, Relighter (T b chosen once)
//   hold the lights                the scene's, moved or replaced by name
//   light a frame                  light(): b, T b and the exitance per patch
//   take it to what people see     lit_mesh(), vertex_irradiance(), camera()
//
// One rule takes the patches' light to the lit mesh: through the bake's final
// gather when it stored one (each vertex sums b + T b of what it sees, plus
// its own direct light), otherwise from the nearest patches (each vertex
// blends the light they send out). The camera's pixels follow the same rule
// (SessionCamera).
//
// Not thread-safe: one call at a time.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake/camera_gather.h"
#include "base/progress.h"
#include "folder/bake_reader.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/camera_image.h"
#include "runtime/final_gather.h"
#include "runtime/light_probes.h"
#include "runtime/mesh_transfer.h"
#include "runtime/probe_interpolation.h"
#include "runtime/relighter.h"
#include "scene/scene.h"

namespace bounce {

struct LightingSessionSettings {
  // The scene the bake was made from; empty: the path its manifest records.
  std::filesystem::path scene;
  // Whether to read the exact matrix T.npy, which can be large.
  BakeReader::Dense dense = BakeReader::Dense::kIfNotCompressed;
  // The product T b, its C++ loop and what the frame keeps (runtime/relighter.h).
  RelighterSettings relighter;
  // Whether the light probes' SH holds the light the emissive surfaces send
  // them (what an engine lights a moving object with: its own lights do not
  // include emissive surfaces). Off: the light reflected at least once
  // alone, what a path tracer's indirect light at the probe is.
  bool probe_emission = true;
};

// The scene `bake` was made from: `given`, or when empty the path its
// manifest records. Throws bounce::Error naming the scene file when it is not
// there or is not the same scene (another triangle count).
Scene load_baked_scene(const LoadedBake& bake, const std::filesystem::path& given,
                       Diagnostics& diagnostics);
// Throws bounce::Error naming the scene when `scene` is not the one `bake`
// was made from.
void check_baked_scene(const LoadedBake& bake, const Scene& scene);

// Moves the light called `name` in `lights` to `position`. Throws
// bounce::Error (about "lights") when no light has that name, listing the
// names there are, or when it is directional and so has no position.
void move_named_light(std::vector<Light>& lights, const std::string& name,
                      const glm::vec3& position);

class SessionCamera;

class LightingSession {
 public:
  // Opens `folder` and the scene it was made from. Throws bounce::Error
  // naming the file at fault.
  explicit LightingSession(const std::filesystem::path& folder,
                           const LightingSessionSettings& settings = {},
                           Diagnostics* diagnostics = nullptr);
  // Over a bake and its scene already read (the studio holds both); checks
  // that they belong together.
  LightingSession(std::shared_ptr<const LoadedBake> bake, std::shared_ptr<const Scene> scene,
                  const LightingSessionSettings& settings = {}, Diagnostics* diagnostics = nullptr);
  ~LightingSession();
  LightingSession(const LightingSession&) = delete;
  LightingSession& operator=(const LightingSession&) = delete;

  const LoadedBake& bake() const { return *bake_; }
  const BakeDescription& description() const { return bake_->description; }
  const Scene& scene() const { return *scene_; }
  const RayTracer& tracer() const { return *tracer_; }
  const Relighter& relighter() const { return *relighter_; }
  const RuntimeFrame& frame() const { return relighter_->frame(); }
  const std::optional<FinalGather>& final_gather() const { return gather_; }
  // "final gather" or "nearest patches": how the patches' light reaches the mesh.
  const char* transfer_name() const;

  // The lights the next frame uses: the scene's point, spot and directional
  // lights, and its emissive triangles as area lights.
  const std::vector<Light>& lights() const { return lights_; }
  const std::vector<AreaLight>& area_lights() const { return area_; }
  void move_light(const std::string& name, const glm::vec3& position);
  // Replaces the light named light.name with `light` (a sun turned, a spot
  // aimed); throws bounce::Error naming the lights when there is none.
  void set_light(const Light& light);
  // Back to the scene's own lights and emitters.
  void reset_lights();
  // Only these lights, without the scene's emitters (the studio's preview
  // lights with the one lamp it moves).
  void use_lights(std::vector<Light> lights);

  // One frame on the patches with the current lights.
  void light();

  // The lit mesh's geometry (refined scene triangles), built on first use and
  // checked against the final gather's vertex count; its radiosity is zero.
  const LitMesh& mesh(Progress* progress = nullptr);
  // The last frame on the mesh: the light each vertex sends out (emission +
  // albedo x (direct + gathered indirect irradiance), or the nearest
  // patches' emission + b + T b without a final gather).
  LitMesh lit_mesh(Progress* progress = nullptr);
  // The same with another T b per patch (the exact product's, to compare).
  LitMesh lit_mesh(const std::vector<glm::vec3>& patch_indirect, Progress* progress = nullptr);
  // The indirect irradiance arriving at each vertex in the last frame, before
  // any albedo: the final gather's sum of b + T b, or without one the nearest
  // patches' T b over their albedo.
  void vertex_irradiance(std::vector<glm::vec3>& out);

  // The bake's light probes (runtime/light_probes.h); nullopt when it has none.
  const std::optional<LightProbes>& light_probes() const { return probes_; }
  // The last frame at the probes: kShCoefficients irradiance SH coefficients
  // per probe (probe p's coefficient j at p * kShCoefficients + j; the
  // convention is runtime/light_probes.h's), from the same b + T b the
  // vertices gather, plus the emissive surfaces' light (worked out once per
  // session) unless settings.probe_emission is off; worked out once per
  // frame. Empty without probes.
  void probe_sh(std::vector<glm::vec3>& sh);
  // The last frame's irradiance SH at `point` in the empty space, blended
  // from the probes around it that see it (runtime/probe_interpolation.h):
  // a handful of occlusion rays; the probes' SH is worked out again only
  // when light() ran since the last call. Returns the blend (count 0 and
  // `sh` zero when no probe within reach sees the point). Throws
  // bounce::Error when the bake has no probes, or (on the first call) when
  // they do not stand at the centres of the grid's cells.
  ProbeBlend probe_sh_at(const glm::vec3& point, std::array<glm::vec3, kShCoefficients>& sh,
                         ProbeVisibility visibility = ProbeVisibility::kTested);

  // The scene camera's pictures: see SessionCamera. `gather_rays` 0: the
  // nearest patches. Throws bounce::Error for a ray count outside 0..65536.
  SessionCamera camera(const CameraImageSettings& settings, int gather_rays,
                       Progress* progress = nullptr) const;

 private:
  void start(const LightingSessionSettings& settings, Diagnostics* diagnostics);
  // Gathers the probes' SH of the frame when light() ran since the last time.
  void refresh_probe_sh();
  // Adds the emissive surfaces' light to each probe direction's irradiance.
  void add_probe_emission(std::vector<glm::vec3>& direction_irradiance);
  LitMesh lit_from_gathered(const std::vector<glm::vec3>& gathered, Progress* progress);
  // The nearest patches' light on the mesh: `patch_exitance` is emission + b + T b.
  LitMesh lit_from_nearest(const std::vector<glm::vec3>& patch_exitance, Progress* progress);

  std::shared_ptr<const LoadedBake> bake_;
  std::shared_ptr<const Scene> scene_;
  std::unique_ptr<RayTracer> tracer_;
  std::optional<FinalGather> gather_;
  std::optional<LightProbes> probes_;
  std::vector<glm::vec3> probe_irradiance_;  // per probe direction, kept between frames
  // The emissive surfaces' light per probe direction, gathered on first use;
  // empty when nothing emits.
  std::optional<std::vector<glm::vec3>> probe_emission_;
  bool with_probe_emission_ = true;  // settings.probe_emission
  std::unique_ptr<ProbeInterpolator> probe_interpolator_;
  std::vector<glm::vec3> frame_probe_sh_;  // the probes' SH of the last frame
  bool frame_probe_sh_stale_ = true;       // light() ran since it was worked out
  std::unique_ptr<Relighter> relighter_;
  std::vector<Light> lights_;
  std::vector<AreaLight> area_;
  std::optional<LitMesh> mesh_;
  // Without a final gather: one over each vertex's mean albedo, turning the
  // nearest patches' reflected T b back into the irradiance they received.
  std::vector<glm::vec3> vertex_inverse_albedo_;
};

// The scene camera over a session: each pixel gathers b + T b from the
// patches it sees, as the bake's vertices do, when the bake keeps what that
// needs (camera_gather_possible) and rays were asked for; otherwise it blends
// the nearest patches' T b. The direct light comes from the session's lights.
class SessionCamera {
 public:
  SessionCamera(const LightingSession& session, const CameraImageSettings& settings,
                int gather_rays, Progress* progress);
  // The pictures of the session's last frame.
  CameraImages images() const;
  // The same with another T b per patch.
  CameraImages images(const std::vector<glm::vec3>& patch_indirect) const;
  // "final gather" or "nearest patches".
  const char* transfer_name() const { return pixels_ ? "final gather" : "nearest patches"; }

 private:
  const LightingSession& session_;
  CameraImageSettings settings_;
  Progress* progress_;
  std::unique_ptr<CameraGather> pixels_;
};

}  // namespace bounce
