#pragma once
// Tangent frames for the live preview's normal maps. A tangent-space normal
// map stores directions in the frame (tangent, bitangent, normal) where the
// tangent runs along +u and the bitangent along +v of the texture
// coordinates; drawing it needs that frame at every pixel. Each face of the
// refined mesh gets the tangent and bitangent its corners' positions and
// texture coordinates imply (the solution of e = du T + dv B over its two
// edges); each vertex then sums the unit tangents of its faces weighted by
// their area, separately for faces of either handedness (mirrored texture
// coordinates turn the bitangent round, and averaging the two would cancel),
// and makes the sum orthogonal to its normal. Seams where a vertex's faces
// map the texture turned against each other are averaged across, which a
// full MikkTSpace would split instead; flat surfaces get their exact frame.
#include <vector>

#include <glm/glm.hpp>

#include "bounce/relight.h"
#include "bounce/scene.h"

namespace bounce::views {

// One tangent per corner of mesh's faces (corner c of face f at 3 f + c):
// xyz the unit tangent, orthogonal to the vertex normal, w the handedness
// (+1 when the bitangent is normal x tangent, -1 when the texture is
// mirrored). w = 0 where there is no frame: the face has no texture
// coordinates, or they do not span it.
std::vector<glm::vec4> corner_tangents(const Scene& scene, const LitMesh& mesh);

}  // namespace bounce::views
