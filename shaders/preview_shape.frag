#version 330 core
// The preview's shapes into the same G-buffer targets as the scene
// (preview_gbuffer.frag's outputs). The SH irradiance goes to the indirect
// target. The composite lights the moving object as it lights the walls,
// albedo x (direct + indirect x occlusion); a probe of the overlay is marked
// by an albedo alpha of 2, and the composite shows its irradiance as is,
// the light a white surface would send out there.
in vec3 view_position;
in vec3 view_normal;
in vec3 frag_irradiance;
flat in vec4 frag_albedo_probe;  // rgb albedo, a: 1 for a probe of the overlay

layout(location = 0) out vec3 g_position;
layout(location = 1) out vec3 g_normal;
layout(location = 2) out vec4 g_albedo;
layout(location = 3) out vec3 g_emission;
layout(location = 4) out vec3 g_indirect;

void main() {
  g_position = view_position;
  g_normal = normalize(view_normal);
  g_albedo = vec4(frag_albedo_probe.rgb, frag_albedo_probe.a > 0.5 ? 2.0 : 1.0);
  g_emission = vec3(0.0);
  g_indirect = frag_irradiance;
}
