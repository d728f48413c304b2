#include "runtime/gather_near_merge.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

namespace bounce {

MergedNearSources merge_near_sources(const std::vector<ChunkRows>& chunks,
                                     const SurfacePatchLookup& lookup, FinalGather& g) {
  MergedNearSources m;
  m.number.resize(chunks.size());
  std::unordered_map<SurfaceCellKey, std::uint32_t, SurfaceCellKeyHash> index;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    const ChunkNearSources& cn = chunks[c].near;
    for (std::size_t l = 0; l < cn.keys.size(); ++l) {
      const auto [it, added] = index.try_emplace(cn.keys[l], static_cast<std::uint32_t>(m.size()));
      if (added) {
        m.position_sum.emplace_back(0.0);
        m.albedo_sum.emplace_back(0.0);
        m.first.push_back(cn.first[l]);
        m.count.push_back(0);
        m.sample.push_back(static_cast<std::uint32_t>(cn.keys[l].sample));
        g.near.normal.push_back(cn.normal[l]);
        g.near.patch.push_back(static_cast<std::uint32_t>(
            lookup.patch_of(static_cast<std::uint32_t>(cn.keys[l].sample))));
      }
      m.position_sum[it->second] += cn.position_sum[l];
      m.albedo_sum[it->second] += cn.albedo_sum[l];
      m.count[it->second] += cn.count[l];
      m.number[c].push_back(it->second);
    }
  }
  for (std::size_t k = 0; k < m.size(); ++k)
    g.near.albedo.push_back(glm::vec3(m.albedo_sum[k] / static_cast<double>(m.count[k])));
  return m;
}

void place_near_sources(const RayTracer& tracer, float offset, const MergedNearSources& merged,
                        FinalGather& g) {
  g.near.position.resize(merged.size());
#pragma omp parallel for schedule(static, 1024)
  for (std::int64_t ki = 0; ki < static_cast<std::int64_t>(merged.size()); ++ki) {
    const auto k = static_cast<std::size_t>(ki);
    const glm::vec3 mean(merged.position_sum[k] / static_cast<double>(merged.count[k]));
    const glm::vec3 lift = offset * g.near.normal[k];
    const glm::vec3 to_mean = mean - merged.first[k];
    const bool blocked = glm::dot(to_mean, to_mean) > 0.0f &&
                         tracer.occluded(merged.first[k] + lift, to_mean, 0.0f, 1.0f);
    g.near.position[k] = blocked ? merged.first[k] : mean;
  }
}

std::vector<std::uint32_t> drop_rare_near_sources(const MergedNearSources& merged, int min_rays,
                                                  FinalGather& g) {
  std::vector<std::uint32_t> near_id(merged.size());
  NearSources kept;
  for (std::size_t k = 0; k < merged.size(); ++k) {
    if (merged.count[k] < static_cast<std::uint32_t>(std::max(1, min_rays))) {
      near_id[k] = kDroppedNearSource;
      g.rays_near -= merged.count[k];
      continue;
    }
    near_id[k] = static_cast<std::uint32_t>(kept.size());
    kept.position.push_back(g.near.position[k]);
    kept.normal.push_back(g.near.normal[k]);
    kept.albedo.push_back(g.near.albedo[k]);
    kept.patch.push_back(g.near.patch[k]);
  }
  g.near = std::move(kept);
  return near_id;
}

namespace {

// What renumbering the rows reads, and the seen rays it adds to.
struct RowRewrite {
  const MergedNearSources& merged;
  const std::vector<std::uint32_t>& near_id;
  const SurfacePatchLookup& lookup;
  const FinalGather& g;
  std::size_t rays, patches, sample_base, near_base;
  std::vector<std::uint64_t>& seen_rays;
  std::vector<std::uint64_t>& cluster_rays;
};

// An entry's weight as the whole number of the point's rays it is.
std::uint32_t hits_of(float weight, std::size_t rays) {
  return static_cast<std::uint32_t>(
      std::lround(static_cast<double>(weight) * static_cast<double>(rays)));
}

// `hits` rays of a dropped near source on `sample` join the row (which
// starts at row_begin) as renumber_rows() says.
void fold_into_row(RowRewrite& r, std::uint32_t sample, std::uint32_t hits, std::size_t row_begin,
                   std::vector<std::uint32_t>& source, std::vector<float>& weight) {
  const auto p = static_cast<std::uint32_t>(r.lookup.patch_of(sample));
  const std::uint32_t targets[3] = {
      static_cast<std::uint32_t>(r.sample_base + sample), p,
      static_cast<std::uint32_t>(r.patches) + r.g.cluster_of_patch[p]};
  std::size_t found = source.size();
  for (const std::uint32_t t : targets) {
    for (std::size_t e = row_begin; e < source.size() && found == source.size(); ++e)
      if (source[e] == t) found = e;
    if (found != source.size()) break;
  }
  if (found == source.size()) {
    source.push_back(p);
    weight.push_back(0.0f);
  }
  if (source[found] < r.sample_base && !r.seen_rays.empty()) {
    r.seen_rays[sample] += hits;
    if (source[found] >= r.patches) r.cluster_rays[p] += hits;
  }
  const double per_ray = 1.0 / static_cast<double>(r.rays);
  weight[found] = static_cast<float>(per_ray * (hits_of(weight[found], r.rays) + hits));
}

void renumber_chunk(RowRewrite& r, const std::vector<std::uint32_t>& number, ChunkRows& rows) {
  std::vector<std::uint32_t> source;
  std::vector<float> weight;
  source.reserve(rows.source.size());
  weight.reserve(rows.weight.size());
  std::size_t at = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> folded;  // (sample, hits) of a row
  for (std::uint32_t& row_count : rows.count) {
    const std::size_t row_begin = source.size();
    folded.clear();
    for (std::size_t k = at; k < at + row_count; ++k) {
      std::uint32_t src = rows.source[k];
      if (src & kChunkNearSource) {
        const std::uint32_t merged = number[src & ~kChunkNearSource];
        if (r.near_id[merged] == kDroppedNearSource) {
          folded.emplace_back(r.merged.sample[merged], hits_of(rows.weight[k], r.rays));
          continue;
        }
        src = static_cast<std::uint32_t>(r.near_base + r.near_id[merged]);
      }
      source.push_back(src);
      weight.push_back(rows.weight[k]);
    }
    for (const auto& [sample, hits] : folded)
      fold_into_row(r, sample, hits, row_begin, source, weight);
    at += row_count;
    row_count = static_cast<std::uint32_t>(source.size() - row_begin);
  }
  rows.source = std::move(source);
  rows.weight = std::move(weight);
}

}  // namespace

void renumber_rows(TracedRows& traced, const MergedNearSources& merged,
                   const std::vector<std::uint32_t>& near_id, const GatherPlan& plan,
                   const SurfacePatchLookup& lookup, const FinalGather& g) {
  RowRewrite r{merged,           near_id,
               lookup,           g,
               plan.rays,        plan.patches,
               plan.sample_base, plan.patches + g.clusters + g.samples,
               traced.seen_rays, traced.cluster_rays};
  for (std::size_t c = 0; c < traced.chunks.size(); ++c)
    renumber_chunk(r, merged.number[c], traced.chunks[c]);
}

}  // namespace bounce
