#include "runtime/transient_allocator.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "base/error.h"

namespace bounce {

namespace {

std::size_t round_up(std::size_t bytes, std::size_t alignment) {
  return (bytes + alignment - 1) / alignment * alignment;
}

void check(const std::vector<TransientLifetime>& lifetimes, std::size_t alignment) {
  if (alignment == 0) throw Error("transient allocator", "alignment must be at least 1");
  for (std::size_t i = 0; i < lifetimes.size(); ++i)
    if (lifetimes[i].first > lifetimes[i].last)
      throw Error("transient allocator", "buffer " + std::to_string(i) + " ends before it starts");
}

bool overlap_in_time(const TransientLifetime& a, const TransientLifetime& b) {
  return a.first <= b.last && b.first <= a.last;
}

}  // namespace

TransientPlacement place_transients(const std::vector<TransientLifetime>& lifetimes,
                                    std::size_t alignment) {
  check(lifetimes, alignment);
  const std::size_t count = lifetimes.size();
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (lifetimes[a].bytes != lifetimes[b].bytes) return lifetimes[a].bytes > lifetimes[b].bytes;
    return lifetimes[a].first < lifetimes[b].first;
  });
  TransientPlacement out;
  out.offsets.assign(count, 0);
  std::vector<std::size_t> placed;
  std::vector<std::pair<std::size_t, std::size_t>> busy;  // [begin, end) in memory
  for (std::size_t i : order) {
    const std::size_t size = round_up(lifetimes[i].bytes, alignment);
    busy.clear();
    for (std::size_t j : placed)
      if (overlap_in_time(lifetimes[i], lifetimes[j]))
        busy.emplace_back(out.offsets[j], out.offsets[j] + round_up(lifetimes[j].bytes, alignment));
    std::sort(busy.begin(), busy.end());
    // The lowest gap that fits: scan the busy ranges in offset order.
    std::size_t offset = 0;
    for (const auto& [begin, end] : busy) {
      if (begin >= offset + size) break;
      if (end > offset) offset = end;  // ends are multiples of alignment
    }
    out.offsets[i] = offset;
    out.peak = std::max(out.peak, offset + size);
    placed.push_back(i);
  }
  return out;
}

std::size_t max_live_bytes(const std::vector<TransientLifetime>& lifetimes, std::size_t alignment) {
  check(lifetimes, alignment);
  std::size_t passes = 0;
  for (const TransientLifetime& l : lifetimes) passes = std::max(passes, l.last + 1);
  std::size_t best = 0;
  for (std::size_t pass = 0; pass < passes; ++pass) {
    std::size_t live = 0;
    for (const TransientLifetime& l : lifetimes)
      if (l.first <= pass && pass <= l.last) live += round_up(l.bytes, alignment);
    best = std::max(best, live);
  }
  return best;
}

std::size_t total_bytes(const std::vector<TransientLifetime>& lifetimes, std::size_t alignment) {
  check(lifetimes, alignment);
  std::size_t sum = 0;
  for (const TransientLifetime& l : lifetimes) sum += round_up(l.bytes, alignment);
  return sum;
}

}  // namespace bounce
