#pragma once
// A bake folder opened for relighting: the bake as BakeReader reads it, its
// scene (for the tracer and the lights) and a Relighter, the sequence
// `bounce solve` runs. relight() lights the patches and, through the bake's
// final gather (or from the patches when it stored none), the lit mesh's
// vertices.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bounce/bake_folder.h"
#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::python {

struct RelitFrame {
  std::vector<glm::vec3> first_hit;  // b per patch
  std::vector<glm::vec3> indirect;   // T b per patch
  std::vector<glm::vec3> reflected;  // b + T b per patch
  std::vector<glm::vec3> exitance;   // emission + b + T b per patch
  std::vector<glm::vec3> vertex_light;
};

class OpenedBake {
 public:
  // `scene` empty: the scene the manifest names. Throws bounce::Error.
  OpenedBake(const std::filesystem::path& folder, const std::filesystem::path& scene);

  std::size_t patch_count() const { return bake_.size(); }
  const Scene& scene() const { return scene_; }
  const LoadedBake& bake() const { return bake_; }
  const std::string& multiply_name() const { return relighter_->multiply_name(); }
  bool has_final_gather() const { return gather_.has_value(); }
  // The lit mesh's vertices and triangles (built on first use).
  const LitMesh& mesh();

  // One frame with the scene's lights, those named in `moved` moved to the
  // given positions. Throws bounce::Error for a name the scene lacks or a
  // directional light.
  RelitFrame relight(const std::map<std::string, glm::vec3>& moved);

  // The scene camera's pictures under the scene's own lights, as `bounce
  // solve` renders them: each pixel gathers b + T b from the patches it sees
  // with `gather_rays` rays when the bake keeps what that needs
  // (camera_gather_possible) and gather_rays > 0, else from the nearest
  // patches. The camera's direct light comes from the scene's lights, so
  // lights moved in relight() do not apply here. Throws bounce::Error for a
  // bad size or ray count.
  CameraImages camera_images(const CameraImageSettings& settings, int gather_rays);

 private:
  std::filesystem::path folder_;
  LoadedBake bake_;
  Scene scene_;
  std::unique_ptr<RayTracer> tracer_;
  std::optional<FinalGather> gather_;
  std::unique_ptr<Relighter> relighter_;
  std::optional<LitMesh> mesh_;
};

}  // namespace bounce::python
