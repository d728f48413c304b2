// Camera pictures gathered from a bake read back (bake/camera_gather.h):
// the folder keeps what a surface lookup needs, so that the lookup built
// from it names the same patch as the bake's own for every point a ray can
// hit; the gathered picture equals the final gather built from the bake in
// memory; its edge-aware filter keeps the light and removes grain; a folder
// without the polygons' triangles is refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "bake/camera_gather.h"
#include "bake/stored_transport.h"
#include "base/error.h"
#include "folder/bake_format.h"
#include "folder/bake_reader.h"
#include "io/npy.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/final_gather_build.h"
#include "runtime/relighter.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

struct Fixture {
  Scene scene;
  BakeResult bake;
  test::ScratchDir dir{"bounce-camera-gather"};
  LoadedBake loaded;

  Fixture() {
    Diagnostics d;
    scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
    BakeSettings s;
    s.voxel_resolution = 6;
    s.codec = CodecChoice::Dense;
    s.pictures = false;
    Progress progress;
    bake = Baker(scene, s, d).run(progress);
    write_bake(dir / "bake", scene, bake, d);
    loaded = BakeReader::read(dir / "bake");
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

CameraImageSettings small_camera() {
  CameraImageSettings cs;
  cs.width = 48;
  cs.height = 36;
  return cs;
}

TEST(CameraGather, LookupFromTheFolderNamesTheBakesPatchEverywhere) {
  const Fixture& f = fixture();
  ASSERT_TRUE(camera_gather_possible(f.loaded));
  const RayTracer tracer(f.scene);
  const SurfacePatchLookup own(f.bake.voxels, f.bake.samples, f.bake.patch_of_sample);
  const TransferGrid t = TransferGrid::from_manifest(f.loaded.manifest);
  const VoxelGrid grid = VoxelGrid::restore(t.origin, t.cell_size, t.dims);
  const SurfacePatchLookup read(grid, f.loaded.voxel_cells, f.loaded.samples,
                                f.loaded.patch_of_sample);
  // Rays from points spread through the box in every direction: the points
  // of surface light and gathers land on.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Bounds b = f.scene.bounds();
  std::size_t hits = 0, with_patch = 0;
  for (int k = 0; k < 20000; ++k) {
    const glm::vec3 from =
        b.lo +
        (b.hi - b.lo) * glm::vec3(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng));
    const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const glm::vec3 dir(s * std::cos(phi), s * std::sin(phi), z);
    const Hit h = tracer.intersect(from, dir);
    if (!h.hit) continue;
    ++hits;
    const bool back = glm::dot(dir, h.geometric_normal) > 0.0f;
    const glm::vec3 x = from + h.t * dir;
    const std::int32_t p = own.patch_at(h.triangle, back, x);
    ASSERT_EQ(read.patch_at(h.triangle, back, x), p) << "ray " << k;
    if (p >= 0) ++with_patch;
  }
  EXPECT_GT(hits, 15000u);
  EXPECT_GT(with_patch, hits / 2) << "most hits should land on a patch";
}

TEST(CameraGather, EqualsTheGatherBuiltFromTheBakeInMemory) {
  const Fixture& f = fixture();
  const RayTracer tracer(f.scene);
  const CameraImageSettings cs = small_camera();
  CameraGather pixels(tracer, f.loaded, cs, 64);
  pixels.set_filter_radius(0);
  // The frame's light: the scene's own lights through the exact matrix.
  Relighter relighter(tracer, f.loaded.samples, f.loaded.patches, stored_transport(f.loaded));
  relighter.light(f.scene.lights, area_lights(f.scene));
  const std::vector<glm::vec3> b = relighter.frame().first_hit(), tb = relighter.frame().indirect();
  const CameraImages images = pixels.images(b, tb, relighter.frame().sample_irradiance(),
                                            f.scene.lights, area_lights(f.scene));

  // The same picture from the in-memory bake's lookup and patches.
  std::vector<CameraHit> hits;
  CameraImages expected = render_camera_direct(tracer, cs, hits);
  std::vector<glm::vec3> positions, normals;
  for (const CameraHit& h : hits) {
    positions.push_back(h.position);
    normals.push_back(h.normal);
  }
  const SurfacePatchLookup own(f.bake.voxels, f.bake.samples, f.bake.patch_of_sample);
  FinalGatherSettings fg;
  fg.rays = 64;
  fg.seed = cs.seed;
  const FinalGather gather = build_final_gather(tracer, own, f.bake.patches.patches,
                                                f.bake.voxels.grid, positions, normals, fg);
  std::vector<glm::vec3> reflected(b.size()), e;
  for (std::size_t p = 0; p < b.size(); ++p) reflected[p] = b[p] + tb[p];
  gather.irradiance(
      reflected,
      sample_exitance(f.bake.samples, f.bake.patches, relighter.frame().sample_irradiance(), tb),
      near_exitance(gather.near, &tracer, f.scene.lights, area_lights(f.scene), tb), e);
  add_indirect(expected, hits, e);
  ASSERT_EQ(images.indirect.pixels.size(), expected.indirect.pixels.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < expected.indirect.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(images.indirect.pixels[i][c], expected.indirect.pixels[i][c],
                  1e-5f * (1.0f + expected.indirect.pixels[i][c]))
          << "pixel " << i;
    sum += expected.indirect.pixels[i].g;
  }
  EXPECT_GT(sum, 0.0);
}

TEST(CameraGather, FilterKeepsTheLightAndRemovesGrain) {
  const Fixture& f = fixture();
  const RayTracer tracer(f.scene);
  const CameraImageSettings cs = small_camera();
  CameraGather pixels(tracer, f.loaded, cs, 64);
  Relighter relighter(tracer, f.loaded.samples, f.loaded.patches, stored_transport(f.loaded));
  relighter.light(f.scene.lights, area_lights(f.scene));
  const auto& frame = relighter.frame();
  pixels.set_filter_radius(0);
  const CameraImages raw =
      pixels.images(frame.first_hit(), frame.indirect(), frame.sample_irradiance(), f.scene.lights,
                    area_lights(f.scene));
  pixels.set_filter_radius(3);
  const CameraImages smooth =
      pixels.images(frame.first_hit(), frame.indirect(), frame.sample_irradiance(), f.scene.lights,
                    area_lights(f.scene));
  // Light: the picture's total indirect light moves by a few percent at
  // most (the filter only moves light between neighbouring pixels of the
  // same surface; where a surface's light has a slope, the mean over a
  // window is its value at the centre).
  // Grain: the difference between horizontal neighbours, mostly noise in
  // a 64-ray gather, falls by more than half.
  double total_raw = 0.0, total_smooth = 0.0, grain_raw = 0.0, grain_smooth = 0.0;
  const int w = cs.width;
  for (std::size_t i = 0; i < raw.indirect.pixels.size(); ++i) {
    total_raw += raw.indirect.pixels[i].g;
    total_smooth += smooth.indirect.pixels[i].g;
    if (i % static_cast<std::size_t>(w) + 1 < static_cast<std::size_t>(w) && raw.coverage[i] > 0 &&
        raw.coverage[i + 1] > 0) {
      grain_raw += std::abs(raw.indirect.pixels[i + 1].g - raw.indirect.pixels[i].g);
      grain_smooth += std::abs(smooth.indirect.pixels[i + 1].g - smooth.indirect.pixels[i].g);
    }
  }
  ASSERT_GT(total_raw, 0.0);
  EXPECT_NEAR(total_smooth / total_raw, 1.0, 0.03);
  EXPECT_LT(grain_smooth, 0.5 * grain_raw);
}

TEST(CameraGather, AFolderWithoutTrianglesIsRefusedByName) {
  Fixture& f = fixture();
  // The carried polygons as bakes wrote them before they kept triangles:
  // three columns.
  const std::filesystem::path old = f.dir / "old";
  std::filesystem::copy(f.dir / "bake", old);
  const NpyArray<std::uint32_t> p = read_npy_u32(old / bake_file::kCarriedPolygons);
  std::vector<std::uint32_t> three;
  const std::size_t rows = p.shape[0];
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < carried_polygon_column::kCountWithoutTriangles; ++c)
      three.push_back(p.data[r * carried_polygon_column::kCount + c]);
  write_npy(old / bake_file::kCarriedPolygons, std::span<const std::uint32_t>(three),
            {rows, carried_polygon_column::kCountWithoutTriangles});
  const LoadedBake loaded = BakeReader::read(old);
  EXPECT_FALSE(camera_gather_possible(loaded));
  const RayTracer tracer(f.scene);
  try {
    CameraGather pixels(tracer, loaded, small_camera(), 64);
    FAIL() << "a folder without triangles was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bake it again"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bounce
