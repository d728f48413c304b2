#pragma once
// What a renderer outside the core needs to draw a scene's textures itself
// (the studio's live preview): texture coordinates anywhere on a triangle.
// The images are the decoded ones the core samples (Texture::levels, linear
// RGB with its MIP pyramid; AlphaMask::values), so a picture drawn from them
// shows what the bake and `bounce solve` reflect and cut away.
#include <cstddef>

#include <glm/glm.hpp>

namespace bounce {

struct Scene;

// Texture coordinates of point p on (or projected onto the plane of)
// triangle tri, interpolated from the triangle's corners; (0, 0) when the
// scene has no texture coordinates.
glm::vec2 texture_coordinates(const Scene& scene, std::size_t tri, const glm::vec3& p);

}  // namespace bounce
