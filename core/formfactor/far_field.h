#pragma once
// The unoccluded far-field part of the form factors: for every
// patch pair (p, q >= p), the sum over the far-field representative points
// i of p and j of q of A_i A_j cos_i cos_j / (pi r^2) for points that face
// each other, skipping i == j when q == p. It is the sum compute_form_factors
// (formfactor/form_factors.cpp) forms inline as `far_sum`, in the same order
// and precision, factored out here so that the C++ path and the OpenCL one
// (formfactor/far_field_cl.h) can be measured and checked against each other.
// compute_form_factors keeps its own loop: it builds the visibility-ray
// candidates in the same pass, so calling this would not be a drop-in.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// The far points of all patches, flattened: patch p owns the points
// [offsets[p], offsets[p + 1]).
struct FarPoints {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit
  std::vector<float> areas;
  std::vector<std::uint32_t> offsets;  // patches() + 1 entries, offsets[0] == 0

  std::size_t patches() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

// Throws bounce::Error unless the offsets are non-decreasing from 0 and the
// arrays have offsets.back() entries each.
void validate(const FarPoints& points);

// The far-field sums, n x n row-major (n = points.patches()): sums[p * n + q]
// for q >= p; the entries below the diagonal are 0. OpenMP over rows.
std::vector<float> far_field_sums(const FarPoints& points);

}  // namespace bounce
