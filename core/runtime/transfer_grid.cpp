#include "runtime/transfer_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "base/error.h"

namespace bounce {

TransferGrid TransferGrid::from(const VoxelGrid& grid) {
  return {grid.bounds().lo, grid.cell_size(), grid.dims()};
}

TransferGrid TransferGrid::from_manifest(const nlohmann::json& manifest) {
  try {
    const nlohmann::json& g = manifest.at("grid");
    TransferGrid t;
    for (int a = 0; a < 3; ++a) {
      t.origin[a] = g.at("origin").at(static_cast<std::size_t>(a)).get<float>();
      t.dims[a] = g.at("dims").at(static_cast<std::size_t>(a)).get<int>();
    }
    t.cell_size = g.at("cell_size").get<float>();
    if (!(t.cell_size > 0.0f) || !std::isfinite(t.cell_size) || t.dims.x < 1 || t.dims.y < 1 ||
        t.dims.z < 1)
      throw Error("manifest.json", "grid: cell_size must be positive and dims at least 1");
    return t;
  } catch (const nlohmann::json::exception& e) {
    throw Error("manifest.json", std::string("grid: ") + e.what());
  }
}

glm::ivec3 TransferGrid::cell_of(const glm::vec3& p) const {
  const glm::vec3 f = glm::floor((p - origin) / cell_size);
  glm::ivec3 c;
  for (int a = 0; a < 3; ++a) {
    // Clamp in float first: a point far outside must not overflow the int.
    const float clamped = std::clamp(f[a], 0.0f, static_cast<float>(dims[a] - 1));
    c[a] = static_cast<int>(clamped);
  }
  return c;
}

}  // namespace bounce
