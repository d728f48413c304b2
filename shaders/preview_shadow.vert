#version 330 core
// Shadow cube map, one face per draw: the scene seen from the light.
layout(location = 0) in vec3 position;  // world space

uniform mat4 light_view_projection;  // this face's 90-degree frustum

out vec3 world_position;

void main() {
  world_position = position;
  gl_Position = light_view_projection * vec4(position, 1.0);
}
