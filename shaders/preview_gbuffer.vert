#version 330 core
// G-buffer pass of the preview (docs/studio.md): view-space position and normal
// (V_vcs = M_mv V, N_vcs = (M_mv^-1)^T N; the view matrix is rigid, so its
// rotation part is its own inverse transpose), plus what the lighting pass
// needs per pixel: albedo (or the texture factor of a textured material),
// emission (or the factor of an emissive texture), texture coordinates, the
// tangent frame of the normal map and the indirect irradiance the runtime
// solve left on this vertex.
layout(location = 0) in vec3 position;  // world space
layout(location = 1) in vec3 normal;    // world space, unit
layout(location = 2) in vec3 albedo;    // textured: the factor the texel is multiplied by
layout(location = 3) in vec3 emission;
layout(location = 4) in vec3 indirect;  // irradiance gathered at the vertex
layout(location = 5) in vec2 uv;
layout(location = 6) in float mapped;  // 1: uv holds the triangle's coordinates; 0: it has none
// World-space unit tangent (+u) orthogonal to the normal, and the
// handedness: the bitangent (+v) is w x normal x tangent; w = 0: no frame.
layout(location = 7) in vec4 tangent;

uniform mat4 view;
uniform mat4 projection;

out vec3 view_position;
out vec3 view_normal;
out vec3 frag_albedo;
out vec3 frag_emission;
out vec3 frag_indirect;
out vec2 frag_uv;
flat out float frag_mapped;
out vec4 view_tangent;

void main() {
  vec4 p = view * vec4(position, 1.0);
  view_position = p.xyz;
  view_normal = mat3(view) * normal;
  frag_albedo = albedo;
  frag_emission = emission;
  frag_indirect = indirect;
  frag_uv = uv;
  frag_mapped = mapped;
  view_tangent = vec4(mat3(view) * tangent.xyz, tangent.w);
  gl_Position = projection * p;
}
