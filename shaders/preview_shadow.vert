#version 330 core
// Shadow cube map, one face per draw: the scene seen from the light.
layout(location = 0) in vec3 position;  // world space
layout(location = 5) in vec2 uv;        // texture coordinates, for the alpha mask

uniform mat4 light_view_projection;  // this face's 90-degree frustum

out vec3 world_position;
out vec2 frag_uv;

void main() {
  world_position = position;
  frag_uv = uv;
  gl_Position = light_view_projection * vec4(position, 1.0);
}
