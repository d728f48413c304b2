#version 330 core
// Stores the distance to the light (divided by far_plane) rather than the
// projected depth: the lighting pass compares distances along any direction
// without knowing which cube face a point falls on.
in vec3 world_position;

uniform vec3 light_position;
uniform float far_plane;

void main() { gl_FragDepth = length(world_position - light_position) / far_plane; }
