#pragma once
// The run-time product on the dense float32 matrices, with OpenBLAS: the
// baseline the compressed product (runtime/compressed_transport.h) is
// measured against, and the product for matrices stored dense (--codec dense).
// It streams 4 n^2 bytes per colour and is bound by memory bandwidth
// (~45-50 GB/s on the development machine).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// indirect[p]_k = (T_c(k) b_k)[p], k = R, G, B, with c = channel_of_rgb and
// `matrices[c]` stored channel c, row-major n x n in patch order (one matrix:
// all colours use it, whatever channel_of_rgb says). One sgemv per colour.
// indirect is resized only when its size differs. Throws bounce::Error on
// size or channel mismatches.
void dense_indirect(const std::vector<const float*>& matrices, std::size_t n,
                    const std::array<int, 3>& channel_of_rgb, const std::vector<glm::vec3>& b,
                    std::vector<glm::vec3>& indirect);
// The same into caller-owned memory (e.g. a frame graph's arena): both spans
// n entries (throws bounce::Error otherwise), not overlapping.
void dense_indirect(const std::vector<const float*>& matrices, std::size_t n,
                    const std::array<int, 3>& channel_of_rgb, std::span<const glm::vec3> b,
                    std::span<glm::vec3> indirect);

}  // namespace bounce
