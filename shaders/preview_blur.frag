#version 330 core
// Paper 002, section 3: an N x N box filter over the occlusion map. N = 4
// here, the size of the tiled noise texture: every 4 x 4 window then holds
// each kernel rotation exactly once, so the rotation noise averages out
// completely on a flat surface.
in vec2 uv;

uniform sampler2D ao;

out float open;

void main() {
  vec2 texel = 1.0 / vec2(textureSize(ao, 0));
  float sum = 0.0;
  for (int y = -2; y < 2; ++y)
    for (int x = -2; x < 2; ++x) sum += texture(ao, uv + vec2(float(x), float(y)) * texel).r;
  open = sum / 16.0;
}
