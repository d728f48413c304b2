#pragma once
// View 5, the live preview (docs/studio.md): the scene in OpenGL 3.3
// core with
//   1. a shadow cube map of the light (distance to the light per texel),
//   2. a G-buffer (view-space position and normal, albedo, emission, and the
//      runtime solve's indirect irradiance per vertex, interpolated), with the
//      albedo and emission looked up in the material's textures, the normal
//      perturbed by its tangent-space normal map (per-vertex tangents from
//      the texture coordinates) and alpha-masked materials cut away (also
//      in the shadow map),
//   3. SSAO (hemisphere kernel of 32 samples rotated per
//      pixel by a tiled 4 x 4 noise texture, depth test with bias delta),
//   4. a 4 x 4 box blur of the occlusion map,
//   5. the composite: albedo x (direct irradiance with percentage-closer
//      filtering + indirect irradiance scaled by the blurred occlusion),
//      plus emission, one fixed
//      exposure, sRGB; each of direct / indirect / AO can be switched off,
// and an overlay with the frame rate and the solve time.
//
// All light transport comes from the core through PreviewLighting (the
// runtime frame graph and the mesh transfer of `bounce solve`); the widget
// only draws. When the light moves the solve runs again: on the UI thread
// when the last one fitted in kUiSolveBudget, otherwise on the studio's view
// jobs (view_jobs.h), where only the latest light position is solved
// (positions the jobs had no time for are skipped).
//
// Mouse: left drag orbits the camera, right drag or the wheel moves it
// closer, Ctrl + left drag moves the light in the plane facing the camera,
// Ctrl + wheel moves it towards or away from the camera. The light stays
// inside the scene's bounds.
//
// With a bake's light probes (runtime/light_probes.h) the preview can show
// them, each a small sphere showing the light its SH L2 irradiance
// gives a white surface facing each way, and a grey object (a sphere, or a
// mesh the user loads) standing for a moving thing, lit by the probes around it (blended where it
// is, through the visibility test of LightingSession::probe_sh_at) and by the light's direct light;
// Shift + left drag moves it in the plane facing the camera. Both follow the light live. The sphere
// casts no shadow and does not light the scene: probes light what moves, not the walls.
#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <QElapsedTimer>
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLWidget>
#include <QPoint>
#include <glm/glm.hpp>

#include "bake_view_data.h"
#include "orbit_camera.h"
#include "preview_material_images.h"
#include "preview_programs.h"
#include "preview_shapes.h"
#include "preview_targets.h"

namespace bounce::views {

class PreviewLighting;
class ViewJobs;

class PreviewWidget : public QOpenGLWidget, protected QOpenGLFunctions_3_3_Core {
  Q_OBJECT
 public:
  struct Passes {
    bool direct = true;
    bool indirect = true;
    bool ao = true;
    // Normal maps perturb the shading normal (direct light and SSAO); off,
    // every surface is drawn with its interpolated normal.
    bool normal_maps = true;
  };
  // A solve faster than this runs on the UI thread (a 60 Hz frame is 16.7
  // ms: half of it is left for the solve, the rest for drawing).
  static constexpr double kUiSolveBudget = 0.008;
  static constexpr int kAoSamples = 32;  // the SSAO kernel size (docs/studio.md: m = 32)
  static constexpr int kShadowSize = 512;

  explicit PreviewWidget(ViewJobs& jobs, QWidget* parent = nullptr);
  ~PreviewWidget() override;

  // Builds the lighting (mesh refinement, frame graph) and solves (twice,
  // timed, for the policy) at the light's scene position. Throws bounce::Error (no scene on disk,
  // no point or spot light, no matrix); the widget then shows nothing.
  void set_data(std::shared_ptr<const BakeViewData> data);
  bool has_data() const { return lighting_ != nullptr; }
  void clear();

  void set_passes(Passes passes);
  Passes passes() const { return passes_; }
  void set_overlay(bool on);

  // The bake's light probes, and whether they are drawn.
  bool has_probes() const;
  std::size_t probe_count() const;
  void set_probes_shown(bool on);
  bool probes_shown() const { return probes_shown_; }
  // The probe-lit sphere: shown or not, where, and the SH it is lit with.
  // Moving it blends the SH there from the probes' last frame.
  void set_sphere_shown(bool on);
  bool sphere_shown() const { return sphere_shown_; }
  void set_sphere_position(const glm::vec3& position);
  glm::vec3 sphere_position() const { return sphere_position_; }
  float sphere_radius() const;
  const std::array<glm::vec3, kShCoefficients>& sphere_sh() const { return sphere_sh_; }
  // The moving object's shape: the mesh in `path` (scaled to the sphere's
  // radius, centred where the sphere is), or the sphere again. Throws
  // bounce::Error naming the file when it cannot be read.
  void load_object(const std::string& path);
  void use_sphere();
  const std::string& object_name() const { return object_name_; }

  // Moves the light. wait: solve on this thread now (tests, screenshots);
  // otherwise as the solve policy says (see above).
  void set_light_position(const glm::vec3& position, bool wait = false);
  glm::vec3 light_position() const { return light_position_; }
  // Position the indirect light on screen belongs to.
  glm::vec3 solved_light_position() const { return solved_light_; }
  // Whether that indirect light is exact there: a moving light's shadow
  // rays are spread over a few solves (PreviewLighting::kShadowFrames), and
  // the preview solves again where it stopped until they are.
  bool solved_settled() const { return solved_settled_; }

  // The picture as the screen shows it (grabFramebuffer).
  QImage render_image();
  // Mean milliseconds per frame of `frames` renders at the current size
  // (glFinish after each, so it is what the GPU took, not what was queued).
  double measure_frame_ms(int frames);
  // Where a world point lands in the widget (pixels, y down).
  QPointF project(const glm::vec3& world) const;

  // Empty unless OpenGL set-up failed (shader compile or link, FBO).
  const QString& gl_error() const { return gl_error_; }
  bool solve_on_worker() const { return solve_on_worker_; }
  double last_solve_ms() const { return 1e3 * (frame_seconds_ + transfer_seconds_); }
  double last_frame_graph_ms() const { return 1e3 * frame_seconds_; }
  double last_transfer_ms() const { return 1e3 * transfer_seconds_; }
  std::size_t vertex_count() const;
  // Writes the lit mesh at the current light position as binary glTF with
  // the scene's materials and textures (what `bounce solve` writes to
  // lit.glb). Throws bounce::Error when no bake is shown or the file cannot
  // be written.
  void export_lit_glb(const std::string& path);
  std::size_t triangle_count() const;

 signals:
  void solved();  // a new indirect light is on screen

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  struct SolveResult;
  void render(GLuint target);
  void render_gbuffer(const glm::mat4& view, const glm::mat4& projection, int w, int h);
  void render_occlusion(const glm::mat4& projection, int w, int h);
  void draw_composite(bool direct, bool indirect, bool ao, float exposure, bool linear);
  void calibrate_exposure(int width, int height);
  void draw_overlay();
  void release_gl();
  void upload_mesh();
  // Draws the mesh one material at a time with `program`, its textures bound
  // to units 0 (albedo), 1 (alpha mask), 2 (normal map) and 3 (emission)
  // and the uniforms that say which of them the material has.
  void draw_mesh(QOpenGLShaderProgram& program);
  void upload_indirect();
  void render_shadow_map();
  void apply(SolveResult result);
  // Solves for the light at `position` (wait: now, on this thread, until
  // settled), without touching the direct light's shadow map.
  void solve_at(const glm::vec3& position, bool wait);
  void reset_camera();
  float aspect() const;  // width / height
  void move_light_by(const glm::vec3& delta);
  glm::vec3 inside_scene(const glm::vec3& p) const;  // clamped a little inside the bounds
  void draw_shapes(const glm::mat4& view, const glm::mat4& projection);
  void upload_shapes();
  void place_sphere();  // by the probe nearest the scene's centre
  // Where a solve blends the sphere's SH, when the probes or the object are
  // shown; a solve without skips the probes.
  std::optional<glm::vec3> probes_wanted() const;
  // The probes' SH for the light last solved, when they are not: a probe
  // view switched on after moves that skipped them.
  void refresh_probes();

  // The one job of this widget: the light solved at its latest position.
  static constexpr int kSolveJob = 0;

  ViewJobs& jobs_;
  std::shared_ptr<const BakeViewData> data_;
  // Shared with the solve running on the jobs, which may outlive the widget.
  std::shared_ptr<PreviewLighting> lighting_;
  std::shared_ptr<std::mutex> lighting_mutex_ =
      std::make_shared<std::mutex>();  // one solve at a time
  bool solve_on_worker_ = false;

  Passes passes_;
  bool overlay_ = true;
  glm::vec3 light_position_{0.0f}, solved_light_{0.0f};
  bool solved_settled_ = true;
  std::vector<glm::vec3> vertex_indirect_;  // indirect irradiance per mesh vertex
  bool probes_shown_ = false, sphere_shown_ = false;
  glm::vec3 sphere_position_{0.0f};
  std::vector<glm::vec3> probe_sh_;  // the last solve's, kShCoefficients per probe
  bool probes_current_ = false;      // probe_sh_ is the last solved light's
  std::array<glm::vec3, kShCoefficients> sphere_sh_{};
  double probe_seconds_ = 0.0;
  double frame_seconds_ = 0.0, transfer_seconds_ = 0.0;

  OrbitCamera camera_;
  QPoint last_mouse_;

  // Frame timing for the overlay.
  QElapsedTimer clock_;
  double last_paint_ = -1.0, mean_interval_ = 0.0;

  // OpenGL objects (0: not made).
  bool gl_ready_ = false, mesh_dirty_ = false, indirect_dirty_ = false, shadow_dirty_ = true,
       shapes_dirty_ = true;
  QString gl_error_;
  PreviewPrograms programs_;
  GLuint mesh_vao_ = 0, static_vbo_ = 0, indirect_vbo_ = 0, empty_vao_ = 0;
  GLsizei corner_count_ = 0;
  std::vector<std::uint32_t> corner_vertex_;  // mesh vertex of each drawn corner
  // The corners are grouped by material: one draw per material, with the
  // OpenGL images of its albedo texture, alpha mask, normal map and emissive
  // texture (0: none).
  struct MaterialDraw {
    GLint first = 0;
    GLsizei count = 0;
    std::size_t material = 0;
    PreviewMaterialImages::Images images;
  };
  std::vector<MaterialDraw> draws_;
  PreviewMaterialImages material_images_{*this};  // every image draws_ names, each once
  GLuint shadow_fbo_ = 0, shadow_cube_ = 0;
  PreviewTargets targets_{*this};
  PreviewShapes probe_spheres_{*this}, object_{*this};
  std::string object_name_ = "sphere";
  GLuint noise_texture_ = 0;
  std::vector<glm::vec3> ao_kernel_;
  // Set from the first frame drawn after set_data, then fixed (see render()).
  std::optional<float> exposure_full_, exposure_indirect_;
};

}  // namespace bounce::views
