#version 330 core
in vec3 view_position;
in vec3 view_normal;
in vec3 frag_albedo;
in vec3 frag_emission;
in vec3 frag_indirect;

layout(location = 0) out vec3 g_position;  // RGB16F, view space
layout(location = 1) out vec3 g_normal;    // RGB16F, view space, unit
layout(location = 2) out vec4 g_albedo;    // RGBA16F, alpha 1 = geometry here
layout(location = 3) out vec3 g_emission;  // RGB16F
layout(location = 4) out vec3 g_indirect;  // RGB16F

void main() {
  g_position = view_position;
  g_normal = normalize(view_normal);
  g_albedo = vec4(frag_albedo, 1.0);
  g_emission = frag_emission;
  g_indirect = frag_indirect;
}
