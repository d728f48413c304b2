#version 330 core
// The surface under each pixel: a textured material's albedo is its texel
// (linear, MIP-mapped) times the factor, clamped to the core's albedo range
// (Scene::albedo_at); an alpha-masked material is cut away where the mask
// times its factor is below the cutoff (Scene::solid_at), so what lies
// behind shows through. A triangle without texture coordinates keeps its
// mean albedo (the vertex attribute) and its whole surface, unless its mask
// is a constant. Texture images are stored from their top row, which is
// v = 1: the lookups flip v. An emissive texture's texel times the factor
// is the emission (Scene::emission_at). A normal map's texel c is the
// direction 2 c - 1 in the frame (tangent, bitangent, normal), its first two
// components times the material's scale (glTF's rule), so the normal the
// direct light and the SSAO see follows the map; where the surface has no
// tangent frame the interpolated normal stays.
in vec3 view_position;
in vec3 view_normal;
in vec3 frag_albedo;
in vec3 frag_emission;
in vec3 frag_indirect;
in vec2 frag_uv;
flat in float frag_mapped;
in vec4 view_tangent;

uniform bool has_texture;
uniform sampler2D albedo_texture;
uniform bool has_mask;
uniform bool constant_mask;  // one texel: the same everywhere, coordinates or not
uniform sampler2D alpha_mask;
uniform float alpha_factor;
uniform float alpha_cutoff;
uniform bool has_normal_map;
uniform sampler2D normal_map;  // stored values (not sRGB-decoded)
uniform float normal_scale;
uniform bool has_emission_texture;
uniform sampler2D emission_texture;

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
  vec3 n = normalize(view_normal);
  if (has_normal_map && mapped && view_tangent.w != 0.0) {
    vec3 t = normalize(view_tangent.xyz - n * dot(n, view_tangent.xyz));
    vec3 b = view_tangent.w * cross(n, t);
    vec3 m = 2.0 * texture(normal_map, st).rgb - 1.0;
    m.xy *= normal_scale;
    if (dot(m, m) > 0.0) n = normalize(mat3(t, b, n) * m);
  }
  vec3 emission = frag_emission;
  if (has_emission_texture && mapped) emission *= texture(emission_texture, st).rgb;
  g_position = view_position;
  g_normal = n;
  g_albedo = vec4(albedo, 1.0);
  g_emission = emission;
  g_indirect = frag_indirect;
}
