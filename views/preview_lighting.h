#pragma once
// The light transport behind the live preview (view 5): a LightingSession
// (bounce/relight.h), the one `bounce solve` and the Python module open,
// over the bake and scene the studio holds. It lights the patches (direct
// light, b = albedo * E, the bake's T b through the compressed C++ product
// or the dense one) and takes their light to the vertices of the refined
// scene mesh by the session's one rule.
// The preview draws the direct light itself per pixel (shadow map), so
// what it takes from here per frame is the indirect irradiance on the
// vertices: the preview reflects it with the albedo under each pixel (the
// texel of a textured material), as `bounce solve`'s camera pictures do.
//
// The preview lights the scene with one movable light: the scene's first
// point or spot light. Other lights and emissive triangles (area lights) are
// left out of both the direct and the indirect light, so the two always
// belong to the same light; emissive surfaces still show their emission.
//
// Not thread-safe: one solve() at a time (on the view jobs or the UI
// thread, never both).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake_view_data.h"
#include "bounce/relight.h"

namespace bounce::views {

class PreviewLighting {
 public:
  struct Solve {
    glm::vec3 light_position{0.0f};
    // Indirect irradiance at each mesh vertex (light arriving, not yet
    // reflected: times the albedo it is the vertex's T b).
    std::vector<glm::vec3> vertex_irradiance;
    double frame_seconds = 0.0;     // the frame graph: direct light, first hit, T b
    double transfer_seconds = 0.0;  // patches -> vertices (gather with occlusion rays)
    // The near sources' shadows are exact for this light position (else
    // more solves there make them so; see kShadowFrames).
    bool settled = true;
    // With a bake's light probes: kShCoefficients irradiance SH coefficients
    // per probe (LightingSession::probe_sh), and the SH at the probe-lit
    // sphere's centre blended from them (LightingSession::probe_sh_at).
    std::vector<glm::vec3> probe_sh;
    bool probes_solved = false;  // probe_sh and sphere_sh are this light's
    glm::vec3 sphere_position{0.0f};
    std::array<glm::vec3, kShCoefficients> sphere_sh{};
    double probe_seconds = 0.0;  // the probes' gather, fit and the sphere's blend
  };

  // A moving light's shadow rays (the patches' samples' and the final
  // gather's near sources') and the gather's vertex rows are spread over
  // this many solves (runtime/shadow_budget.h, runtime/gather_row_budget.h):
  // a drag costs a quarter of them per frame, and kShadowFrames solves at
  // the position where the light stops make its light exact.
  static constexpr int kShadowFrames = 4;

  // Throws bounce::Error when the bake's scene is not loaded, the scene has
  // no point or spot light, or the bake holds no matrix to multiply by.
  explicit PreviewLighting(std::shared_ptr<const BakeViewData> data);
  ~PreviewLighting();
  PreviewLighting(const PreviewLighting&) = delete;
  PreviewLighting& operator=(const PreviewLighting&) = delete;

  // One frame with the light at `light_position`; `settle`: as many more
  // there as its shadows need to be exact (at most kShadowFrames in all).
  // With `probes_at` and a bake with light probes: the probes' SH too, and
  // the sphere's blended at `probes_at` (without, a move skips them: they
  // cost 1-2 ms a move on Sponza, for nothing when neither is shown).
  Solve solve(const glm::vec3& light_position, bool settle = false,
              const std::optional<glm::vec3>& probes_at = std::nullopt);
  // The probes' SH for the last solve's light, and the sphere's at
  // `sphere_position`, into `s` (nothing without probes).
  void solve_probes(const glm::vec3& sphere_position, Solve& s);

  // The bake's light probes: none when it was baked without them.
  bool has_probes() const { return session_->light_probes().has_value(); }
  const std::vector<glm::vec3>& probe_positions() const;
  // The SH at `point` blended from the last solve's probes (zero without
  // probes), as the sphere gets it when it moves and the light does not.
  std::array<glm::vec3, kShCoefficients> sh_at(const glm::vec3& point);
  // The bake's voxel edge: the probes stand at least this far apart.
  float cell_size() const;

  // The whole light leaving each vertex with the light at `light_position`:
  // emission + albedo x (direct + indirect irradiance), what `bounce solve`
  // writes to lit.ply and lit.glb, for File > Export. Same threading rule as
  // solve().
  LitMesh lit_mesh(const glm::vec3& light_position);

  // The refined mesh (positions, normals, triangles, source triangle); its
  // radiosity is not kept up to date (solve() returns the light).
  const LitMesh& mesh() const { return *geometry_; }
  const Scene& scene() const { return *data_->scene; }
  const Light& light() const { return light_; }  // at its scene position
  const std::string& multiply_name() const { return session_->relighter().multiply_name(); }
  std::size_t patch_count() const { return data_->patch_count(); }

 private:
  std::shared_ptr<const BakeViewData> data_;
  std::unique_ptr<LightingSession> session_;
  // The session's mesh geometry: read by the UI thread, built before the
  // first solve() and never written after.
  const LitMesh* geometry_ = nullptr;
  Light light_;  // at its scene position
};

}  // namespace bounce::views
