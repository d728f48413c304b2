#include "formfactor/form_factors.h"

#include <algorithm>
#include <cmath>

#include <limits>
#include <map>
#include <numbers>

#include "base/form_factor_kernel.h"
#include "voxel/polygon.h"

namespace bounce {

namespace {

using Point = SurfacePoint;

// A piece of surface a patch stands for: the Voronoi cell of one of its
// samples (a polygon), or the parts no ray hit that a sample carries, lumped
// into one point (polygon == nullptr): on finely meshed surfaces those are
// many tiny triangles, and integrating each exactly costs far more than the
// accuracy it buys.
struct Receiver {
  const glm::vec3* polygon;  // nullptr: a point piece
  int vertex_count;
  glm::vec3 centroid;
  glm::vec3 normal;  // of the receiving side
  float area;
};

// The pieces one sample carries, with a bounding sphere, so that two clumps
// far apart against their sizes can be summed as two points.
struct Clump {
  glm::vec3 centroid;
  glm::vec3 normal;  // normalised area-weighted sum
  float area;
  float radius2;               // squared radius of a sphere about the centroid holding every piece
  std::uint32_t first, count;  // pieces in PatchGeometry::surface[p]
};

constexpr std::size_t kRayEnds = 4;

struct PatchGeometry {
  std::vector<std::vector<Point>> far;  // a few points carrying the patch's area
  // Where visibility rays start and end: kRayEnds piece centroids per far
  // point, ray_ends[p][r * kRayEnds + m], picked in its group at the area
  // quantiles (m + 1/2) / kRayEnds. A far point is a mean and need not lie on
  // any surface: one averaging a light 1 cm below a ceiling with the ceiling
  // (one voxel patch holds both) lies between the two, and rays from there
  // hit the light's back, cutting the brightest patch off the scene. Pieces
  // picked by area, rotated over the pairs, see each surface of a group in
  // proportion to its area.
  std::vector<std::vector<Point>> ray_ends;
  std::vector<std::vector<Receiver>> surface;  // the pieces of surface it stands for
  std::vector<std::vector<Clump>> clumps;      // the pieces grouped by sample
};

// Reduces a patch's pieces of surface to at most k points for far-field sums:
// seeds by farthest-point sampling, every piece assigned to its nearest seed,
// each representative the area-weighted mean of its group. Areas add up to
// the patch's, so this is a quadrature of the patch, not a subsample.
// `on_surface` gets kRayEnds pieces of each representative's group
// (PatchGeometry::ray_ends).
std::vector<Point> representatives(const std::vector<Point>& all, std::size_t k,
                                   std::vector<Point>& on_surface) {
  if (all.size() <= k) {
    on_surface.clear();
    for (const Point& x : all) on_surface.insert(on_surface.end(), kRayEnds, x);
    return all;
  }
  // Distance in position and orientation: a patch may hold pieces of several
  // faces (a box corner with one patch per voxel), and a representative that
  // averaged a floor piece with a wall piece would have a normal neither has.
  float area = 0.0f;
  for (const Point& x : all) area += x.area;
  const float normal_weight = 4.0f * area;
  auto distance2 = [&](const Point& a, const Point& b) {
    const glm::vec3 dp = a.position - b.position, dn = a.normal - b.normal;
    return glm::dot(dp, dp) + normal_weight * glm::dot(dn, dn);
  };
  std::vector<std::size_t> seeds{0};
  std::vector<float> dist(all.size(), std::numeric_limits<float>::infinity());
  while (seeds.size() < k) {
    std::size_t farthest = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      dist[i] = std::min(dist[i], distance2(all[i], all[seeds.back()]));
      if (dist[i] > dist[farthest]) farthest = i;
    }
    if (dist[farthest] <= 0.0f) break;  // all remaining pieces coincide with seeds
    seeds.push_back(farthest);
  }
  std::vector<Point> reps(seeds.size(), Point{glm::vec3(0.0f), glm::vec3(0.0f), 0.0f});
  std::vector<std::size_t> group(all.size(), 0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Point& x = all[i];
    std::size_t best = 0;
    float best_d = std::numeric_limits<float>::infinity();
    for (std::size_t r = 0; r < seeds.size(); ++r) {
      const float d = distance2(x, all[seeds[r]]);
      if (d < best_d) {
        best_d = d;
        best = r;
      }
    }
    group[i] = best;
    reps[best].position += x.area * x.position;
    reps[best].normal += x.area * x.normal;
    reps[best].area += x.area;
  }
  for (Point& r : reps) {
    r.position /= r.area;
    const float len = glm::length(r.normal);
    r.normal = len > 0.0f ? r.normal / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  // Pieces in member order (samples spread over the voxel), walked by
  // cumulative area within each group.
  on_surface.assign(reps.size() * kRayEnds, Point{glm::vec3(0.0f), glm::vec3(0.0f), 0.0f});
  std::vector<float> walked(reps.size(), 0.0f);
  std::vector<std::size_t> next(reps.size(), 0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const std::size_t r = group[i];
    walked[r] += all[i].area;
    while (next[r] < kRayEnds && walked[r] >= (static_cast<float>(next[r]) + 0.5f) /
                                                  static_cast<float>(kRayEnds) * reps[r].area)
      on_surface[r * kRayEnds + next[r]++] = all[i];
  }
  // Rounding can leave the last quantiles of a group unreached: its last piece.
  for (std::size_t i = all.size(); i-- > 0;) {
    const std::size_t r = group[i];
    while (next[r] < kRayEnds) on_surface[r * kRayEnds + next[r]++] = all[i];
  }
  return reps;
}

PatchGeometry gather(const Scene& scene, const Voxelization& vox, const SampleSet& set,
                     const PatchSet& patches, int far_count) {
  PatchGeometry g;
  const std::size_t n = patches.size();
  g.far.resize(n);
  g.ray_ends.resize(n);
  g.surface.resize(n);
  g.clumps.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::vector<Point> members;
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const std::uint32_t si = patches.member_samples[k];
      Clump clump{glm::vec3(0.0f),
                  glm::vec3(0.0f),
                  0.0f,
                  0.0f,
                  static_cast<std::uint32_t>(g.surface[p].size()),
                  0};
      Receiver lumped{nullptr, 0, glm::vec3(0.0f), glm::vec3(0.0f), 0.0f};
      auto add_piece = [&](const Receiver& r) {
        g.surface[p].push_back(r);
        // Far-field points sit at the pieces' centroids, not at the samples
        // (a sample need not be at the centre of the surface it stands for).
        members.push_back({r.centroid, r.normal, r.area});
        clump.centroid += r.area * r.centroid;
        clump.normal += r.area * r.normal;
        clump.area += r.area;
        clump.count++;
      };
      for (std::uint32_t c = set.carried_first[si]; c < set.carried_first[si + 1]; ++c) {
        const CarriedArea& piece = set.carried[c];
        if (piece.whole_part) {
          const glm::vec3* poly = &set.carried_vertices[piece.first_vertex];
          const std::uint32_t tri = vox.parts[piece.part].triangle;
          lumped.centroid += piece.area * polygon_centroid(poly, piece.vertex_count);
          lumped.normal +=
              piece.area * glm::normalize(scene.triangle_cross(tri)) * (piece.back ? -1.0f : 1.0f);
          lumped.area += piece.area;
          continue;
        }
        Receiver r;
        r.polygon = &set.carried_vertices[piece.first_vertex];
        r.vertex_count = static_cast<int>(piece.vertex_count);
        r.centroid = polygon_centroid(r.polygon, piece.vertex_count);
        const std::uint32_t tri = vox.parts[piece.part].triangle;
        r.normal = glm::normalize(scene.triangle_cross(tri)) * (piece.back ? -1.0f : 1.0f);
        r.area = piece.area;
        add_piece(r);
      }
      if (lumped.area > 0.0f) {
        lumped.centroid /= lumped.area;
        const float len = glm::length(lumped.normal);
        lumped.normal = len > 0.0f ? lumped.normal / len : glm::vec3(0.0f, 0.0f, 1.0f);
        // The mean of parts spread over a curved surface lies off it (inside
        // a convex mesh such as the bunny), where rays to and from it are
        // blocked by the surface itself: the point stands at the centroid of
        // the carried part nearest that mean, on the surface.
        float nearest = std::numeric_limits<float>::infinity();
        glm::vec3 on_surface = lumped.centroid;
        for (std::uint32_t c = set.carried_first[si]; c < set.carried_first[si + 1]; ++c) {
          const CarriedArea& piece = set.carried[c];
          if (!piece.whole_part) continue;
          const glm::vec3 x =
              polygon_centroid(&set.carried_vertices[piece.first_vertex], piece.vertex_count);
          const glm::vec3 d = x - lumped.centroid;
          if (glm::dot(d, d) < nearest) {
            nearest = glm::dot(d, d);
            on_surface = x;
          }
        }
        lumped.centroid = on_surface;
        add_piece(lumped);
      }
      if (clump.count == 0 || !(clump.area > 0.0f)) continue;
      clump.centroid /= clump.area;
      const float len = glm::length(clump.normal);
      clump.normal = len > 0.0f ? clump.normal / len : glm::vec3(0.0f);
      for (std::uint32_t r = clump.first; r < clump.first + clump.count; ++r) {
        const Receiver& piece = g.surface[p][r];
        for (int v = 0; v < piece.vertex_count; ++v) {
          const glm::vec3 d = piece.polygon[v] - clump.centroid;
          clump.radius2 = std::max(clump.radius2, glm::dot(d, d));
        }
        if (!piece.polygon) {  // a lumped point: its distance plus a disk of its area
          const float reach = glm::length(piece.centroid - clump.centroid) +
                              std::sqrt(piece.area / std::numbers::pi_v<float>);
          clump.radius2 = std::max(clump.radius2, reach * reach);
        }
      }
      g.clumps[p].push_back(clump);
    }
    g.far[p] =
        representatives(members, static_cast<std::size_t>(std::max(1, far_count)), g.ray_ends[p]);
  }
  return g;
}

// Far-field exchange between two points: A_i A_j cos_i cos_j / (pi r^2).
float far_exchange(const Point& a, const Point& b) {
  const glm::vec3 d = b.position - a.position;
  const float r2 = glm::dot(d, d);
  const float fa = glm::dot(a.normal, d), fb = -glm::dot(b.normal, d);
  if (fa <= 0.0f || fb <= 0.0f || !(r2 > 0.0f)) return 0.0f;
  return a.area * b.area * fa * fb / (std::numbers::pi_v<float> * r2 * r2);
}

// Form factor from a point (normal n) to a receiver: exact point-to-polygon
// where the receiver is large against its distance, differential otherwise.
double point_to_receiver(const glm::vec3& x, const glm::vec3& n, const Receiver& r) {
  const glm::vec3 d = r.centroid - x;
  const float in_front = -glm::dot(r.normal, d);  // > 0: x is in front of the receiver
  if (in_front <= 0.0f) return 0.0;
  const float r2 = glm::dot(d, d);
  if (r2 < kNearFactor * kNearFactor * r.area)
    return point_to_polygon_form_factor(x, n, r.polygon, r.vertex_count);
  const float cos_x = glm::dot(n, d);
  if (cos_x <= 0.0f) return 0.0;
  return r.area * cos_x * in_front / (std::numbers::pi_v<float> * r2 * r2);
}

// Integral over the triangle (a,b,c) of the form factor from its points to
// the receiver, by the centroid rule on a subdivision that refines where the
// triangle is large against its distance to the receiver (up to 4^depth
// pieces), so edges and corners are integrated, not point-sampled.
double integrate_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                          const glm::vec3& n, const Receiver& r, int depth) {
  const glm::vec3 m = (a + b + c) / 3.0f;
  const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
  const glm::vec3 d = r.centroid - m;
  const float r2 = glm::dot(d, d);
  if (depth == 0 || area * kNearFactor * kNearFactor < r2) return area * point_to_receiver(m, n, r);
  const glm::vec3 ab = 0.5f * (a + b), bc = 0.5f * (b + c), ca = 0.5f * (c + a);
  return integrate_triangle(a, ab, ca, n, r, depth - 1) +
         integrate_triangle(ab, b, bc, n, r, depth - 1) +
         integrate_triangle(ca, bc, c, n, r, depth - 1) +
         integrate_triangle(ab, bc, ca, n, r, depth - 1);
}

// Energy leaving the surface one patch stands for that reaches the surface
// another stands for: sum over source pieces s and receiver pieces r of the
// integral over s of F(x -> r) dx.
float near_transfer(const std::vector<Receiver>& from_pieces, const std::vector<Clump>& from,
                    const std::vector<Receiver>& to_pieces, const std::vector<Clump>& to) {
  constexpr int kMaxDepth = 4;
  constexpr float kSeparated = kNearFactor * kNearFactor;
  auto point_pair = [](const glm::vec3& d, float r2, const glm::vec3& ns, float as,
                       const glm::vec3& nr, float ar) {
    const float cs = glm::dot(ns, d), cr = -glm::dot(nr, d);
    if (cs <= 0.0f || cr <= 0.0f) return 0.0;
    return static_cast<double>(as) * ar * cs * cr / (std::numbers::pi_v<float> * r2 * r2);
  };
  double sum = 0.0;
  for (const Clump& cs : from) {
    for (const Clump& cr : to) {
      const glm::vec3 dc = cr.centroid - cs.centroid;
      const float rc2 = glm::dot(dc, dc);
      if (rc2 >= kSeparated * std::max(cs.radius2, cr.radius2)) {
        // Two clumps small against their distance: two points.
        sum += point_pair(dc, rc2, cs.normal, cs.area, cr.normal, cr.area);
        continue;
      }
      for (std::uint32_t a = cs.first; a < cs.first + cs.count; ++a) {
        const Receiver& s = from_pieces[a];
        for (std::uint32_t b = cr.first; b < cr.first + cr.count; ++b) {
          const Receiver& r = to_pieces[b];
          if (&s == &r) continue;
          const glm::vec3 d = r.centroid - s.centroid;
          const float r2 = glm::dot(d, d);
          if (!s.polygon || !r.polygon) {
            // A lumped point on either side: the disk-bounded kernel, the same
            // both ways so the pair stays reciprocal.
            sum += bounded_exchange({s.centroid, s.normal, s.area}, {r.centroid, r.normal, r.area});
            continue;
          }
          if (r2 >= kSeparated * std::max(s.area, r.area)) {
            // Both pieces small against their distance: the differential
            // kernel between their centroids.
            sum += point_pair(d, r2, s.normal, s.area, r.normal, r.area);
            continue;
          }
          for (int v = 1; v + 1 < s.vertex_count; ++v)
            sum += integrate_triangle(s.polygon[0], s.polygon[v], s.polygon[v + 1], s.normal, r,
                                      kMaxDepth);
        }
      }
    }
  }
  return static_cast<float>(sum);
}

struct PairSum {
  float unoccluded_pq = 0.0f;  // energy P -> Q without visibility
  float unoccluded_qp = 0.0f;  // energy Q -> P without visibility
  std::uint32_t first_ray = 0, ray_count = 0;
  std::uint32_t q = 0;
};

// Computes the pairs (p, q >= p) of the rows settings deals to this process
// and hands each pair's two entries to store(p, q, F_pq, F_qp) (F_qp unused
// when q == p); pairs that exchange nothing are not stored. Returns how many
// entries were capped at 1.
template <class Store>
std::size_t compute_pairs(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                          const SampleSet& set, const PatchSet& patches,
                          const FormFactorSettings& settings, Progress* progress, Store&& store) {
  const std::size_t n = patches.size();
  const PatchGeometry geo = gather(scene, vox, set, patches, settings.far_representatives);
  const float cell = vox.grid.cell_size();
  const float near2 = settings.near_cells * settings.near_cells * cell * cell;
  const float eps = 10.0f * tracer.epsilon();
  const auto rays_per_pair = static_cast<std::size_t>(std::max(1, settings.visibility_rays));

  // Rows are uneven (row p handles q >= p), so hand them out dynamically, and
  // report progress in pair units.
  const std::size_t stride = std::max<std::size_t>(1, settings.row_stride);
  std::size_t own_pairs = 0;
  for (std::size_t p = settings.row_offset; p < n; p += stride) own_pairs += n - p;
  if (progress) progress->begin_stage("form factors", std::max<std::size_t>(1, own_pairs));
  std::size_t clamped = 0;
  // F_pq is the mean over P of F(x -> Q) <= 1 (see FormFactorMatrix).
  auto at_most_one = [&clamped](float value) {
    if (!(value > 1.0f)) return value;
#pragma omp atomic
    ++clamped;
    return 1.0f;
  };
#pragma omp parallel
  {
    std::vector<PairSum> pairs;
    std::vector<ShadowRay> rays;
    std::vector<float> ray_weight;
    std::vector<std::uint8_t> blocked;
    struct Candidate {
      std::uint32_t i, j;
      float w;
    };
    std::vector<Candidate> facing;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
      if (progress && progress->should_stop()) continue;
      const auto p = static_cast<std::size_t>(pi);
      if (p < settings.row_offset || (p - settings.row_offset) % stride != 0) continue;
      pairs.clear();
      rays.clear();
      ray_weight.clear();
      for (std::size_t q = p; q < n; ++q) {
        const glm::vec3 d = patches.patches[q].position - patches.patches[p].position;
        const bool near = q == p || glm::dot(d, d) < near2;
        const auto& P = geo.far[p];
        const auto& Q = geo.far[q];
        // Member pairs that face each other: the far-field sum, and the
        // candidates for visibility rays.
        facing.clear();
        float far_sum = 0.0f;
        for (std::size_t i = 0; i < P.size(); ++i)
          for (std::size_t j = 0; j < Q.size(); ++j) {
            if (q == p && i == j) continue;
            const float w = far_exchange(P[i], Q[j]);
            if (w <= 0.0f) continue;
            far_sum += w;
            facing.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), w});
          }
        float g_pq = far_sum, g_qp = far_sum;
        if (near) {
          // Each direction integrated over both surfaces; not averaged, so
          // that each row keeps its own closure (the two agree to the
          // quadrature error, reported as the reciprocity error).
          g_pq = near_transfer(geo.surface[p], geo.clumps[p], geo.surface[q], geo.clumps[q]);
          g_qp = q == p
                     ? g_pq
                     : near_transfer(geo.surface[q], geo.clumps[q], geo.surface[p], geo.clumps[p]);
        }
        if (g_pq <= 0.0f && g_qp <= 0.0f) continue;
        // Near surfaces can face each other where their representative
        // points do not (around an edge): trace between those points anyway.
        if (facing.empty()) facing.push_back({0, 0, 1.0f});
        PairSum ps;
        ps.unoccluded_pq = g_pq;
        ps.unoccluded_qp = g_qp;
        ps.q = static_cast<std::uint32_t>(q);
        ps.first_ray = static_cast<std::uint32_t>(rays.size());
        // Evenly spaced picks over the facing pairs (stored in member order,
        // so they spread over both patches), weighted by their kernel.
        const std::size_t picks = std::min(rays_per_pair, facing.size());
        for (std::size_t k = 0; k < picks; ++k) {
          const Candidate& c = facing[(2 * k + 1) * facing.size() / (2 * picks)];
          // Each pair its own turn through the ray ends (PatchGeometry).
          const Point& a = geo.ray_ends[p][c.i * kRayEnds + (q + k) % kRayEnds];
          const Point& b = geo.ray_ends[q][c.j * kRayEnds + (p + k) % kRayEnds];
          const glm::vec3 from = a.position + eps * a.normal;
          const glm::vec3 to = b.position + eps * b.normal;
          rays.push_back({from, to - from, 0.0f, 1.0f - 1e-4f});
          ray_weight.push_back(c.w);
        }
        ps.ray_count = static_cast<std::uint32_t>(picks);
        pairs.push_back(ps);
      }
      blocked.resize(rays.size());
      tracer.occluded(rays.data(), rays.size(), blocked.data());
      const float area_p = patches.patches[p].area;
      for (const PairSum& ps : pairs) {
        float seen = 0.0f, total = 0.0f;
        for (std::uint32_t k = ps.first_ray; k < ps.first_ray + ps.ray_count; ++k) {
          total += ray_weight[k];
          if (!blocked[k]) seen += ray_weight[k];
        }
        const float v = total > 0.0f ? seen / total : 0.0f;
        const float f_pq = at_most_one(ps.unoccluded_pq * v / area_p);
        const float f_qp =
            ps.q != p ? at_most_one(ps.unoccluded_qp * v / patches.patches[ps.q].area) : 0.0f;
        store(p, static_cast<std::size_t>(ps.q), f_pq, f_qp);
      }
      if (progress) progress->advance(n - p);
    }
  }
  if (progress) progress->check();
  if (progress) progress->end_stage();
  return clamped;
}

}  // namespace

FormFactorMatrix compute_form_factors(const Scene& scene, const RayTracer& tracer,
                                      const Voxelization& vox, const SampleSet& samples,
                                      const PatchSet& patches, const FormFactorSettings& settings,
                                      Progress* progress) {
  const std::size_t n = patches.size();
  FormFactorMatrix f;
  f.n = n;
  f.values.assign(n * n, 0.0f);
  float* values = f.values.data();
  f.clamped_to_one =
      compute_pairs(scene, tracer, vox, samples, patches, settings, progress,
                    [values, n](std::size_t p, std::size_t q, float f_pq, float f_qp) {
                      values[p * n + q] = f_pq;
                      if (q != p) values[q * n + p] = f_qp;
                    });
  return f;
}

std::size_t FormFactorRows::segment_length(std::size_t n, std::size_t p) {
  return p < n ? 2 * (n - p) - 1 : 0;
}

FormFactorRows compute_form_factor_rows(const Scene& scene, const RayTracer& tracer,
                                        const Voxelization& vox, const SampleSet& samples,
                                        const PatchSet& patches, const FormFactorSettings& settings,
                                        Progress* progress) {
  FormFactorRows r;
  r.n = patches.size();
  r.row_offset = settings.row_offset;
  r.row_stride = std::max<std::size_t>(1, settings.row_stride);
  r.first.push_back(0);
  for (std::size_t p = r.row_offset; p < r.n; p += r.row_stride)
    r.first.push_back(r.first.back() + FormFactorRows::segment_length(r.n, p));
  r.values.assign(r.first.back(), 0.0f);
  float* values = r.values.data();
  const std::size_t* first = r.first.data();
  const std::size_t n = r.n, offset = r.row_offset, stride = r.row_stride;
  r.clamped_to_one = compute_pairs(scene, tracer, vox, samples, patches, settings, progress,
                                   [=](std::size_t p, std::size_t q, float f_pq, float f_qp) {
                                     float* row = values + first[(p - offset) / stride];
                                     row[q - p] = f_pq;
                                     if (q != p) row[(n - p) + (q - p - 1)] = f_qp;
                                   });
  return r;
}

FormFactorChecks check_form_factors(const FormFactorMatrix& f, const PatchSet& patches,
                                    const std::vector<float>* closure) {
  FormFactorChecks c;
  const std::size_t n = f.n;
  std::vector<double> row_sum(n, 0.0), row_asym(n, 0.0);
  double sum_of_sums = 0.0, asym2 = 0.0, norm2 = 0.0;
  // Blocked so the transposed reads F_ji stay in cache.
  constexpr std::size_t kBlock = 64;
  for (std::size_t bi = 0; bi < n; bi += kBlock) {
    for (std::size_t bj = 0; bj < n; bj += kBlock) {
      for (std::size_t i = bi; i < std::min(n, bi + kBlock); ++i) {
        const double ai = patches.patches[i].area;
        for (std::size_t j = bj; j < std::min(n, bj + kBlock); ++j) {
          const float v = f(i, j);
          if (!std::isfinite(v)) {
            c.non_finite++;
            continue;
          }
          row_sum[i] += v;
          c.value_max = std::max(c.value_max, static_cast<double>(v));
          const double diff = ai * v - patches.patches[j].area * f(j, i);
          if (!std::isfinite(diff)) continue;
          row_asym[i] += std::abs(diff);
          asym2 += 0.5 * diff * diff;  // each unordered pair is visited twice
          norm2 += ai * v * ai * v;
        }
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    sum_of_sums += row_sum[i];
    c.row_sum_max = std::max(c.row_sum_max, row_sum[i]);
    if (row_sum[i] > 1.0 + 1e-3) c.rows_above_one++;
    if (closure && i < closure->size()) {
      const double excess = row_sum[i] - (*closure)[i];
      c.closure_excess_max = std::max(c.closure_excess_max, excess);
      if (excess > 1e-5) c.rows_above_closure++;
    }
    if (row_sum[i] <= 0.0) {
      c.patches_seeing_nothing++;
      continue;
    }
    c.reciprocity_error_max =
        std::max(c.reciprocity_error_max, row_asym[i] / (patches.patches[i].area * row_sum[i]));
  }
  c.clamped_to_one = f.clamped_to_one;
  c.reciprocity_error_rel = norm2 > 0.0 ? std::sqrt(asym2 / norm2) : 0.0;
  c.row_sum_mean = n ? sum_of_sums / static_cast<double>(n) : 0.0;
  return c;
}

FormFactorMatrix remove_patches(const FormFactorMatrix& f, const std::vector<bool>& keep) {
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < f.n; ++i)
    if (keep[i]) index.push_back(i);
  FormFactorMatrix out;
  out.n = index.size();
  // Removed patches see nothing (their rows are zero), so no clamped entry
  // is in their rows; one in their columns would stay counted.
  out.clamped_to_one = f.clamped_to_one;
  out.values.resize(out.n * out.n);
  for (std::size_t a = 0; a < out.n; ++a)
    for (std::size_t b = 0; b < out.n; ++b) out.values[a * out.n + b] = f(index[a], index[b]);
  return out;
}

}  // namespace bounce
