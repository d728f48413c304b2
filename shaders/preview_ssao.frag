#version 330 core
// Screen-space ambient occlusion (docs/studio.md, the preview). For the point
// P (view space, from G_pos) with normal N (from G_norm): the tangent-space
// hemisphere kernel S_t (z >= 0) is turned into view space by
// M_tbn = (T B N), T from the per-pixel random vector V_r by Gram-Schmidt,
// B = N x T; each sample A_t = P + R S_t is projected to the screen, the
// surface point P_t seen through that pixel is read from G_pos, and A_t
// counts as inside an object when P_t.z >= A_t.z + delta (the surface is
// nearer the eye than the sample). k = inside / m is the occlusion; this
// pass writes 1 - k, the share of the hemisphere that is open.
//
// One addition to the paper: a sample whose P_t lies more than R in front of
// P (an object far in front of the wall) counts with weight
// smoothstep(0, 1, R / |P.z - P_t.z|), so silhouettes do not throw dark halos
// on what lies far behind them.
in vec2 uv;

uniform sampler2D g_position;
uniform sampler2D g_normal;
uniform sampler2D g_albedo;  // alpha 0: background
uniform sampler2D noise;     // V_r per pixel, tiled (xy in [-1, 1], z = 0)
uniform vec3 kernel[64];
uniform int kernel_size;  // m >= 32
uniform float radius;     // R
uniform float delta;      // the paper's bias against self-occlusion
uniform mat4 projection;
uniform vec2 noise_scale;  // viewport size / noise size

out float open;

void main() {
  if (texture(g_albedo, uv).a < 0.5) {
    open = 1.0;
    return;
  }
  vec3 p = texture(g_position, uv).xyz;
  vec3 n = normalize(texture(g_normal, uv).xyz);
  vec3 vr = vec3(texture(noise, uv * noise_scale).xy, 0.0);
  vec3 t = vr - n * dot(vr, n);
  if (dot(t, t) < 1e-8) t = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  t = normalize(t - n * dot(t, n));
  vec3 b = cross(n, t);
  mat3 tbn = mat3(t, b, n);
  float inside = 0.0;
  for (int i = 0; i < kernel_size; ++i) {
    vec3 a = p + radius * (tbn * kernel[i]);
    vec4 clip = projection * vec4(a, 1.0);
    vec2 screen = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(screen, vec2(0.0))) || any(greaterThan(screen, vec2(1.0)))) continue;
    if (texture(g_albedo, screen).a < 0.5) continue;  // background never occludes
    float surface_z = texture(g_position, screen).z;
    float range = smoothstep(0.0, 1.0, radius / max(abs(p.z - surface_z), 1e-6));
    inside += (surface_z >= a.z + delta ? 1.0 : 0.0) * range;
  }
  open = 1.0 - inside / float(kernel_size);
}
