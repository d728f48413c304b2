// The run-time product of the compressed multi-bounce matrix on an OpenCL
// device (host side: core/runtime/compressed_transport_cl.cpp; layout of
// every buffer: core/runtime/compressed_transport_tables.h):
//   y[i] = sum_j T~[i][j] b[j]   for the stored (permuted) rows i,
// three colours at once (x, y, z of a float4; w unused and 0).
//
// One work-group per block row (4 matrix rows). Its work-items stride over
// the block columns, so neighbouring work-items read neighbouring blocks; each
// reads the 8-byte block, takes the 2-bit (BC1) or 3-bit (BC4) index of every
// texel from it and looks the value up in the block's palette (values after
// the inverse log step), accumulating 4 rows x 3 colours privately. The kept
// entries of the same 4 rows (the corrections kept - decoded) are spread over
// the same work-items and added to the same accumulators, then one tree
// reduction in local memory sums the work-items.
//
// Palettes on the device: with three stored channels (BC1), entry-major,
// (R, G, B, 0) per entry, 16 floats per block, so a texel is one float4
// load (the host has applied the colours' channel mapping); with one stored
// channel, the 4 (BC1) or 8 (BC4) values of the block, which every colour
// uses. (Entry-major measured 1.5-2x faster than three scalar loads per
// texel from the channel-major tables on PoCL's CPU device.)
//
// Compile-time options (-D), set by the host from the tables:
//   BC4               1 for BC4 blocks (8 levels, 3-bit indices), 0 for BC1
//   RGB_PALETTE       1 for entry-major (R, G, B, 0) palettes, 0 for one value
//   CORRECTION_WIDTH  correction values per kept position: 3 (R, G, B) or 1
// The local size must be a power of two (the reduction halves it).

#if RGB_PALETTE
#define PALETTE_FLOATS 16
#elif BC4
#define PALETTE_FLOATS 8
#else
#define PALETTE_FLOATS 4
#endif

// Palette index of texel t = 4 * row + column of a block.
inline uint texel_index(const uint2 block, const uint t) {
#if BC4
  // Bytes 2..7: 16 indices of 3 bits, little-endian.
  const ulong field = ((ulong)block.x >> 16) | ((ulong)block.y << 16);
  return (uint)(field >> (3 * t)) & 7u;
#else
  // Bytes 4..7: 16 indices of 2 bits, little-endian.
  return (block.y >> (2 * t)) & 3u;
#endif
}

inline float4 texel(__global const float* palette, const uint2 block, const uint t) {
  const uint e = texel_index(block, t);
#if RGB_PALETTE
  return vload4(e, palette);
#else
  return (float4)(palette[e]);
#endif
}

// One row of a block times the b of its 4 columns.
inline float4 block_row(__global const float* palette, const uint2 block, const uint r,
                        const float4 b0, const float4 b1, const float4 b2, const float4 b3) {
  return texel(palette, block, 4 * r) * b0 + texel(palette, block, 4 * r + 1) * b1 +
         texel(palette, block, 4 * r + 2) * b2 + texel(palette, block, 4 * r + 3) * b3;
}

__kernel void compressed_transport(const uint block_cols,
                                   __global const uint2* restrict blocks,
                                   __global const float* restrict palettes,
                                   __global const uint* restrict correction_ptr,
                                   __global const uint* restrict correction_index,
                                   __global const float* restrict correction_value,
                                   __global const float4* restrict b,
                                   __global float4* restrict y,
                                   __local float4* scratch) {  // 4 per work-item
  const uint I = get_group_id(0);
  const uint lid = get_local_id(0), lsize = get_local_size(0);
  float4 acc0 = (float4)(0.0f), acc1 = (float4)(0.0f), acc2 = (float4)(0.0f),
         acc3 = (float4)(0.0f);
  for (uint J = lid; J < block_cols; J += lsize) {
    const size_t at = (size_t)I * block_cols + J;
    const uint2 block = blocks[at];
    __global const float* palette = palettes + at * PALETTE_FLOATS;
    const float4 b0 = b[4 * J], b1 = b[4 * J + 1], b2 = b[4 * J + 2], b3 = b[4 * J + 3];
    acc0 += block_row(palette, block, 0, b0, b1, b2, b3);
    acc1 += block_row(palette, block, 1, b0, b1, b2, b3);
    acc2 += block_row(palette, block, 2, b0, b1, b2, b3);
    acc3 += block_row(palette, block, 3, b0, b1, b2, b3);
  }
  const uint end = correction_ptr[4 * I + 4];
  for (uint e = correction_ptr[4 * I] + lid; e < end; e += lsize) {
    const uint packed = correction_index[e];
#if CORRECTION_WIDTH == 3
    const float4 value = (float4)(vload3(e, correction_value), 0.0f);
#else
    const float4 value = (float4)(correction_value[e]);
#endif
    const float4 term = value * b[packed & 0x3FFFFFFFu];
    switch (packed >> 30) {
      case 0: acc0 += term; break;
      case 1: acc1 += term; break;
      case 2: acc2 += term; break;
      default: acc3 += term; break;
    }
  }
  scratch[4 * lid] = acc0;
  scratch[4 * lid + 1] = acc1;
  scratch[4 * lid + 2] = acc2;
  scratch[4 * lid + 3] = acc3;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint step = lsize / 2; step > 0; step /= 2) {
    if (lid < step)
      for (uint r = 0; r < 4; ++r) scratch[4 * lid + r] += scratch[4 * (lid + step) + r];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid < 4) y[4 * I + lid] = scratch[lid];
}
