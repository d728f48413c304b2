#version 330 core
// Lighting and composite. Units are those of `bounce solve`: a surface sends
// out emission + albedo * (E_direct + E_indirect) (runtime/patch_lighting.h),
// with the albedo under the pixel (the texel of a textured material), as
// `bounce solve`'s camera pictures. The direct irradiance is computed here
// per pixel from the light, with the shadow cube map and percentage-closer
// filtering; the indirect irradiance is the runtime solve's, transferred to
// the vertices and interpolated; the ambient occlusion map scales the
// indirect part only (it stands for occlusion of
// light arriving from everywhere, the paper's I_amb; the direct light has
// its own shadow). Then one fixed exposure and the sRGB curve.
// linear_output skips both: the widget reads that picture back once to set
// the exposure with the core's ToneMap rule.
in vec2 uv;

uniform sampler2D g_position;
uniform sampler2D g_normal;
uniform sampler2D g_albedo;
uniform sampler2D g_emission;
uniform sampler2D g_indirect;
uniform sampler2D ao;
uniform samplerCube shadow_map;

uniform mat3 view_to_world;     // rotation of the inverse view matrix
uniform vec3 light_view;        // light position, view space
uniform vec3 light_power;       // colour * intensity (W/sr per colour unit)
uniform int light_is_spot;      // 0: point, 1: spot
uniform vec3 spot_axis_view;    // unit, where the spot shines, view space
uniform vec2 spot_cos;          // cos(inner), cos(outer)
uniform float far_plane;        // shadow distances are stored / far_plane
uniform float shadow_bias;      // world units
uniform float pcf_radius;       // world units, at unit distance from the light

uniform bool show_direct;
uniform bool show_indirect;
uniform bool use_ao;
uniform float exposure;
uniform bool linear_output;  // exposure calibration: linear light, background 0
uniform vec3 background;

out vec4 colour;

// 20 directions spread over the cube's faces and edges for PCF: offsets of
// the lookup direction perpendicular enough to any face to move across
// texels of the face it lands on.
const vec3 kPcf[20] = vec3[](
    vec3(1, 1, 1), vec3(1, -1, 1), vec3(-1, -1, 1), vec3(-1, 1, 1), vec3(1, 1, -1),
    vec3(1, -1, -1), vec3(-1, -1, -1), vec3(-1, 1, -1), vec3(1, 1, 0), vec3(1, -1, 0),
    vec3(-1, -1, 0), vec3(-1, 1, 0), vec3(1, 0, 1), vec3(-1, 0, 1), vec3(1, 0, -1),
    vec3(-1, 0, -1), vec3(0, 1, 1), vec3(0, -1, 1), vec3(0, -1, -1), vec3(0, 1, -1));

float lit_fraction(vec3 from_light_world, float distance, float cos_n) {
  // Steeper incidence needs more bias: depth changes faster across a texel.
  float bias = shadow_bias * (1.0 + 2.0 * (1.0 - cos_n));
  float spread = pcf_radius * distance;
  float lit = 0.0;
  for (int i = 0; i < 20; ++i) {
    float nearest = texture(shadow_map, from_light_world + spread * kPcf[i]).r * far_plane;
    lit += distance - bias <= nearest ? 1.0 : 0.0;
  }
  return lit / 20.0;
}

vec3 srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
  vec4 albedo = texture(g_albedo, uv);
  if (albedo.a < 0.5) {
    colour = vec4(linear_output ? vec3(0.0) : background, 1.0);
    return;
  }
  // A light probe of the overlay (preview_shape.frag): the light its SH
  // gives a white surface, whatever the passes; no direct light, no
  // occlusion, since neither is in the probe's light.
  if (albedo.a > 1.5) {
    vec3 e = texture(g_indirect, uv).rgb;
    colour = vec4(linear_output ? e : srgb(exposure * e), 1.0);
    return;
  }
  vec3 p = texture(g_position, uv).xyz;
  vec3 n = normalize(texture(g_normal, uv).xyz);
  vec3 light = vec3(0.0);
  if (show_direct) {
    vec3 to_light = light_view - p;
    float r2 = dot(to_light, to_light);
    float r = sqrt(r2);
    vec3 l = to_light / r;
    float cos_n = dot(n, l);
    if (cos_n > 0.0) {
      float spot = 1.0;
      if (light_is_spot == 1) {
        float t = clamp((dot(-l, spot_axis_view) - spot_cos.y) / max(1e-6, spot_cos.x - spot_cos.y),
                        0.0, 1.0);
        spot = t * t * (3.0 - 2.0 * t);
      }
      if (spot > 0.0) {
        vec3 from_light_world = view_to_world * (-to_light);
        float shadow = lit_fraction(from_light_world, r, cos_n);
        light += albedo.rgb * light_power * (spot * cos_n / r2) * shadow;
      }
    }
    light += texture(g_emission, uv).rgb;
  }
  if (show_indirect) {
    float open = use_ao ? texture(ao, uv).r : 1.0;
    light += albedo.rgb * texture(g_indirect, uv).rgb * open;
  }
  colour = vec4(linear_output ? light : srgb(exposure * light), 1.0);
}
