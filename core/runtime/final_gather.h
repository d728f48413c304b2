#pragma once
// Final gather: the indirect light at output points (mesh vertices, camera
// pixels) gathered from the patches through precomputed, visibility-checked
// point-to-patch form factors, instead of interpolated from nearby patches.
//
// Patches are a few per voxel, 1-2 m across on an architectural scene; the
// light that matters to the eye changes within centimetres (the bright foot
// of a sunlit pillar, the dark under an arch). A point's irradiance is the
// light arriving from everything it sees, and that is what the gather sums:
//
//   E(x) = sum_p F_xp B_p,   indirect light leaving x = albedo(x) E(x),
//
// with B_p the light leaving patch p after at least one reflection (the
// first-hit light b plus the multi-bounce T b) and F_xp the form factor from
// the point to the surface patch p stands for, visibility included.
//
// F_xp by rays: cosine-distributed directions from x (a stratified Fibonacci
// pattern, rotated per point), each first hit given to the patch standing for
// the surface it lands on (patches/surface_patch_lookup.h): the share of rays
// landing on p is an unbiased estimate of F_xp, and the rays see exactly what
// x sees, so there is no leak through walls and no light from behind a pillar.
// Rays that escape, hit a one-sided back face or unsampled surface carry
// nothing, as light does there.
//
// Storage: the `kept` strongest patches per point exactly; the weaker ones
// are folded into their clusters -- the patches of a block of voxels facing
// the same way -- whose light each frame is the mean of their patches'
// weighted by the rays folded into each (see seen weights below). Every ray keeps its weight, so
// each point's total (its closure) stays exact, and light concentrated in small patches (the
// ceiling above a lamp) is not lost: spreading the weak patches' share over the kept ones instead
// took 15% of the Cornell box's indirect light at 4000 patches. A frame is then a sparse product of
// a few dozen entries per point.
//
// Sample sources (optional): a patch's light is its mean over 1-2 m, but the
// first-hit light b changes within centimetres (a sun shadow's edge, the lit
// and the turned-away face of one column in one patch). The samples a point's
// rays hit most can be kept as sources of their own, carrying the sample's
// own b plus its patch's T b; the rest of the patch keeps the patch's mean.
// The frame computes b per sample anyway (the direct light is traced from
// every sample), so this costs only the extra entries.
//
// Near sources (optional): a sample stands for a piece of surface a quarter
// of a voxel across, and its b is the direct light at its centre. A point
// within centimetres of a sunlit ledge sees the part of the ledge next to
// it, lit or shaded whatever the sample's centre is: on Sponza the 1% of
// vertices next to sunlit ledges held 83% of the squared vertex error,
// reading 3-40 times too little light. Rays that land within `near`
// voxels of their point therefore go to near sources instead: small cells
// of one triangle's surface within one sample (`near_resolution` per voxel
// edge), merged over all points, each lit every frame at its own position
// (one shadow ray per light, as a sample is) and carrying its own b plus its
// patch's T b. A cell holds one triangle only: a sample carries every small
// face of a moulding that faces its way, and a cell mixing the top and the
// side of a ledge was lit at the mean of their points, inside the moulding,
// with one face's normal (on Sponza that left the first bounce at the
// vertices 5% low, and the sunlit mouldings' undersides half as bright as
// their own surface makes them). Each is lit at the mean of the points that
// landed in it, unless a ray a hair above the surface from the first of them
// (in point and ray order, so whatever the thread count) to the mean is
// blocked: then it is lit at that first point. One triangle can run on under
// a block standing on it (a parapet's top under a column's base), and the
// mean of the points landing in front of the base and beside it fell under
// the base, in its shade: on the sunlit Sponza, vertices at the foot of such
// bases read 3% of the reference's light. (Lighting every source at its first
// point instead was worse over the whole scene: a point on a cell's edge
// stands for the cell less well than its mean.)
//
// Spots (optional): a sample's first-hit light is the direct light at its
// centre, but the part of a sample the gather's rays land on is not its
// centre: the top of a ledge more than its shaded front, a column's face
// toward the court more than its back. The light a point reads from a sample
// is the light where its rays landed. Far rays (not near sources) are
// therefore grouped by the cell (`spot_resolution` per voxel edge) and
// triangle they landed on within each sample, over all points; the `spots`
// cells most rays landed in become points lit every frame, one shadow ray
// per light as near sources are, and the sample's light is the sample's
// albedo times their irradiance weighted by those rays, plus its patch's
// T b. On the sunlit Sponza the centres' light left the vertices' mean
// indirect level 2-5% low at 4000-16000 patches. Spots are kept as near
// sources past the ones the rows read, so every caller that lights the near
// sources lights them too.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/progress.h"
#include "patches/patch_set.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_light_cache.h"
#include "runtime/area_lights.h"
#include "runtime/gather_row_budget.h"
#include "runtime/mesh_transfer.h"
#include "runtime/shadow_budget.h"

namespace bounce {

namespace gather_loops {
struct PaddedLight;  // runtime/gather_row_loops.h
}  // namespace gather_loops

// Surface cells lit on their own each frame (see near sources above): the
// mean of the points the rays landed on (or the first of them, see above),
// the side they landed on, the mean albedo there, and the patch whose
// multi-bounce light T b they carry.
struct NearSources {
  std::vector<glm::vec3> position, normal, albedo;
  std::vector<std::uint32_t> patch;
  // The last `spot_count` are spots (FinalGather::spot_first). Under an area
  // light a spot takes one jittered shadow ray per emissive triangle where a
  // near source takes kAreaStrata squared: a sample's light averages its
  // spots, and a point's light the hundreds of samples it reads, so the
  // jitter averages out, while 16 rays for each of the Cornell box's 48,900
  // spots made a light move 2.5 times as long.
  std::size_t spot_count = 0;
  std::size_t size() const { return position.size(); }
};

// Sparse rows: point i gathers weight[k] * L[source[k]] for k in
// [first[i], first[i + 1]), where L holds the patches' light, then the
// clusters' (source - patches), then the samples' (source - patches -
// clusters; only when `samples` > 0), then the near sources' (source -
// patches - clusters - samples).
struct FinalGather {
  std::vector<std::uint64_t> first;  // points + 1
  std::vector<std::uint32_t> source;
  std::vector<float> weight;
  std::size_t patches = 0;  // size of the B it multiplies
  // Per patch: its cluster, and its share of the cluster's light (its share
  // of the rays folded into the cluster; of its area where none were).
  std::vector<std::uint32_t> cluster_of_patch;
  std::vector<float> cluster_share;
  std::size_t clusters = 0;
  // Seen weights (rows read samples; empty: a patch reads its own light): a
  // patch's light as its entries read it is the mean of its samples' light
  // (b + T b) weighted by how many of the rays read through the patch (or
  // its cluster) landed on each, over all points -- not by area. Within a
  // patch, the parts open to the sun are the parts other surfaces see
  // (the top of a ledge, a column's face toward the open court), so an area
  // mean weighs the shaded parts the gather's rays seldom reach as much as
  // the lit ones. Summed over all points, the light the patch entries carry
  // is then what sample entries would carry. Patch p's samples are
  // seen_sample[k], weight seen_weight[k], k in [seen_first[p],
  // seen_first[p + 1]); a patch with none reads its own light.
  std::vector<std::uint32_t> seen_first, seen_sample;
  std::vector<float> seen_weight;
  // Sample sources: the sample count of the bake (0: the rows read no sample
  // and there are no near sources).
  std::size_t samples = 0;
  NearSources near;
  // Spots (empty: samples are lit at their centres): sample s's light is
  // sum over k in [spot_first[s], spot_first[s + 1]) of spot_weight[k] x the
  // light of near source spot_base() + k (its albedo is the sample's); a
  // sample with none keeps its centre's light. The spots are the last
  // spot_first.back() near sources; no row reads them.
  std::vector<std::uint32_t> spot_first;
  std::vector<float> spot_weight;
  std::size_t spots() const { return spot_first.empty() ? 0 : spot_first.back(); }
  std::size_t spot_base() const { return near.size() - spots(); }
  int rays = 0;
  // Where the rays went (at build time): onto a patch, out of the scene,
  // onto the back of a one-sided triangle, onto surface no patch stands for.
  std::size_t rays_landed = 0, rays_escaped = 0, rays_back = 0, rays_unrepresented = 0;
  // Points shut inside the geometry (more than half their rays met the back
  // of a one-sided face): their rows are empty and their rays counted
  // nowhere else.
  std::size_t points_enclosed = 0;
  // Of the landed rays, those that went to near sources.
  std::size_t rays_near = 0;

  // The rows again, four bytes an entry: a ray count in the low
  // `compact_count_bits` bits, the source above them (weight = count /
  // compact_rays, exactly the float weight). Every weight is a whole number
  // of the point's rays, so this loses nothing, and the product, which
  // streams the rows every frame, reads half the bytes. Empty when the rows
  // do not fit (weights not whole ray counts, or too many sources for the
  // bits left); the product then reads `source` and `weight`.
  std::vector<std::uint32_t> compact;
  int compact_count_bits = 0, compact_rays = 0;
  // The loop that sums the compact rows ("sse2", "avx2", "avx512"; see
  // runtime/gather_row_loops.h): the fastest of those this CPU has, timed on
  // these rows by compact_rows(). A caller may name another this CPU has.
  std::string compact_loop;
  // Fills `compact` from the rows (after building or reading them, or after
  // any change to them) and picks `compact_loop`.
  void compact_rows();

  std::size_t points() const { return first.empty() ? 0 : first.size() - 1; }
  // E at every point from the light leaving each patch (size `patches`).
  // Throws bounce::Error when sizes differ, or when the rows read samples.
  void irradiance(const std::vector<glm::vec3>& patch_exitance, std::vector<glm::vec3>& out) const;
  // The same when the rows read samples: `sample_exitance` (size `samples`)
  // is sample_exitance() of the frame. Without sample sources it is ignored.
  void irradiance(const std::vector<glm::vec3>& patch_exitance,
                  const std::vector<glm::vec3>& sample_exitance, std::vector<glm::vec3>& out) const;
  // The same when the rows read near sources: `near_exitance` (size
  // near.size()) is near_exitance() of the frame.
  void irradiance(const std::vector<glm::vec3>& patch_exitance,
                  const std::vector<glm::vec3>& sample_exitance,
                  const std::vector<glm::vec3>& near_exitance, std::vector<glm::vec3>& out) const;
  // One frame of a relighter: the near sources lit as near_exitance() lights
  // them (shadow rays from `tracer` to `lights` and `area`, plus their
  // patch's T b from `patch_indirect`), written straight into the product's
  // buffer, then E at every point as irradiance() gives it. `near_seconds`
  // (if given): the time lighting the near sources took. `area_cache` (if
  // given) keeps the near sources' light from the area lights between
  // frames (runtime/area_light_cache.h); `shadow_budget` (if given)
  // spreads the shadow rays to the other lights over frames while they
  // move (runtime/shadow_budget.h). `row_budget` (if given) sums only some
  // rows while the sources' light is not exact (runtime/gather_row_budget.h):
  // exact when `sources_exact` (the patches' and samples' light, from the
  // frame) and the near sources' shadows are; the rows it leaves keep what
  // `out` held, so `out` must hold this gather's last product. Use each with
  // this gather only.
  void irradiance_lighting_near(
      const std::vector<glm::vec3>& patch_exitance, const std::vector<glm::vec3>& sample_exitance,
      const RayTracer& tracer, const std::vector<Light>& lights, const std::vector<AreaLight>& area,
      const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out,
      double* near_seconds = nullptr, AreaLightCache* area_cache = nullptr,
      ShadowBudget* shadow_budget = nullptr, GatherRowBudget* row_budget = nullptr,
      bool sources_exact = true) const;
  // Checks the rows: monotone offsets, sources in range, finite weights in
  // [0, 1], row totals at most 1 (+ rounding), clusters' shares. Throws
  // bounce::Error naming `what` and the first bad row.
  void validate(const std::string& what) const;

 private:
  void check_light(const std::vector<glm::vec3>& patch_exitance,
                   const std::vector<glm::vec3>& sample_exitance) const;
  // The product from the padded light of every source, over the rows
  // `slice` takes.
  void sum_padded(const gather_loops::PaddedLight* light, std::vector<glm::vec3>& out,
                  RowSlice slice = {}) const;
};

// The light a sample source carries: the sample's own first-hit light
// albedo_s E_s (E_s: its direct irradiance, `sample_irradiance`) plus its
// patch's multi-bounce T b (`patch_indirect`); 0 for left-out samples.
std::vector<glm::vec3> sample_exitance(const SampleSet& samples, const PatchSet& patches,
                                       const std::vector<glm::vec3>& sample_irradiance,
                                       const std::vector<glm::vec3>& patch_indirect);
// The same into `out`, whose memory a caller lighting frame after frame keeps.
void sample_exitance(const SampleSet& samples, const PatchSet& patches,
                     const std::vector<glm::vec3>& sample_irradiance,
                     const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out);

// The light near sources carry: albedo x their direct irradiance (shadow
// rays from `tracer` to `lights` and `area`; no tracer: none, for callers
// that want the multi-bounce part alone) plus their patch's T b.
std::vector<glm::vec3> near_exitance(const NearSources& near, const RayTracer* tracer,
                                     const std::vector<Light>& lights,
                                     const std::vector<AreaLight>& area,
                                     const std::vector<glm::vec3>& patch_indirect);
// The same into `out`.
void near_exitance(const NearSources& near, const RayTracer* tracer,
                   const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                   const std::vector<glm::vec3>& patch_indirect, std::vector<glm::vec3>& out);

// Where the vertices of a lit mesh gather from: each moved 5% of the way to
// the centroid of a face using it. A vertex on the line where two walls meet
// lies in the other wall's plane, where rays slip behind that wall; a point
// just inside its own face sees the corner as the face does.
std::vector<glm::vec3> gather_points_of_vertices(const std::vector<glm::vec3>& positions,
                                                 const std::vector<glm::uvec3>& triangles);

// Lights a lit mesh's vertices: radiosity = emission + albedo x (direct
// irradiance, shadowed, at the vertex's gather point + `gathered`, the
// indirect irradiance its final gather summed). Albedo and emission come from
// a scene triangle the vertex's faces stand for.
void light_vertices(const RayTracer& tracer, const std::vector<Light>& lights,
                    const std::vector<AreaLight>& area, const std::vector<glm::vec3>& gathered,
                    LitMesh& mesh);

}  // namespace bounce
