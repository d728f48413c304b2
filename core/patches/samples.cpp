#include "patches/samples.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "base/random.h"
#include "voxel/polygon.h"

namespace bounce {

namespace {

// Distance along the ray to where it leaves the box (origin inside or on it).
float exit_distance(const Bounds& box, const glm::vec3& o, const glm::vec3& d) {
  float t = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0f) t = std::min(t, (box.hi[a] - o[a]) / d[a]);
    if (d[a] < 0.0f) t = std::min(t, (box.lo[a] - o[a]) / d[a]);
  }
  return std::max(t, 0.0f);
}

struct PartKey {
  std::uint32_t triangle;
  bool front;
  bool operator<(const PartKey& o) const {
    return triangle != o.triangle ? triangle < o.triangle : front < o.front;
  }
};

struct VoxelSamples {
  std::vector<Sample> samples;
  std::vector<std::vector<CarriedArea>> carried;  // per sample; vertices index `vertices`
  std::vector<glm::vec3> vertices;
};

// The Voronoi cell of samples[mine] among `all` (samples on one planar part),
// clipped to the part's polygon. Computed in double, relative to the sample:
// the bisector written in absolute float coordinates, n.x <= (|q|^2 - |p|^2)/2,
// cancels (|q|^2 ~ the scene's size squared, the difference ~ its size times
// |q - p|), so a one-ulp change of the coordinates (a decimal rescale of the
// scene) moved the bisectors of close samples by ~1e-7 scene / |q - p| and
// changed small cells' areas by up to 0.4% (docs/stability.md).
std::vector<glm::vec3> voronoi_cell(const std::vector<glm::vec3>& part,
                                    const std::vector<Sample>& samples,
                                    const std::vector<std::uint32_t>& all, std::uint32_t mine) {
  const glm::dvec3 p(samples[mine].position);
  std::vector<glm::dvec3> cell, next;
  for (const glm::vec3& x : part) cell.push_back(glm::dvec3(x) - p);
  for (std::uint32_t other : all) {
    if (other == mine || cell.size() < 3) continue;
    const glm::dvec3 n = glm::dvec3(samples[other].position) - p;
    const double offset = 0.5 * glm::dot(n, n);  // the bisector: n.y = |n|^2 / 2
    if (offset <= 0.0) continue;                 // coincident samples: split below by count
    next.clear();
    for (std::size_t k = 0; k < cell.size(); ++k) {
      const glm::dvec3& a = cell[k];
      const glm::dvec3& b = cell[(k + 1) % cell.size()];
      const double da = glm::dot(n, a) - offset, db = glm::dot(n, b) - offset;
      if (da <= 0.0) next.push_back(a);
      if ((da <= 0.0) != (db <= 0.0)) next.push_back(a + (da / (da - db)) * (b - a));
    }
    cell.swap(next);
  }
  std::vector<glm::vec3> out;
  out.reserve(cell.size());
  for (const glm::dvec3& y : cell) out.push_back(glm::vec3(p + y));
  return out;
}

// Where the ray meets the plane of the triangle it hit, in double. Embree's
// float hit distance has its own error of a few ulps of the ray's length,
// which a ray grazing the surface stretches along it; the plane intersection
// in double leaves only the rounding of the result. (The ray origin's own
// rounding is stretched the same way and stays: docs/stability.md.)
glm::vec3 hit_on_plane(const Scene& scene, std::uint32_t triangle, const glm::vec3& origin,
                       const glm::vec3& dir, float t) {
  const glm::dvec3 v0(scene.vertex(triangle, 0)), v1(scene.vertex(triangle, 1)),
      v2(scene.vertex(triangle, 2));
  const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
  const glm::dvec3 o(origin), d(dir);
  const double den = glm::dot(n, d);
  const double exact_t = den != 0.0 ? glm::dot(n, v0 - o) / den : static_cast<double>(t);
  // Keep Embree's distance if the plane disagrees by more than a rounding
  // error would (a degenerate triangle).
  if (!(std::abs(exact_t - static_cast<double>(t)) <= 1e-3 * std::abs(static_cast<double>(t))))
    return origin + t * dir;
  return glm::vec3(o + exact_t * d);
}

VoxelSamples sample_voxel(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                          std::uint32_t v, const SamplingSettings& settings, double& centred,
                          std::size_t& centre_samples, double& cut_away) {
  const OccupiedVoxel& voxel = vox.voxels[v];
  const Bounds box = vox.grid.cell_bounds(voxel.coord);
  const float cell = vox.grid.cell_size();
  const int g = settings.samples_per_face;
  Rng rng(settings.seed, voxel.cell);

  std::vector<Sample> samples;
  std::map<PartKey, std::vector<std::uint32_t>> samples_of_part;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const bool high = face % 2 == 1;
    const int u_axis = (axis + 1) % 3, w_axis = (axis + 2) % 3;
    glm::vec3 inward(0.0f);
    inward[axis] = high ? -1.0f : 1.0f;
    glm::vec3 tu(0.0f), tw(0.0f);
    tu[u_axis] = 1.0f;
    tw[w_axis] = 1.0f;
    for (int iu = 0; iu < g; ++iu) {
      for (int iw = 0; iw < g; ++iw) {
        glm::vec3 origin;
        origin[axis] = high ? box.hi[axis] : box.lo[axis];
        origin[u_axis] = box.lo[u_axis] +
                         cell * (static_cast<float>(iu) + rng.uniform()) / static_cast<float>(g);
        origin[w_axis] = box.lo[w_axis] +
                         cell * (static_cast<float>(iw) + rng.uniform()) / static_cast<float>(g);
        // Cosine-weighted direction about the inward normal.
        const float r = std::sqrt(rng.uniform());
        const float phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
        const float z = std::sqrt(std::max(0.0f, 1.0f - r * r));
        const glm::vec3 dir =
            glm::normalize(z * inward + r * std::cos(phi) * tu + r * std::sin(phi) * tw);
        const float t_exit = exit_distance(box, origin, dir);
        for (const Hit& h :
             tracer.intersect_all(origin, dir, 0.0f, t_exit, settings.max_hits_per_ray)) {
          const bool front = glm::dot(dir, h.geometric_normal) < 0.0f;
          if (!front && !scene.two_sided(h.triangle)) continue;
          const Material& m = scene.material_of(h.triangle);
          Sample s{};
          s.position = hit_on_plane(scene, h.triangle, origin, dir, h.t);
          s.normal = front ? h.geometric_normal : -h.geometric_normal;
          s.albedo = m.albedo;
          s.emission = m.emission;
          s.voxel = v;
          s.triangle = h.triangle;
          s.mesh = scene.triangle_mesh[h.triangle];
          samples_of_part[{h.triangle, front}].push_back(
              static_cast<std::uint32_t>(samples.size()));
          samples.push_back(s);
        }
      }
    }
  }

  // Sampled parts: Voronoi cells of their samples; unsampled parts go to the
  // nearest sample facing the same way.
  std::vector<std::vector<CarriedArea>> carried(samples.size());
  std::vector<glm::vec3> vertices;
  auto carry = [&](std::size_t s, std::uint32_t part_index, bool back,
                   const std::vector<glm::vec3>& poly, float area, bool whole) {
    samples[s].area += area;
    carried[s].push_back({part_index, back, area, static_cast<std::uint32_t>(vertices.size()),
                          static_cast<std::uint32_t>(poly.size()), whole,
                          vox.parts[part_index].triangle});
    vertices.insert(vertices.end(), poly.begin(), poly.end());
  };
  for (std::uint32_t k = 0; k < voxel.part_count; ++k) {
    const std::uint32_t part_index = voxel.first_part + k;
    const TrianglePart& part = vox.parts[part_index];
    const std::vector<glm::vec3> polygon(
        vox.part_vertices.begin() + part.first_vertex,
        vox.part_vertices.begin() + part.first_vertex + part.vertex_count);
    const bool two_sided = scene.two_sided(part.triangle);
    const bool masked = scene.masked(part.triangle);
    const glm::vec3 n_front = glm::normalize(scene.triangle_cross(part.triangle));
    glm::vec3 centroid = (scene.vertex(part.triangle, 0) + scene.vertex(part.triangle, 1) +
                          scene.vertex(part.triangle, 2)) /
                         3.0f;
    centroid = glm::clamp(centroid, box.lo, box.hi);
    for (int side = 0; side < (two_sided ? 2 : 1); ++side) {
      const bool front = side == 0;
      const auto it = samples_of_part.find({part.triangle, front});
      if (it != samples_of_part.end()) {
        // Cells tile the part; rescale their areas so they add up to the
        // clipped area exactly (rounding), and split coincident samples' cells.
        std::vector<std::vector<glm::vec3>> cells;
        std::vector<float> areas;
        float total = 0.0f;
        for (std::uint32_t s : it->second) {
          cells.push_back(voronoi_cell(polygon, samples, it->second, s));
          areas.push_back(polygon_area(cells.back()));
          total += areas.back();
        }
        for (std::size_t c = 0; c < cells.size(); ++c) {
          float area = total > 0.0f ? areas[c] * part.area / total
                                    : part.area / static_cast<float>(cells.size());
          if (masked) {
            // Sampling rays pass the holes, so the cells tile the part with
            // its cut-away pieces in them: each carries its solid share.
            const std::vector<glm::vec3>& cell_polygon = areas[c] > 0.0f ? cells[c] : polygon;
            const float solid =
                scene.solid_fraction(part.triangle, cell_polygon.data(), cell_polygon.size());
            cut_away += static_cast<double>(area * (1.0f - solid));
            area *= solid;
          }
          if (area > 0.0f)
            carry(it->second[c], part_index, !front, areas[c] > 0.0f ? cells[c] : polygon, area,
                  false);
        }
        continue;
      }
      // A part no ray hit (a small triangle, or a sliver) goes whole to the
      // nearest sample of this voxel on the same surface: facing the same
      // way, with the whole part within kSameSurfaceCells of its plane, so
      // that light found anywhere on the part is that sample's. Without such
      // a sample the part gets its own at its centre: given to a sample on
      // another surface (the floor under a slab to the slab's top), it
      // would stand for light it does not receive, and rays that land on it
      // would find nothing.
      // A cut-away part is not there: nothing carries it. A partly cut
      // one is carried with its solid share of the area.
      float part_area = part.area;
      if (masked) {
        const float solid = scene.solid_fraction(part.triangle, polygon.data(), polygon.size());
        cut_away += static_cast<double>(part_area * (1.0f - solid));
        part_area *= solid;
        if (!(part_area > 0.0f)) continue;
      }
      const glm::vec3 n_side = front ? n_front : -n_front;
      const float tolerance = kSameSurfaceCells * cell;
      glm::vec3 centre(0.0f);
      for (const glm::vec3& x : polygon) centre += x;
      centre /= static_cast<float>(polygon.size());
      float best = std::numeric_limits<float>::infinity();
      std::int64_t best_index = -1;
      for (std::size_t s = 0; s < samples.size(); ++s) {
        if (glm::dot(samples[s].normal, n_side) <= 0.5f) continue;
        bool same_surface = true;
        for (const glm::vec3& x : polygon)
          same_surface = same_surface && std::abs(glm::dot(samples[s].position - x,
                                                           samples[s].normal)) <= tolerance;
        if (!same_surface) continue;
        const glm::vec3 d = samples[s].position - centre;
        const float dist2 = glm::dot(d, d);
        if (dist2 < best) {
          best = dist2;
          best_index = static_cast<std::int64_t>(s);
        }
      }
      if (best_index < 0) {
        if (!(part.area > 0.0f)) continue;
        const Material& m = scene.material_of(part.triangle);
        Sample own{};
        own.position = centre;
        own.normal = n_side;
        own.albedo = m.albedo;
        own.emission = m.emission;
        own.voxel = v;
        own.triangle = part.triangle;
        own.mesh = scene.triangle_mesh[part.triangle];
        best_index = static_cast<std::int64_t>(samples.size());
        samples.push_back(own);
        carried.emplace_back();
        centred += part_area;
        ++centre_samples;
      }
      carry(static_cast<std::size_t>(best_index), part_index, !front, polygon, part_area, true);
    }
  }
  // A hit exactly on the voxel's boundary can land on a triangle whose part
  // in this voxel has no area: such a sample carries nothing.
  VoxelSamples out;
  out.vertices = std::move(vertices);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    if (!(samples[s].area > 0.0f)) continue;
    out.samples.push_back(samples[s]);
    out.carried.push_back(std::move(carried[s]));
  }
  return out;
}

}  // namespace

SampleSet generate_samples(const Scene& scene, const RayTracer& tracer, const Voxelization& vox,
                           const SamplingSettings& settings, Progress* progress) {
  const std::size_t nv = vox.voxels.size();
  if (progress) progress->begin_stage("sample", nv);
  std::vector<VoxelSamples> per_voxel(nv);
  std::vector<double> centred(nv, 0.0);
  std::vector<std::size_t> centre_samples(nv, 0);
  std::vector<double> cut_away(nv, 0.0);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t v = 0; v < static_cast<std::int64_t>(nv); ++v) {
    if (progress && progress->should_stop()) continue;
    const auto vi = static_cast<std::size_t>(v);
    per_voxel[vi] = sample_voxel(scene, tracer, vox, static_cast<std::uint32_t>(v), settings,
                                 centred[vi], centre_samples[vi], cut_away[vi]);
    if (progress) progress->advance();
  }
  if (progress) progress->check();

  SampleSet set;
  set.first.reserve(nv + 1);
  set.carried_first.push_back(0);
  for (std::size_t v = 0; v < nv; ++v) {
    set.first.push_back(static_cast<std::uint32_t>(set.samples.size()));
    const VoxelSamples& vs = per_voxel[v];
    if (vs.samples.empty()) set.voxels_without_samples++;
    for (std::size_t s = 0; s < vs.samples.size(); ++s) {
      set.sampled_area += vs.samples[s].area;
      set.samples.push_back(vs.samples[s]);
      for (CarriedArea c : vs.carried[s]) {
        c.first_vertex += static_cast<std::uint32_t>(set.carried_vertices.size());
        set.carried.push_back(c);
      }
      set.carried_first.push_back(static_cast<std::uint32_t>(set.carried.size()));
    }
    set.centre_sampled_area += centred[v];
    set.centre_samples += centre_samples[v];
    set.cut_away_area += cut_away[v];
    set.carried_vertices.insert(set.carried_vertices.end(), vs.vertices.begin(), vs.vertices.end());
  }
  set.first.push_back(static_cast<std::uint32_t>(set.samples.size()));
  for (std::size_t t = 0; t < scene.triangle_count(); ++t)
    set.surface_area += scene.triangle_area(t) * (scene.two_sided(t) ? 2.0 : 1.0);
  if (progress) progress->end_stage();
  return set;
}

}  // namespace bounce
