#pragma once
// The published reordering of the compression method, kept exactly as printed
// so every other ordering can be compared with it: a greedy nearest-neighbour
// tour by L1 row distance, first over rows, then over columns.
//
// Pass 1: start at row 0; repeatedly go to the unvisited row with the smallest
//   L1 distance to the current row (sum over all columns and channels of
//   |a - b| on the uint8 codes); ties go to the smallest row index. The visit
//   order p1 reorders rows AND columns: image1[i][j] = image[p1[i]][p1[j]].
// Pass 2: the same over the columns of image1 (start at column 0 of image1,
//   ties to the smallest column index of image1), giving p2; the result is
//   compose(p1, p2), i.e. image2[i][j] = image[p[i]][p[j]] with p[i] = p1[p2[i]].
//
// Cost: n^2 / 2 row distances of n * channels bytes each, O(n^3): 6.6 TB
// read per pass at n = 16384, about 18 minutes at the ~6 GB/s one core
// streams here. Two exact shortcuts: SIMD sums of absolute differences
// (psadbw) that stop once a candidate is already farther than the best one
// found, with the best seeded from the likely neighbours (the previous
// runner-up, the next index); they read ~1/10 of each row. Measured on one
// core of the shared machine, random patch order, one pass: 0.35 s at
// n = 2048, 2.6 s at 4096, 24 s at 8192, 122 s at 16384 (two passes take
// twice as long). Large steps search in parallel (OpenMP); the result is the
// plain loop's, whatever the thread count. Pass 2 makes a transposed copy of
// the image (n * n * channels bytes). Use our_ordering() for large n.
#include <cstddef>
#include <cstdint>

#include "compress/ordering_permutation.h"

namespace bounce {

// Sum of |a[k] - b[k]| over k < length; AVX2 when the CPU has it.
std::uint64_t l1_distance(const std::uint8_t* a, const std::uint8_t* b, std::size_t length);

// Greedy nearest-neighbour visit order of `count` byte rows (row k starts at
// rows + k * row_bytes), starting at row 0, ties to the smaller index.
Permutation greedy_l1_tour(const std::uint8_t* rows, std::size_t count, std::size_t row_bytes);

// The paper's ordering with 1 or 2 passes (throws bounce::Error otherwise).
Permutation paper_ordering(const std::uint8_t* image, std::size_t n, std::size_t channels,
                           int passes);

}  // namespace bounce
