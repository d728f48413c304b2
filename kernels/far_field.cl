// The unoccluded far-field sums of the form factors on an OpenCL device
// (host side: core/formfactor/far_field_cl.cpp; the C++ reference and the
// meaning of every buffer: core/formfactor/far_field.h):
//   sums[p * n + q] = sum_{i in p, j in q, (q != p or i != j)}
//                     A_i A_j cos_i cos_j / (pi r^2)   for facing points,
// for q >= p, and 0 below the diagonal.
//
// One work-item per (p, q): dimension 0 is q, so neighbouring work-items
// read neighbouring patches' points and write neighbouring sums. The range is
// the whole square (rounded up to the work-group size): the items below the
// diagonal write their 0 and stop, which saves the host a fill of the
// buffer.
//
// Positions and normals are packed floats, 3 per point (vload3), not float3
// arrays, whose elements take 16 bytes on the device.

// The C++ path rounds after every operation (no FMA on x86-64 without
// -mfma); contracting here would make the two differ in the last bits.
#pragma OPENCL FP_CONTRACT OFF

// As far_exchange in form_factors.cpp, operation for operation.
inline float exchange(const float3 pa, const float3 na, const float aa, const float3 pb,
                      const float3 nb, const float ab) {
  const float3 d = pb - pa;
  const float r2 = d.x * d.x + d.y * d.y + d.z * d.z;
  const float fa = na.x * d.x + na.y * d.y + na.z * d.z;
  const float fb = -(nb.x * d.x + nb.y * d.y + nb.z * d.z);
  if (fa <= 0.0f || fb <= 0.0f || !(r2 > 0.0f)) return 0.0f;
  return aa * ab * fa * fb / (M_PI_F * r2 * r2);
}

__kernel void far_field(const uint n, __global const float* restrict positions,
                        __global const float* restrict normals,
                        __global const float* restrict areas,
                        __global const uint* restrict offsets, __global float* restrict sums) {
  const uint q = (uint)get_global_id(0), p = (uint)get_global_id(1);
  if (q >= n || p >= n) return;
  const size_t at = (size_t)p * n + q;
  if (q < p) {
    sums[at] = 0.0f;
    return;
  }
  const uint p0 = offsets[p], p1 = offsets[p + 1], q0 = offsets[q], q1 = offsets[q + 1];
  float sum = 0.0f;
  for (uint i = p0; i < p1; ++i) {
    const float3 pa = vload3(i, positions), na = vload3(i, normals);
    const float aa = areas[i];
    for (uint j = q0; j < q1; ++j) {
      if (q == p && i == j) continue;  // a point does not exchange with itself
      const float w = exchange(pa, na, aa, vload3(j, positions), vload3(j, normals), areas[j]);
      if (w <= 0.0f) continue;
      sum += w;
    }
  }
  sums[at] = sum;
}
