#version 330 core
// Stores the distance to the light (divided by far_plane) rather than the
// projected depth: the lighting pass compares distances along any direction
// without knowing which cube face a point falls on. Where an alpha mask cuts
// the surface away it casts no shadow, as rays pass there in the core.
in vec3 world_position;
in vec2 frag_uv;
flat in float frag_mapped;  // 0: no texture coordinates, only a constant mask applies

uniform vec3 light_position;
uniform float far_plane;
uniform bool has_mask;
uniform bool constant_mask;
uniform sampler2D alpha_mask;  // coverage, row 0 = top of the image = v 1
uniform float alpha_factor;
uniform float alpha_cutoff;

void main() {
  if (has_mask && (frag_mapped > 0.5 || constant_mask) &&
      texture(alpha_mask, vec2(frag_uv.x, 1.0 - frag_uv.y)).r * alpha_factor < alpha_cutoff)
    discard;
  gl_FragDepth = length(world_position - light_position) / far_plane;
}
