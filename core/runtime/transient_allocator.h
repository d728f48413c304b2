#pragma once
// Transient-memory aliasing for the frame graph:
// buffers whose lifetimes (the passes between the first and the last that
// touch them) do not overlap may share memory. Placing them is interval-graph
// colouring with sizes (dynamic storage allocation, NP-hard in general); we
// use the usual greedy: largest first (ties: earliest first), each at the
// lowest aligned offset where it overlaps no already placed buffer that is
// live at the same time. For equal sizes this is first-fit colouring of an
// interval graph in order of start, which is optimal: the peak is then the
// largest number of buffers live at once times the size.
#include <cstddef>
#include <vector>

namespace bounce {

struct TransientLifetime {
  std::size_t first = 0, last = 0;  // passes, inclusive; first <= last
  std::size_t bytes = 0;
};

struct TransientPlacement {
  std::vector<std::size_t> offsets;  // one per lifetime, in the input order
  std::size_t peak = 0;              // arena size: max over offset + size
};

// Offsets are multiples of `alignment` (>= 1), sizes rounded up to it.
// Throws bounce::Error on first > last or alignment 0.
TransientPlacement place_transients(const std::vector<TransientLifetime>& lifetimes,
                                    std::size_t alignment = 256);

// The lower bound of any placement: the largest sum of (aligned) sizes live
// during one pass.
std::size_t max_live_bytes(const std::vector<TransientLifetime>& lifetimes,
                           std::size_t alignment = 256);

// Without aliasing: every buffer its own memory (sum of aligned sizes).
std::size_t total_bytes(const std::vector<TransientLifetime>& lifetimes,
                        std::size_t alignment = 256);

}  // namespace bounce
