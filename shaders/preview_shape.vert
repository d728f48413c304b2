#version 330 core
// The preview's shapes (views/preview_shapes.h) into the G-buffer: a mesh
// of unit size instanced at each centre and radius, with the irradiance its
// SH L2 coefficients give for the surface normal, evaluated per vertex (SH
// L2 varies too slowly for per-pixel evaluation to show). The
// basis and order are runtime/light_probes.h's: E(n) = sum_j c_j Y_j(n),
// the irradiance of light reflected at least once.
layout(location = 0) in vec3 unit;      // a point of the mesh, within the unit ball
layout(location = 12) in vec3 normal;  // unit
layout(location = 1) in vec4 centre_radius;
layout(location = 2) in vec4 albedo_probe;
layout(location = 3) in vec3 sh0;
layout(location = 4) in vec3 sh1;
layout(location = 5) in vec3 sh2;
layout(location = 6) in vec3 sh3;
layout(location = 7) in vec3 sh4;
layout(location = 8) in vec3 sh5;
layout(location = 9) in vec3 sh6;
layout(location = 10) in vec3 sh7;
layout(location = 11) in vec3 sh8;

uniform mat4 view;
uniform mat4 projection;

out vec3 view_position;
out vec3 view_normal;
out vec3 frag_irradiance;
flat out vec4 frag_albedo_probe;

vec3 sh_irradiance(vec3 n) {
  return sh0 * 0.282095 + sh1 * (0.488603 * n.y) + sh2 * (0.488603 * n.z) +
         sh3 * (0.488603 * n.x) + sh4 * (1.092548 * n.x * n.y) + sh5 * (1.092548 * n.y * n.z) +
         sh6 * (0.315392 * (3.0 * n.z * n.z - 1.0)) + sh7 * (1.092548 * n.x * n.z) +
         sh8 * (0.546274 * (n.x * n.x - n.y * n.y));
}

void main() {
  vec4 p = view * vec4(centre_radius.xyz + centre_radius.w * unit, 1.0);
  view_position = p.xyz;
  view_normal = mat3(view) * normal;
  // A fit can dip below zero where little light arrives: no negative light.
  frag_irradiance = max(sh_irradiance(normal), vec3(0.0));
  frag_albedo_probe = albedo_probe;
  gl_Position = projection * p;
}
