#include "patches/clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

#include "patches/sample_separation.h"
#include "patches/target_exchange.h"

namespace bounce {

namespace {

struct Targets {
  std::vector<std::uint32_t> of_voxel;  // target index of each occupied voxel
  std::vector<std::vector<std::uint32_t>> samples;
  std::vector<float> area;
  std::vector<std::uint32_t> representative;  // sample index
  std::uint32_t block = 1;
};

Targets make_targets(const Voxelization& vox, const SampleSet& set, std::size_t max_targets) {
  Targets t;
  // Coarsen voxels into blocks until the number of targets fits.
  for (t.block = 1;; t.block *= 2) {
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    t.of_voxel.assign(vox.voxels.size(), 0);
    for (std::size_t v = 0; v < vox.voxels.size(); ++v) {
      const glm::ivec3 c = vox.voxels[v].coord / static_cast<int>(t.block);
      const std::uint64_t key = (static_cast<std::uint64_t>(c.z) << 42) |
                                (static_cast<std::uint64_t>(c.y) << 21) |
                                static_cast<std::uint64_t>(c.x);
      auto [it, inserted] = index.emplace(key, static_cast<std::uint32_t>(index.size()));
      t.of_voxel[v] = it->second;
    }
    if (index.size() <= max_targets || t.block >= 1u << 20) {
      t.samples.assign(index.size(), {});
      break;
    }
  }
  for (std::size_t s = 0; s < set.samples.size(); ++s)
    t.samples[t.of_voxel[set.samples[s].voxel]].push_back(static_cast<std::uint32_t>(s));
  // Voxels whose surface no ray hit leave targets without samples: drop them
  // (their zero area would divide the column term by zero).
  std::vector<std::uint32_t> renumber(t.samples.size(), 0);
  std::vector<std::vector<std::uint32_t>> kept;
  for (std::size_t k = 0; k < t.samples.size(); ++k) {
    renumber[k] = static_cast<std::uint32_t>(kept.size());
    if (!t.samples[k].empty()) kept.push_back(std::move(t.samples[k]));
  }
  t.samples = std::move(kept);
  for (auto& target : t.of_voxel) target = renumber[target];
  t.area.assign(t.samples.size(), 0.0f);
  t.representative.assign(t.samples.size(), 0);
  for (std::size_t k = 0; k < t.samples.size(); ++k) {
    glm::vec3 centroid(0.0f);
    for (std::uint32_t s : t.samples[k]) {
      t.area[k] += set.samples[s].area;
      centroid += set.samples[s].area * set.samples[s].position;
    }
    if (t.area[k] > 0.0f) centroid /= t.area[k];
    float best = std::numeric_limits<float>::infinity();
    for (std::uint32_t s : t.samples[k]) {
      const glm::vec3 d = set.samples[s].position - centroid;
      if (glm::dot(d, d) < best) {
        best = glm::dot(d, d);
        t.representative[k] = s;
      }
    }
  }
  return t;
}

TargetPoints target_points(const SampleSet& set, const Targets& targets) {
  TargetPoints points;
  std::vector<SurfacePoint> of_target;
  for (const std::vector<std::uint32_t>& members : targets.samples) {
    of_target.clear();
    for (std::uint32_t j : members) {
      const Sample& b = set.samples[j];
      of_target.push_back({b.position, b.normal, b.area});
    }
    points.add_target(of_target);
  }
  return points;
}

// Row `si` of F: the exchange sums divided by the sample's area, zero where
// the one visibility ray to the target's representative is blocked.
void finish_row(const RayTracer& tracer, const SampleSet& set, const Targets& targets,
                std::size_t si, const float* sums, std::size_t lane, float* row,
                std::vector<ShadowRay>& rays, std::vector<std::uint32_t>& ray_target,
                std::vector<std::uint8_t>& blocked) {
  const float eps = 10.0f * tracer.epsilon();
  const Sample& a = set.samples[si];
  rays.clear();
  ray_target.clear();
  for (std::size_t t = 0; t < targets.samples.size(); ++t) {
    const float sum = sums[t * kExchangeLanes + lane];
    if (sum <= 0.0f) continue;
    row[t] = sum / a.area;
    const Sample& rep = set.samples[targets.representative[t]];
    const glm::vec3 from = a.position + eps * a.normal;
    const glm::vec3 to = rep.position + eps * rep.normal;
    rays.push_back({from, to - from, 0.0f, 1.0f - 1e-4f});
    ray_target.push_back(static_cast<std::uint32_t>(t));
  }
  blocked.resize(rays.size());
  tracer.occluded(rays.data(), rays.size(), blocked.data());
  for (std::size_t k = 0; k < rays.size(); ++k)
    if (blocked[k]) row[ray_target[k]] = 0.0f;
}

// F from each sample to each target, with one visibility ray per pair; the
// rows of this process's range only when shared (SampleRowSharing), then the
// others' gathered into place. Rows go kExchangeLanes at a time through the
// exchange sums.
std::vector<float> sample_target_form_factors(const RayTracer& tracer, const SampleSet& set,
                                              const Targets& targets,
                                              const SampleRowSharing& sharing, Progress* progress) {
  const std::size_t ns = set.samples.size(), nt = targets.samples.size();
  std::vector<float> f(ns * nt, 0.0f);
  const SampleRows own =
      sharing.gather ? sample_rows_of(sharing.part, sharing.parts, ns) : SampleRows{0, ns};
  const TargetPoints points = target_points(set, targets);
  const std::size_t groups = (own.end - own.first + kExchangeLanes - 1) / kExchangeLanes;
  if (progress)
    progress->begin_stage("cluster: form factors to targets",
                          std::max<std::size_t>(1, own.end - own.first));
#pragma omp parallel
  {
    std::vector<ShadowRay> rays;
    std::vector<std::uint32_t> ray_target;
    std::vector<std::uint8_t> blocked;
    std::vector<float> sums(nt * kExchangeLanes);
    SurfacePoint sources[kExchangeLanes];
#pragma omp for schedule(dynamic, 2)
    for (std::int64_t gi = 0; gi < static_cast<std::int64_t>(groups); ++gi) {
      if (progress && progress->should_stop()) continue;
      const std::size_t first = own.first + static_cast<std::size_t>(gi) * kExchangeLanes;
      const std::size_t count = std::min(kExchangeLanes, own.end - first);
      for (std::size_t l = 0; l < count; ++l) {
        const Sample& a = set.samples[first + l];
        sources[l] = {a.position, a.normal, a.area};
      }
      exchange_with_targets(sources, count, points, sums.data());
      for (std::size_t l = 0; l < count; ++l)
        finish_row(tracer, set, targets, first + l, sums.data(), l, &f[(first + l) * nt], rays,
                   ray_target, blocked);
      if (progress) progress->advance(count);
    }
  }
  if (progress) progress->check();
  if (sharing.gather) sharing.gather(f.data(), ns, nt);
  return f;
}

struct Cluster {
  std::vector<std::uint32_t> members;
  float area = 0.0f;
  glm::vec3 color{0.0f};       // area-weighted mean albedo
  glm::vec3 normal_sum{0.0f};  // area-weighted
  std::vector<float> f;        // F to each target, as a source (area-weighted mean)
  bool emissive = false;
  // Only in a voxel with separated samples (SampleSeparation): the members
  // as bits of the voxel's local sample index, and every sample separated
  // from one of them. Merged clusters take the union of both.
  std::vector<std::uint64_t> member_bits, apart_bits;
  glm::vec3 normal() const {
    const float len = glm::length(normal_sum);
    return len > 0.0f ? normal_sum / len : glm::vec3(0.0f);
  }
};

// A member of one is separated from a member of the other.
bool kept_apart(const Cluster& a, const Cluster& b) {
  for (std::size_t w = 0; w < a.apart_bits.size(); ++w)
    if (a.apart_bits[w] & b.member_bits[w]) return true;
  return false;
}

float metric(const Cluster& a, const Cluster& b, const std::vector<float>& target_area) {
  float ff = 0.0f;
  for (std::size_t t = 0; t < a.f.size(); ++t) {
    const float d_row = a.f[t] - b.f[t];
    const float d_col = (a.area * a.f[t] - b.area * b.f[t]) / target_area[t];
    ff += d_row * d_row + d_col * d_col;
  }
  return (1.0f + glm::length(a.color - b.color)) * (2.0f - glm::dot(a.normal(), b.normal())) *
         (1.0f + std::sqrt(ff));
}

// Per voxel: its patch density (area-weighted mean of its samples' meshes')
// and the mesh with most area in it. Empty when every density is 1, so that
// such a scene takes exactly the path it took before densities existed.
struct VoxelDensity {
  std::vector<double> density;
  std::vector<std::uint32_t> mesh;
};

VoxelDensity voxel_densities(const SampleSet& set, const std::vector<float>& mesh_density) {
  VoxelDensity out;
  if (std::all_of(mesh_density.begin(), mesh_density.end(), [](float d) { return d == 1.0f; }))
    return out;
  const std::size_t nv = set.first.size() - 1;
  out.density.assign(nv, 1.0);
  out.mesh.assign(nv, 0);
  std::unordered_map<std::uint32_t, double> area_of_mesh;
  for (std::size_t v = 0; v < nv; ++v) {
    double area = 0.0, weighted = 0.0;
    area_of_mesh.clear();
    for (std::uint32_t s = set.first[v]; s < set.first[v + 1]; ++s) {
      const Sample& x = set.samples[s];
      const double d = x.mesh < mesh_density.size() ? mesh_density[x.mesh] : 1.0;
      area += x.area;
      weighted += d * x.area;
      area_of_mesh[x.mesh] += x.area;
    }
    if (area > 0.0) out.density[v] = weighted / area;
    double most = -1.0;
    for (const auto& [mesh, a] : area_of_mesh)
      if (a > most || (a == most && mesh < out.mesh[v])) {
        most = a;
        out.mesh[v] = mesh;
      }
  }
  return out;
}

// Patches each voxel keeps under a total budget with densities: `kept` (what
// the cheapest-merge-first rule kept at density 1) times the voxel's density
// times one factor k, each within [fewest, most] (as far as the voxel can
// merge, its sample count), k chosen by bisection so the total is the budget.
// Rounded with the remainder carried on per mesh (by the voxel's main mesh),
// so each mesh's count is its share to within one patch.
std::vector<std::size_t> density_allotment(const std::vector<std::size_t>& kept,
                                           const std::vector<std::size_t>& fewest,
                                           const std::vector<std::size_t>& most,
                                           const VoxelDensity& vd, std::size_t budget) {
  const std::size_t nv = kept.size();
  const auto share = [&](double k, std::size_t v) {
    const double want = k * vd.density[v] * static_cast<double>(kept[v]);
    return std::clamp(want, static_cast<double>(fewest[v]), static_cast<double>(most[v]));
  };
  const auto total = [&](double k) {
    double sum = 0.0;
    for (std::size_t v = 0; v < nv; ++v) sum += share(k, v);
    return sum;
  };
  const auto target = static_cast<double>(budget);
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 64 && total(hi) < target; ++i) hi *= 2.0;
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < target ? lo : hi) = mid;
  }
  std::unordered_map<std::uint32_t, double> carried;
  std::vector<std::size_t> out(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    double& c = carried[vd.mesh[v]];
    const double want = share(hi, v);
    const auto n = std::llround(c + want) - std::llround(c);
    c += want;
    out[v] = std::clamp(static_cast<std::size_t>(std::max<long long>(n, 0)), fewest[v], most[v]);
  }
  return out;
}

}  // namespace

SampleRows sample_rows_of(std::size_t part, std::size_t parts, std::size_t ns) {
  parts = std::max<std::size_t>(1, parts);
  part = std::min(part, parts - 1);
  return {ns * part / parts, ns * (part + 1) / parts};
}

PatchSet cluster_virtual_patches(const RayTracer& tracer, const Voxelization& vox,
                                 const SampleSet& set, const ClusteringSettings& settings,
                                 ClusteringStats& stats, Progress* progress) {
  const Targets targets = make_targets(vox, set, settings.max_targets);
  stats.feature_targets = targets.samples.size();
  stats.target_block = targets.block;
  const std::vector<float> f =
      sample_target_form_factors(tracer, set, targets, settings.sharing, progress);
  const std::size_t nt = targets.samples.size();
  const std::size_t nv = vox.voxels.size();
  const auto keep = static_cast<std::size_t>(std::max(1, settings.patches_per_voxel));
  const VoxelDensity vd = voxel_densities(set, settings.mesh_density);
  const auto keep_in = [&](std::size_t v) {
    if (vd.density.empty()) return keep;
    return static_cast<std::size_t>(
        std::max(1.0, std::round(vd.density[v] * static_cast<double>(keep))));
  };

  if (progress) progress->begin_stage("cluster: merge samples", nv);
  std::vector<std::vector<std::vector<std::uint32_t>>> clusters_of_voxel(nv);
  // With a total budget every voxel merges down as far as it can and records
  // its merges (cost, kept cluster, absorbed cluster) in order; the budget
  // then takes the cheapest next merge over all voxels (below).
  struct Merge {
    float cost;
    std::uint32_t into, from;
  };
  const bool budget = settings.total_patches > 0;
  std::vector<std::vector<Merge>> merges_of_voxel(nv);
  std::vector<std::size_t> separated_pairs(nv, 0);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t vi = 0; vi < static_cast<std::int64_t>(nv); ++vi) {
    if (progress && progress->should_stop()) continue;
    const auto v = static_cast<std::size_t>(vi);
    const SampleSeparation separation(tracer, set, v);
    separated_pairs[v] = separation.separated_pairs();
    std::vector<Cluster> cl;
    for (std::uint32_t s = set.first[v]; s < set.first[v + 1]; ++s) {
      const Sample& x = set.samples[s];
      Cluster c;
      if (!separation.empty()) {
        const std::size_t local = s - set.first[v];
        c.member_bits.assign(separation.words(), 0);
        c.member_bits[local / 64] = std::uint64_t{1} << (local % 64);
        c.apart_bits.assign(separation.row(local), separation.row(local) + separation.words());
      }
      c.members = {s};
      c.area = x.area;
      c.color = x.albedo;
      c.normal_sum = x.area * x.normal;
      c.emissive = x.emission.r > 0.0f || x.emission.g > 0.0f || x.emission.b > 0.0f;
      c.f.assign(f.begin() + static_cast<std::ptrdiff_t>(s * nt),
                 f.begin() + static_cast<std::ptrdiff_t>((s + 1) * nt));
      cl.push_back(std::move(c));
    }
    const std::size_t n = cl.size();
    // Pairwise metric, kept up to date as clusters merge. Pairs facing more
    // than 90 degrees apart are never merged (infinite distance), nor emitting
    // with non-emitting surface: a lamp just under a ceiling is their
    // cheapest merge by normal, colour and position, and the merged patch
    // would send the lamp's light out as if from the shaded ceiling behind it
    // too (docs/method.md section 4). Nor are samples with a surface between
    // them, such as the floor on the two sides of a thin wall.
    constexpr float kNever = std::numeric_limits<float>::infinity();
    std::vector<float> m(n * n, kNever);
    std::vector<bool> alive(n, true);
    auto update = [&](std::size_t a, std::size_t b) {
      const float d = glm::dot(cl[a].normal(), cl[b].normal()) < 0.0f ||
                              cl[a].emissive != cl[b].emissive || kept_apart(cl[a], cl[b])
                          ? kNever
                          : metric(cl[a], cl[b], targets.area);
      m[a * n + b] = m[b * n + a] = d;
    };
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) update(a, b);
    std::size_t remaining = n;
    const std::size_t stop_at = budget ? 1 : keep_in(v);
    while (remaining > stop_at) {
      float best = kNever;
      std::size_t ba = 0, bb = 0;
      for (std::size_t a = 0; a < n; ++a) {
        if (!alive[a]) continue;
        for (std::size_t b = a + 1; b < n; ++b)
          if (alive[b] && m[a * n + b] < best) {
            best = m[a * n + b];
            ba = a;
            bb = b;
          }
      }
      if (best == kNever) break;  // only opposite-facing clusters left
      if (budget)
        merges_of_voxel[v].push_back(
            {best, static_cast<std::uint32_t>(ba), static_cast<std::uint32_t>(bb)});
      Cluster& A = cl[ba];
      Cluster& B = cl[bb];
      const float area = A.area + B.area;
      const float wa = area > 0.0f ? A.area / area : 0.5f, wb = 1.0f - wa;
      for (std::size_t t = 0; t < nt; ++t) A.f[t] = wa * A.f[t] + wb * B.f[t];
      A.color = wa * A.color + wb * B.color;
      A.normal_sum += B.normal_sum;
      A.area = area;
      A.members.insert(A.members.end(), B.members.begin(), B.members.end());
      for (std::size_t w = 0; w < A.member_bits.size(); ++w) {
        A.member_bits[w] |= B.member_bits[w];
        A.apart_bits[w] |= B.apart_bits[w];
      }
      alive[bb] = false;
      --remaining;
      for (std::size_t c = 0; c < n; ++c)
        if (alive[c] && c != ba) update(ba, c);
    }
    if (!budget)
      for (std::size_t c = 0; c < n; ++c)
        if (alive[c]) clusters_of_voxel[v].push_back(std::move(cl[c].members));
    if (progress) progress->advance();
  }
  if (progress) progress->check();
  if (budget) {
    // Merges per voxel, cheapest next merge first, until the budget is met.
    std::size_t count = set.samples.size();
    std::vector<std::size_t> taken(nv, 0);
    using Next = std::pair<float, std::size_t>;
    std::priority_queue<Next, std::vector<Next>, std::greater<>> next;
    for (std::size_t v = 0; v < nv; ++v)
      if (!merges_of_voxel[v].empty()) next.push({merges_of_voxel[v][0].cost, v});
    while (count > settings.total_patches && !next.empty()) {
      const std::size_t v = next.top().second;
      next.pop();
      --count;
      if (++taken[v] < merges_of_voxel[v].size()) next.push({merges_of_voxel[v][taken[v]].cost, v});
    }
    if (!vd.density.empty()) {
      std::vector<std::size_t> kept(nv), fewest(nv), most(nv);
      for (std::size_t v = 0; v < nv; ++v) {
        most[v] = set.first[v + 1] - set.first[v];
        fewest[v] = most[v] - merges_of_voxel[v].size();
        kept[v] = most[v] - taken[v];
      }
      const std::vector<std::size_t> allot =
          density_allotment(kept, fewest, most, vd, settings.total_patches);
      for (std::size_t v = 0; v < nv; ++v) taken[v] = most[v] - allot[v];
    }
    for (std::size_t v = 0; v < nv; ++v) {
      std::vector<std::vector<std::uint32_t>> members;
      for (std::uint32_t s = set.first[v]; s < set.first[v + 1]; ++s) members.push_back({s});
      std::vector<bool> alive(members.size(), true);
      for (std::size_t k = 0; k < taken[v]; ++k) {
        const Merge& mg = merges_of_voxel[v][k];
        auto& into = members[mg.into];
        into.insert(into.end(), members[mg.from].begin(), members[mg.from].end());
        alive[mg.from] = false;
      }
      for (std::size_t c = 0; c < members.size(); ++c)
        if (alive[c]) clusters_of_voxel[v].push_back(std::move(members[c]));
    }
  }

  PatchSet patches;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!budget && clusters_of_voxel[v].size() > keep_in(v)) stats.voxels_above_target++;
    if (separated_pairs[v] > 0) {
      ++stats.voxels_with_separated_samples;
      stats.separated_sample_pairs += separated_pairs[v];
    }
    for (const auto& members : clusters_of_voxel[v]) patches.add_patch(set.samples, members);
  }
  if (progress) progress->end_stage();
  return patches;
}

PatchSet voxel_patches(const SampleSet& set) {
  PatchSet patches;
  const std::size_t nv = set.first.size() - 1;
  for (std::size_t v = 0; v < nv; ++v) {
    std::vector<std::uint32_t> bins[6];
    for (std::uint32_t s = set.first[v]; s < set.first[v + 1]; ++s) {
      const glm::vec3 n = set.samples[s].normal;
      const glm::vec3 a = glm::abs(n);
      const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
      bins[2 * axis + (n[axis] < 0.0f ? 1 : 0)].push_back(s);
    }
    for (const auto& bin : bins)
      if (!bin.empty()) patches.add_patch(set.samples, bin);
  }
  return patches;
}

}  // namespace bounce
