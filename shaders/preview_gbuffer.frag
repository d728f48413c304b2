#version 330 core
// The surface under each pixel: a textured material's albedo is its texel
// (linear, MIP-mapped) times the factor, clamped to the core's albedo range
// (Scene::albedo_at); an alpha-masked material is cut away where the mask
// times its factor is below the cutoff (Scene::solid_at), so what lies
// behind shows through. A triangle without texture coordinates keeps its
// mean albedo (the vertex attribute) and its whole surface, unless its mask
// is a constant. Texture images are stored from their top row, which is
// v = 1: the lookups flip v.
in vec3 view_position;
in vec3 view_normal;
in vec3 frag_albedo;
in vec3 frag_emission;
in vec3 frag_indirect;
in vec2 frag_uv;
flat in float frag_mapped;

uniform bool has_texture;
uniform sampler2D albedo_texture;
uniform bool has_mask;
uniform bool constant_mask;  // one texel: the same everywhere, coordinates or not
uniform sampler2D alpha_mask;
uniform float alpha_factor;
uniform float alpha_cutoff;

layout(location = 0) out vec3 g_position;  // RGB16F, view space
layout(location = 1) out vec3 g_normal;    // RGB16F, view space, unit
layout(location = 2) out vec4 g_albedo;    // RGBA16F, alpha 1 = geometry here
layout(location = 3) out vec3 g_emission;  // RGB16F
layout(location = 4) out vec3 g_indirect;  // RGB16F, irradiance

const float kMaxAlbedo = 0.9999;  // the core's bound (scene/scene.h)

void main() {
  vec2 st = vec2(frag_uv.x, 1.0 - frag_uv.y);
  bool mapped = frag_mapped > 0.5;
  if (has_mask && (mapped || constant_mask) &&
      texture(alpha_mask, st).r * alpha_factor < alpha_cutoff)
    discard;
  vec3 albedo = frag_albedo;
  if (has_texture && mapped)
    albedo = clamp(albedo * texture(albedo_texture, st).rgb, 0.0, kMaxAlbedo);
  g_position = view_position;
  g_normal = normalize(view_normal);
  g_albedo = vec4(albedo, 1.0);
  g_emission = frag_emission;
  g_indirect = frag_indirect;
}
