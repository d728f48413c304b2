// Temporal radiosity on an OpenCL device (host side:
// core/dynamic/temporal_radiosity_cl.cpp; the method and the C++ path it
// must match: core/dynamic/temporal_radiosity.h). One work-item per patch p:
// for every stored channel c it draws `samples` columns from the alias table
// of row p of T_c with the counter-based hash of core/dynamic/counter_hash.h
// (same constants, same order of folding, so both paths draw the same
// columns), sums b over them in sample order, scales by row_sum / samples,
// then blends into the history in place:
//   history[p] = weight * history[p] + (1 - weight) * b_new[p].
// Vectors are float4 (R, G, B, 0). colour_channel_{r,g,b}: the stored channel
// each colour reads.
#pragma OPENCL FP_CONTRACT OFF

// core/dynamic/alias_table.h's AliasEntry: 8 bytes, one slot per draw.
typedef struct {
  float probability;
  uint alias;
} AliasEntry;

uint hash32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// counter_hash.h's row_stream: sample s of the row is hash32(stream ^ s).
uint row_stream(uint seed, uint frame, uint row, uint lane) {
  uint h = hash32(seed ^ (lane * 0x9e3779b9u));
  h = hash32(h ^ frame);
  return hash32(h ^ row);
}

__kernel void temporal_radiosity(uint n, uint channels, int colour_channel_r,
                                 int colour_channel_g, int colour_channel_b, uint samples,
                                 uint seed, uint frame, float weight,
                                 __global const AliasEntry* table,
                                 __global const float* row_sum, __global const float4* b,
                                 __global float4* history, __global float4* b_new) {
  const uint p = get_global_id(0);
  if (p >= n) return;
  float4 estimate = (float4)(0.0f);
  for (uint c = 0; c < channels; ++c) {
    const float4 mask = (float4)(colour_channel_r == (int)c ? 1.0f : 0.0f,
                                 colour_channel_g == (int)c ? 1.0f : 0.0f,
                                 colour_channel_b == (int)c ? 1.0f : 0.0f, 0.0f);
    if (mask.x == 0.0f && mask.y == 0.0f && mask.z == 0.0f) continue;
    const ulong row = ((ulong)c * n + p) * n;
    const uint lane = 2u * c;
    float4 acc = (float4)(0.0f);
    const uint index_stream = row_stream(seed, frame, p, lane);
    const uint coin_stream = row_stream(seed, frame, p, lane + 1u);
    for (uint s = 0; s < samples; ++s) {
      const uint i = mul_hi(hash32(index_stream ^ s), n);
      const float u = (float)(hash32(coin_stream ^ s) >> 8) * (1.0f / 16777216.0f);
      const AliasEntry slot = table[row + i];
      const uint q = u < slot.probability ? i : slot.alias;
      acc += b[q];
    }
    const float scale = row_sum[(ulong)c * n + p] / (float)samples;
    estimate += mask * (acc * scale);
  }
  b_new[p] = estimate;
  history[p] = weight * history[p] + (1.0f - weight) * estimate;
}
