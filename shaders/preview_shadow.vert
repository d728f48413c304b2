#version 330 core
// Shadow cube map, one face per draw: the scene seen from the light.
layout(location = 0) in vec3 position;  // world space
layout(location = 5) in vec2 uv;        // texture coordinates, for the alpha mask
layout(location = 6) in float mapped;   // 1: uv holds the triangle's coordinates; 0: it has none

uniform mat4 light_view_projection;  // this face's 90-degree frustum

out vec3 world_position;
out vec2 frag_uv;
flat out float frag_mapped;

void main() {
  world_position = position;
  frag_uv = uv;
  frag_mapped = mapped;
  gl_Position = light_view_projection * vec4(position, 1.0);
}
