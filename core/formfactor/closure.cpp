#include "formfactor/closure.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/random.h"
#include "raytrace/cosine_lattice.h"

namespace bounce {

namespace {

// A polygon a patch's rays start from, with the outward normal of its side.
struct Piece {
  const glm::vec3* polygon;
  std::uint32_t vertex_count;
  glm::vec3 normal;
  float area;
};

// A uniform point in a convex planar polygon: a fan triangle by area, then a
// uniform point in it.
glm::vec3 point_in_polygon(const Piece& piece, float u, float v, float w) {
  const glm::vec3* poly = piece.polygon;
  double total = 0.0;
  for (std::uint32_t k = 1; k + 1 < piece.vertex_count; ++k)
    total += glm::length(glm::cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
  std::uint32_t tri = 1;
  double walked = 0.0;
  for (std::uint32_t k = 1; k + 1 < piece.vertex_count; ++k) {
    walked += glm::length(glm::cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
    tri = k;
    if (walked >= u * total) break;
  }
  if (v + w > 1.0f) {
    v = 1.0f - v;
    w = 1.0f - w;
  }
  return poly[0] + v * (poly[tri] - poly[0]) + w * (poly[tri + 1] - poly[0]);
}

}  // namespace

PatchClosure measure_closure(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                             const SampleSet& set, const PatchSet& patches,
                             const SurfacePatchLookup& lookup, const ClosureSettings& settings,
                             Progress* progress) {
  const std::size_t n = patches.size();
  const std::size_t rays = static_cast<std::size_t>(std::max(1, settings.rays_per_patch));
  const float eps = 10.0f * tracer.epsilon();
  const CosineLattice lattice(rays);

  PatchClosure out;
  out.rays_per_patch = static_cast<int>(rays);
  out.closure.assign(n, 0.0f);
  if (progress) progress->begin_stage("closure", std::max<std::size_t>(1, n));
#pragma omp parallel
  {
    std::vector<Piece> pieces;
    std::vector<std::uint32_t> order(rays);
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
      if (progress && progress->should_stop()) continue;
      const auto p = static_cast<std::size_t>(pi);
      pieces.clear();
      double area = 0.0;
      for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
        const std::uint32_t s = patches.member_samples[k];
        for (std::uint32_t c = set.carried_first[s]; c < set.carried_first[s + 1]; ++c) {
          const CarriedArea& piece = set.carried[c];
          if (!(piece.area > 0.0f) || piece.vertex_count < 3) continue;
          const std::uint32_t tri = vox.parts[piece.part].triangle;
          const glm::vec3 normal =
              glm::normalize(scene.triangle_cross(tri)) * (piece.back ? -1.0f : 1.0f);
          pieces.push_back(
              {&set.carried_vertices[piece.first_vertex], piece.vertex_count, normal, piece.area});
          area += piece.area;
        }
      }
      if (pieces.empty() || !(area > 0.0)) continue;
      Rng rng(settings.seed, 0xC105u ^ (static_cast<std::uint64_t>(p) << 20));
      // Directions shuffled against the origins, which walk the pieces in
      // order: otherwise the first pieces would get the steepest directions.
      for (std::size_t k = 0; k < rays; ++k) order[k] = static_cast<std::uint32_t>(k);
      for (std::size_t k = rays; k-- > 1;)
        std::swap(order[k], order[static_cast<std::size_t>(rng.next() % (k + 1))]);
      const float turn = 2.0f * std::numbers::pi_v<float> * rng.uniform();
      const float shift = rng.uniform();
      std::size_t closed = 0, at = 0;
      double walked = pieces[0].area;
      for (std::size_t k = 0; k < rays; ++k) {
        // Systematic sampling of the pieces by area.
        const double target = (static_cast<double>(k) + shift) / static_cast<double>(rays) * area;
        while (walked < target && at + 1 < pieces.size()) walked += pieces[++at].area;
        const Piece& piece = pieces[at];
        glm::vec3 origin = point_in_polygon(piece, rng.uniform(), rng.uniform(), rng.uniform()) +
                           eps * piece.normal;
        const glm::vec3 dir = lattice.direction(order[k], CosineLattice::Frame(piece.normal, turn));
        const Hit h = intersect_leaving_surface(tracer, origin, dir, eps);
        if (!h.hit) continue;
        const bool back = glm::dot(dir, h.geometric_normal) > 0.0f;
        if (back && !scene.two_sided(h.triangle)) continue;
        if (lookup.patch_at(h.triangle, back, origin + h.t * dir) >= 0) ++closed;
      }
      out.closure[p] = static_cast<float>(static_cast<double>(closed) / static_cast<double>(rays));
      if (progress) progress->advance();
    }
  }
  if (progress) progress->check();
  if (progress) progress->end_stage();

  double weighted = 0.0, total_area = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const double c = out.closure[p], a = patches.patches[p].area;
    weighted += a * c;
    total_area += a;
    out.min = std::min(out.min, c);
    out.max = std::max(out.max, c);
    if (c < 1.0) ++out.open_patches;
    out.standard_error_max =
        std::max(out.standard_error_max, std::sqrt(c * (1.0 - c) / static_cast<double>(rays)));
  }
  out.mean = total_area > 0.0 ? weighted / total_area : 0.0;
  if (n == 0) out.min = 0.0;
  return out;
}

}  // namespace bounce
