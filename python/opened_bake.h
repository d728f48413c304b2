#pragma once
// A bake folder opened for relighting from Python: a LightingSession
// (bounce/relight.h) with the calls the module exposes. relight() lights the
// patches and the lit mesh's vertices with the scene's lights, some of them
// moved; camera_images() renders the scene camera.
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bounce/relight.h"

namespace bounce::python {

struct RelitFrame {
  std::vector<glm::vec3> first_hit;  // b per patch
  std::vector<glm::vec3> indirect;   // T b per patch
  std::vector<glm::vec3> reflected;  // b + T b per patch
  std::vector<glm::vec3> exitance;   // emission + b + T b per patch
  std::vector<glm::vec3> vertex_light;
  // The light probes' irradiance SH, 9 per probe (empty without probes).
  std::vector<glm::vec3> probe_sh;
};

class OpenedBake {
 public:
  // `scene` empty: the scene the manifest names. Throws bounce::Error.
  OpenedBake(const std::filesystem::path& folder, const std::filesystem::path& scene);

  std::size_t patch_count() const { return session_.bake().size(); }
  const Scene& scene() const { return session_.scene(); }
  const LoadedBake& bake() const { return session_.bake(); }
  const std::string& multiply_name() const { return session_.relighter().multiply_name(); }
  bool has_final_gather() const { return session_.final_gather().has_value(); }
  // The light probes' positions (empty without probes).
  std::vector<glm::vec3> probe_positions() const {
    return session_.light_probes() ? session_.light_probes()->position : std::vector<glm::vec3>{};
  }
  // The lit mesh's vertices and triangles (built on first use).
  const LitMesh& mesh() { return session_.mesh(); }

  // One frame with the scene's lights, those named in `moved` moved to the
  // given positions. Throws bounce::Error for a name the scene lacks or a
  // directional light.
  RelitFrame relight(const std::map<std::string, glm::vec3>& moved);

  // The scene camera's pictures under the scene's own lights, as `bounce
  // solve` renders them (SessionCamera). Throws bounce::Error for a bad size
  // or ray count.
  CameraImages camera_images(const CameraImageSettings& settings, int gather_rays);

  // The irradiance SH at `point` in the last frame (relight() or
  // camera_images(); before either, the scene's own lights), blended from
  // the probes that see it; zero when none does. Throws bounce::Error
  // without probes.
  std::array<glm::vec3, kShCoefficients> probe_sh_at(const glm::vec3& point);

 private:
  LightingSession session_;
  bool lit_ = false;  // a frame has been lit
};

}  // namespace bounce::python
