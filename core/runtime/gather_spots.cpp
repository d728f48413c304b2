#include "runtime/gather_spots.h"

#include <algorithm>
#include <vector>

namespace bounce {

void SpotCells::add(const SurfaceCellKey& key, const SpotCell& cell) {
  const auto s = static_cast<std::size_t>(key.sample);
  if (s >= by_sample_.size()) by_sample_.resize(s + 1);
  auto& cells = by_sample_[s];
  const auto it =
      std::find_if(cells.begin(), cells.end(), [&](const auto& c) { return c.first == key; });
  if (it == cells.end()) {
    cells.emplace_back(key, cell);
    ++size_;
    return;
  }
  // A found cell moves one place forward: the cells most rays land in end up
  // first, where the scan finds them soonest (the order is not a result).
  auto found = it;
  if (found != cells.begin()) {
    std::iter_swap(found, found - 1);
    --found;
  }
  SpotCell& into = found->second;
  into.rays += cell.rays;
  if (cell.first < into.first) {
    into.first = cell.first;
    into.position = cell.position;
    into.normal = cell.normal;
  }
}

void SpotCells::merge(const SpotCells& other) {
  other.for_each([&](const SurfaceCellKey& key, const SpotCell& cell) { add(key, cell); });
}

void make_spots(const SurfacePatchLookup& lookup, const SpotCells& cells, int spots,
                FinalGather& g) {
  struct Candidate {
    std::uint32_t sample;
    SpotCell cell;
  };
  std::vector<Candidate> all;
  all.reserve(cells.size());
  cells.for_each([&](const SurfaceCellKey& key, const SpotCell& cell) {
    all.push_back({static_cast<std::uint32_t>(key.sample), cell});
  });
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
    if (a.sample != b.sample) return a.sample < b.sample;
    if (a.cell.rays != b.cell.rays) return a.cell.rays > b.cell.rays;
    return a.cell.first < b.cell.first;
  });
  const SampleSet& samples = lookup.samples();
  g.spot_first.assign(g.samples + 1, 0);
  std::vector<std::uint32_t> count(g.samples, 0);
  std::size_t at = 0;
  while (at < all.size()) {
    const std::uint32_t s = all[at].sample;
    std::size_t end = at;
    while (end < all.size() && all[end].sample == s) ++end;
    const std::size_t kept = std::min(end - at, static_cast<std::size_t>(spots));
    std::uint64_t total = 0;
    for (std::size_t k = at; k < at + kept; ++k) total += all[k].cell.rays;
    for (std::size_t k = at; k < at + kept; ++k) {
      g.spot_weight.push_back(
          static_cast<float>(static_cast<double>(all[k].cell.rays) / static_cast<double>(total)));
      g.near.position.push_back(all[k].cell.position);
      g.near.normal.push_back(all[k].cell.normal);
      g.near.albedo.push_back(samples.samples[s].albedo);
      g.near.patch.push_back(static_cast<std::uint32_t>(lookup.patch_of(s)));
    }
    count[s] = static_cast<std::uint32_t>(kept);
    at = end;
  }
  for (std::size_t s = 0; s < g.samples; ++s) g.spot_first[s + 1] = g.spot_first[s] + count[s];
  g.near.spot_count = g.spot_first.back();
}

}  // namespace bounce
