#include "runtime/gather_spots.h"

#include <algorithm>
#include <vector>

namespace bounce {

void add_to_spot_cell(SpotCells& cells, const SurfaceCellKey& key, const SpotCell& cell) {
  const auto [it, added] = cells.try_emplace(key, cell);
  if (added) return;
  it->second.rays += cell.rays;
  if (cell.first < it->second.first) {
    it->second.first = cell.first;
    it->second.position = cell.position;
    it->second.normal = cell.normal;
  }
}

void make_spots(const SurfacePatchLookup& lookup, const SpotCells& cells, int spots,
                FinalGather& g) {
  struct Candidate {
    std::uint32_t sample;
    SpotCell cell;
  };
  std::vector<Candidate> all;
  all.reserve(cells.size());
  for (const auto& [key, cell] : cells)
    all.push_back({static_cast<std::uint32_t>(key.sample), cell});
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
