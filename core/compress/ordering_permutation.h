#pragma once
// Symmetric reordering of the quantised transport image, as the
// published compression does: ONE permutation is applied to rows and columns, so a patch keeps the
// same index as receiver and as source and the run-time product only needs the
// light vector permuted once.
//
// Convention used everywhere in compress/ordering*: a permutation p lists, for
// each new index, the old index it takes its data from:
//   permuted[i][j] = image[p[i]][p[j]]
// This is also what matrix_picture() expects.
//
// Image layout: n x n pixels, row-major, `channels` interleaved uint8 codes
// per pixel (T_R, T_G, T_B for the transport image).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce {

using Permutation = std::vector<std::uint32_t>;

// 0, 1, ..., n-1.
Permutation identity_permutation(std::size_t n);

// True when p holds each of 0..p.size()-1 exactly once.
bool is_bijection(const Permutation& p);

// q with q[p[i]] = i: the new index of each old index.
Permutation inverse(const Permutation& p);

// Reordering by `first`, then reordering the result by `second`, equals one
// reordering by compose(first, second)[i] = first[second[i]]:
//   apply_symmetric(apply_symmetric(x, first), second)
//     == apply_symmetric(x, compose(first, second)).
Permutation compose(const Permutation& first, const Permutation& second);

// permuted[i][j] = image[p[i]][p[j]] (all channels). Throws bounce::Error if p
// is not a bijection of 0..n-1.
std::vector<std::uint8_t> apply_symmetric(const std::uint8_t* image, std::size_t n,
                                          std::size_t channels, const Permutation& p);

// The exact inverse of apply_symmetric with the same p:
//   unapply_symmetric(apply_symmetric(x, p), p) == x, bit for bit.
std::vector<std::uint8_t> unapply_symmetric(const std::uint8_t* permuted, std::size_t n,
                                            std::size_t channels, const Permutation& p);

}  // namespace bounce
