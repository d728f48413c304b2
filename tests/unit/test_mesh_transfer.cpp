// Light on patches back onto the scene's mesh and into pictures from the
// scene camera: normalised weights (a constant comes back unchanged), no leak
// through a wall thinner than a voxel, the PLY file as a viewer reads it, and
// camera images whose parts add up, whose background is black and which
// mirror with the scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "bake/bake.h"
#include "base/diagnostics.h"
#include "io/exr_writer.h"
#include "io/ply_writer.h"
#include "io/png_writer.h"
#include "io/tone_map.h"
#include "patches/surface_patch_lookup.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/camera_image.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_build.h"
#include "runtime/mesh_transfer.h"
#include "runtime/patch_gather.h"
#include "scene/scene_loader.h"
#include "test_scenes.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

class MeshTransferTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("bounce-mesh-transfer-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
};

BakeResult tiny_bake(const Scene& scene, int voxels) {
  Diagnostics d;
  BakeSettings bs;
  bs.voxel_resolution = voxels;
  bs.codec = CodecChoice::Dense;
  bs.pictures = false;
  Progress progress;
  return Baker(scene, bs, d).run(progress);
}

// The Cornell box and a bake of it at voxel 5, shared by the tests below.
struct Cornell {
  Scene scene;
  BakeResult bake;
};
const Cornell& cornell() {
  static const Cornell c = [] {
    Diagnostics d;
    Cornell r;
    r.scene = SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
    r.bake = tiny_bake(r.scene, 5);
    return r;
  }();
  return c;
}

float edge_length_max(const LitMesh& m) {
  float longest = 0.0f;
  for (const glm::uvec3& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, glm::length(m.positions[t[k]] - m.positions[t[(k + 1) % 3]]));
  return longest;
}

TEST(MeshTransfer, ConstantLightOnEveryPatchComesBackOnEveryLitVertex) {
  const Cornell& c = cornell();
  const RayTracer tracer(c.scene);
  const TransferGrid grid = TransferGrid::from(c.bake.voxels.grid);
  // The grid as a bake folder's manifest gives it is the same grid.
  const glm::vec3 lo = c.bake.voxels.grid.bounds().lo;
  const glm::ivec3 dims = c.bake.voxels.grid.dims();
  nlohmann::json manifest;
  manifest["grid"] = {{"origin", {lo.x, lo.y, lo.z}},
                      {"cell_size", c.bake.voxels.grid.cell_size()},
                      {"dims", {dims.x, dims.y, dims.z}}};
  const TransferGrid read = TransferGrid::from_manifest(manifest);
  EXPECT_EQ(read.origin, grid.origin);
  EXPECT_EQ(read.cell_size, grid.cell_size);
  EXPECT_EQ(read.dims, grid.dims);
  manifest["grid"].erase("cell_size");
  EXPECT_THROW(TransferGrid::from_manifest(manifest), Error);

  const glm::vec3 constant(0.3f, 0.5f, 0.7f);
  const std::vector<glm::vec3> light(c.bake.patches.size(), constant);
  const TransferSettings settings;
  const LitMesh m = transfer_to_mesh(tracer, c.bake.patches.patches, grid, light, settings);

  std::printf(
      "cornell voxel 5: %zu patches, %zu triangles -> %zu faces, %zu vertices "
      "(%zu edge splits, %zu crease vertices, %zu duplicated faces), %zu dark, "
      "%zu widened, %zu rays\n",
      c.bake.patches.size(), m.counts.scene_triangles, m.counts.faces, m.counts.vertices,
      m.counts.split_edges, m.counts.crease_vertices, m.counts.duplicated_faces,
      m.counts.dark_vertices, m.counts.widened_vertices, m.counts.occlusion_rays);
  ASSERT_EQ(m.positions.size(), m.counts.vertices);
  ASSERT_EQ(m.normals.size(), m.counts.vertices);
  ASSERT_EQ(m.radiosity.size(), m.counts.vertices);
  ASSERT_EQ(m.triangles.size(), m.counts.faces);
  ASSERT_EQ(m.source_triangle.size(), m.counts.faces);
  // Big walls were refined to half a voxel, and the box's corners split.
  EXPECT_GT(m.counts.split_edges, 0u);
  EXPECT_LE(edge_length_max(m), settings.max_edge_cells * grid.cell_size * 1.0001f);
  EXPECT_GT(m.counts.crease_vertices, 0u);
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
  // Every face keeps its source triangle's orientation.
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    const glm::vec3 cross =
        glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    if (glm::length(cross) < 1e-9f) continue;
    ASSERT_GT(glm::dot(cross, c.scene.triangle_cross(m.source_triangle[f])), 0.0f) << f;
  }

  std::size_t dark = 0;
  for (const glm::vec3& r : m.radiosity) {
    if (r == glm::vec3(0.0f)) {
      ++dark;
      continue;
    }
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(r[k], constant[k], 1e-5f);
  }
  EXPECT_EQ(dark, m.counts.dark_vertices);
  // Dark vertices would be where no patch is seen; vertices on the lines
  // where walls meet must not be among them (their rays start in the
  // neighbouring wall's plane).
  EXPECT_LT(static_cast<double>(dark), 0.01 * static_cast<double>(m.counts.vertices));
}

// A box with a thin slab (thickness 0.12 voxel) a little above its floor
// (0.6 voxel): only the slab's top side is lit.
struct SlabScene {
  static constexpr float kBottom = 0.10f, kTop = 0.12f, kLo = 0.3f, kHi = 0.7f;
  Scene scene;
  BakeResult bake;
  std::vector<glm::vec3> light;
};
const SlabScene& slab_scene() {
  static const SlabScene s = [] {
    SlabScene r;
    r.scene = test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(0.0f));
    r.scene.name = "thin-slab";
    const float b = SlabScene::kBottom, t = SlabScene::kTop, lo = SlabScene::kLo,
                hi = SlabScene::kHi;
    const glm::vec3 p[8] = {{lo, b, lo}, {hi, b, lo}, {hi, b, hi}, {lo, b, hi},
                            {lo, t, lo}, {hi, t, lo}, {hi, t, hi}, {lo, t, hi}};
    // Outward-facing, closed.
    test_scenes::add_mesh(r.scene, "slab", std::vector<glm::vec3>(p, p + 8),
                          {{0, 1, 2},
                           {0, 2, 3},
                           {4, 7, 6},
                           {4, 6, 5},
                           {0, 4, 5},
                           {0, 5, 1},
                           {3, 2, 6},
                           {3, 6, 7},
                           {0, 3, 7},
                           {0, 7, 4},
                           {1, 5, 6},
                           {1, 6, 2}});
    r.bake = tiny_bake(r.scene, 6);
    for (const Patch& patch : r.bake.patches.patches) {
      const bool top = patch.normal.y > 0.9f && std::abs(patch.position.y - t) < 1e-3f;
      r.light.push_back(glm::vec3(top ? 1.0f : 0.0f));
    }
    return r;
  }();
  return s;
}

struct SlabLevels {
  double top_mean = 0.0;    // slab's lit side
  double bottom_max = 0.0;  // slab's far side
  double floor_max = 0.0;   // floor under the slab, same normal as the lit side
  std::size_t top = 0, bottom = 0, floor = 0;
};

SlabLevels slab_levels(const LitMesh& m) {
  using S = SlabScene;
  SlabLevels l;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const glm::vec3 p = m.positions[v], n = m.normals[v];
    const double r = m.radiosity[v].r;
    const bool inside = p.x > S::kLo + 1e-3f && p.x < S::kHi - 1e-3f && p.z > S::kLo + 1e-3f &&
                        p.z < S::kHi - 1e-3f;
    if (n.y > 0.99f && std::abs(p.y - S::kTop) < 1e-5f) {
      l.top_mean += r;
      ++l.top;
    } else if (n.y < -0.99f && std::abs(p.y - S::kBottom) < 1e-5f) {
      l.bottom_max = std::max(l.bottom_max, r);
      ++l.bottom;
    } else if (n.y > 0.99f && p.y < 1e-5f && inside) {
      l.floor_max = std::max(l.floor_max, r);
      ++l.floor;
    }
  }
  if (l.top > 0) l.top_mean /= static_cast<double>(l.top);
  return l;
}

TEST(MeshTransfer, NoLightLeaksThroughAWallThinnerThanAVoxel) {
  const SlabScene& s = slab_scene();
  const RayTracer tracer(s.scene);
  const TransferGrid grid = TransferGrid::from(s.bake.voxels.grid);
  ASSERT_LT(SlabScene::kTop - SlabScene::kBottom, 0.2f * grid.cell_size);
  ASSERT_LT(SlabScene::kBottom, grid.cell_size);
  TransferSettings settings;
  const LitMesh m = transfer_to_mesh(tracer, s.bake.patches.patches, grid, s.light, settings);
  const SlabLevels l = slab_levels(m);
  std::printf(
      "thin slab: %zu patches (%zu lit); lit side mean %.4f over %zu vertices, far side "
      "max %.2e over %zu, floor under it max %.2e over %zu\n",
      s.bake.patches.size(),
      static_cast<std::size_t>(std::count(s.light.begin(), s.light.end(), glm::vec3(1.0f))),
      l.top_mean, l.top, l.bottom_max, l.bottom, l.floor_max, l.floor);
  ASSERT_GT(l.top, 10u);
  ASSERT_GT(l.bottom, 10u);
  ASSERT_GT(l.floor, 10u);
  EXPECT_GT(l.top_mean, 0.5);
  EXPECT_LT(l.bottom_max, 0.01 * l.top_mean);
  EXPECT_LT(l.floor_max, 0.01 * l.top_mean);

  // Without occlusion rays the far side still stays dark (its normal
  // disagrees), but the floor, facing the same way as the lit top less than
  // a voxel above it, catches its light: the rays are what stop that.
  settings.gather.visibility = false;
  const SlabLevels blind =
      slab_levels(transfer_to_mesh(tracer, s.bake.patches.patches, grid, s.light, settings));
  std::printf("without occlusion rays: far side max %.2e, floor under it max %.2e\n",
              blind.bottom_max, blind.floor_max);
  EXPECT_LT(blind.bottom_max, 0.01 * blind.top_mean);
  EXPECT_GT(blind.floor_max, 0.1 * blind.top_mean);
}

TEST(MeshTransfer, FinalGatherSeesNoLightThroughAWallThinnerThanAVoxel) {
  // The final gather's rays see what each vertex sees: the slab's far side
  // and the floor under it see nothing of its lit top, exactly.
  const SlabScene& s = slab_scene();
  const RayTracer tracer(s.scene);
  const TransferGrid grid = TransferGrid::from(s.bake.voxels.grid);
  LitMesh m = build_transfer_mesh(s.scene, grid, TransferSettings{});
  const SurfacePatchLookup lookup(s.bake.voxels, s.bake.samples, s.bake.patch_of_sample);
  const FinalGather g =
      build_final_gather(tracer, lookup, s.bake.patches.patches, s.bake.voxels.grid,
                         gather_points_of_vertices(m.positions, m.triangles), m.normals, {});
  g.validate("slab gather");
  // Each sample source carries its patch's light.
  std::vector<glm::vec3> sample_light(s.bake.samples.samples.size(), glm::vec3(0.0f));
  for (std::size_t p = 0; p < s.bake.patches.size(); ++p)
    for (std::uint32_t k = s.bake.patches.member_first[p]; k < s.bake.patches.member_first[p + 1];
         ++k)
      sample_light[s.bake.patches.member_samples[k]] = s.light[p];
  // And so does each near source.
  std::vector<glm::vec3> near_light(g.near.size());
  for (std::size_t k = 0; k < near_light.size(); ++k) near_light[k] = s.light[g.near.patch[k]];
  g.irradiance(s.light, sample_light, near_light, m.radiosity);
  const SlabLevels l = slab_levels(m);
  std::printf(
      "final gather, thin slab: far side max %.2e over %zu, floor under it max %.2e over "
      "%zu; lit side mean %.4f\n",
      l.bottom_max, l.bottom, l.floor_max, l.floor, l.top_mean);
  // The walls and ceiling do see the lit top.
  double lit = 0.0;
  for (const glm::vec3& e : m.radiosity) lit = std::max(lit, static_cast<double>(e.r));
  std::printf("final gather: brightest vertex %.4f\n", lit);
  EXPECT_GT(lit, 0.01);
  ASSERT_GT(l.bottom, 10u);
  ASSERT_GT(l.floor, 10u);
  EXPECT_EQ(l.bottom_max, 0.0);
  EXPECT_EQ(l.floor_max, 0.0);
}

TEST(MeshTransfer, NonManifoldFacesGetTheirOwnVerticesAndTwoSidedFacesABackCopy) {
  // Three triangles on one edge (a complex edge), plus a two-sided square.
  Scene s = test_scenes::parallel_squares();
  // A fin on the bottom square's edge 0-1, sharing its vertices (one soup,
  // one vertex list), once with each winding: the second face would give
  // the edge a third face.
  const auto apex = static_cast<std::uint32_t>(s.positions.size());
  s.positions.push_back({0.5f, 0.5f, 0.5f});
  Material fin;
  fin.name = "fin";
  fin.albedo = glm::vec3(0.5f);
  s.materials.push_back(fin);
  s.meshes.push_back({"fin", "memory", 4, 2, false, 1.0f});
  for (const glm::uvec3 t : {glm::uvec3(1, 0, apex), glm::uvec3(0, 1, apex)}) {
    s.triangles.push_back(t);
    s.triangle_material.push_back(2);
    s.triangle_mesh.push_back(2);
  }
  test_scenes::add_mesh(s, "sheet", {{0, 0, 0.5f}, {1, 0, 0.5f}, {1, 1, 0.5f}, {0, 1, 0.5f}},
                        {{0, 1, 2}, {0, 2, 3}}, glm::vec3(0.5f), glm::vec3(0.0f), true);
  TransferGrid grid;
  grid.origin = glm::vec3(-0.01f);
  grid.cell_size = 0.5f;
  grid.dims = glm::ivec3(3);
  TransferSettings settings;
  settings.max_edge_cells = 10.0f;  // no refinement: count faces exactly
  const LitMesh m = build_transfer_mesh(s, grid, settings);
  EXPECT_EQ(m.counts.scene_triangles, 8u);
  EXPECT_EQ(m.counts.back_faces, 2u);
  EXPECT_EQ(m.counts.faces, 10u) << "nothing dropped";
  EXPECT_EQ(m.counts.duplicated_faces, 1u);
  // The sheet's back copy faces -z, its front +z, at the same positions.
  std::size_t up = 0, down = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    if (std::abs(m.positions[v].z - 0.5f) < 1e-6f && m.positions[v].x > 0.9f &&
        m.positions[v].y > 0.9f) {
      if (m.normals[v].z > 0.99f) ++up;
      if (m.normals[v].z < -0.99f) ++down;
    }
  EXPECT_EQ(up, 1u);
  EXPECT_EQ(down, 1u);
}

// Reads a binary little-endian PLY as any viewer would: header lines, then
// fixed-size vertex records and uchar-counted int index lists.
struct PlyFile {
  std::vector<std::string> header;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> vertex_properties;
  std::string body;
};
PlyFile read_ply(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  PlyFile f;
  std::string line;
  while (std::getline(in, line)) {
    f.header.push_back(line);
    std::istringstream words(line);
    std::string a, b, c;
    words >> a >> b >> c;
    if (a == "element" && b == "vertex") f.vertices = std::stoul(c);
    if (a == "element" && b == "face") f.faces = std::stoul(c);
    if (a == "property" && f.faces == 0 && b != "list") f.vertex_properties.push_back(b + " " + c);
    if (line == "end_header") break;
  }
  f.body.assign(std::istreambuf_iterator<char>(in), {});
  return f;
}
float le_f32(const std::string& s, std::size_t at) {
  std::uint32_t u = 0;
  for (int b = 0; b < 4; ++b)
    u |= static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + static_cast<std::size_t>(b)]))
         << (8 * b);
  return std::bit_cast<float>(u);
}

TEST_F(MeshTransferTest, PlyRoundTrip) {
  std::vector<glm::vec3> pos, nrm, rad;
  std::vector<glm::uvec3> tri;
  for (int i = 0; i < 200; ++i) {
    // A spiral staircase: a fan from vertex 0 with no degenerate triangle.
    const float x = static_cast<float>(i);
    pos.push_back({(1.0f + 0.1f * x) * std::cos(0.3f * x), 0.05f * x,
                   (1.0f + 0.1f * x) * std::sin(0.3f * x)});
    nrm.push_back(glm::normalize(glm::vec3(1.0f, x, 2.0f)));
    rad.push_back({0.01f * x, 0.02f * x + 0.001f, 0.5f});
    if (i >= 2) tri.push_back({0u, static_cast<unsigned>(i - 1), static_cast<unsigned>(i)});
  }
  const fs::path path = dir / "mesh.ply";
  const float exposure = write_lit_ply(path, {pos, nrm, rad, tri});
  const PlyFile f = read_ply(path);
  ASSERT_GE(f.header.size(), 3u);
  EXPECT_EQ(f.header[0], "ply");
  EXPECT_EQ(f.header[1], "format binary_little_endian 1.0");
  EXPECT_EQ(f.header.back(), "end_header");
  EXPECT_EQ(f.vertices, 200u);
  EXPECT_EQ(f.faces, 198u);
  const std::vector<std::string> expected = {
      "float x",    "float y",          "float z",          "float nx",
      "float ny",   "float nz",         "uchar red",        "uchar green",
      "uchar blue", "float radiance_r", "float radiance_g", "float radiance_b"};
  EXPECT_EQ(f.vertex_properties, expected);
  ASSERT_TRUE(std::find(f.header.begin(), f.header.end(),
                        "property list uchar int vertex_indices") != f.header.end());
  constexpr std::size_t kVertex = 9 * 4 + 3;  // nine floats, three bytes
  ASSERT_EQ(f.body.size(), 200 * kVertex + 198 * 13);
  for (std::size_t v : {0u, 1u, 57u, 199u}) {
    const std::size_t at = v * kVertex;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(le_f32(f.body, at + 4 * static_cast<std::size_t>(k)), pos[v][k]);
      EXPECT_EQ(le_f32(f.body, at + 12 + 4 * static_cast<std::size_t>(k)), nrm[v][k]);
      EXPECT_EQ(static_cast<unsigned char>(f.body[at + 24 + static_cast<std::size_t>(k)]),
                ToneMap::srgb8(exposure * rad[v][k]));
      EXPECT_EQ(le_f32(f.body, at + 27 + 4 * static_cast<std::size_t>(k)), rad[v][k]);
    }
  }
  // The 99th percentile of luminance maps to 0.9.
  std::vector<float> lum;
  for (const glm::vec3& r : rad) lum.push_back(luminance(r));
  std::sort(lum.begin(), lum.end());
  EXPECT_NEAR(exposure * lum[static_cast<std::size_t>(std::lround(0.99 * 199))], 0.9f, 1e-5f);
  const std::size_t faces_at = 200 * kVertex;
  for (std::size_t t : {0u, 100u, 197u}) {
    const std::size_t at = faces_at + t * 13;
    EXPECT_EQ(f.body[at], 3);
    for (int k = 0; k < 3; ++k) {
      std::uint32_t idx = 0;
      std::memcpy(&idx, &f.body[at + 1 + 4 * static_cast<std::size_t>(k)], 4);
      EXPECT_EQ(idx, tri[t][k]);
    }
  }
  // Nothing but the file is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);

  // A third-party reader (Assimp, through the scene loader) opens it whole.
  Diagnostics d;
  const Scene back = SceneLoader(d).load(path);
  EXPECT_EQ(back.triangle_count(), tri.size());
  Bounds bounds;
  for (const glm::vec3& p : pos) bounds.extend(p);
  EXPECT_EQ(back.bounds().lo, bounds.lo);
  EXPECT_EQ(back.bounds().hi, bounds.hi);
}

// Indirect light (T b) of the scene's own lights on the Cornell bake.
std::vector<glm::vec3> cornell_indirect(const Cornell& c, const RayTracer& tracer) {
  const std::vector<glm::vec3> b =
      first_bounce(c.bake.patches, direct_irradiance(tracer, c.bake.samples, c.bake.patches,
                                                     c.scene.lights, area_lights(c.scene)));
  const std::size_t n = b.size();
  std::vector<glm::vec3> tb(n, glm::vec3(0.0f));
  for (int ch = 0; ch < 3; ++ch) {
    const MatrixValues& t = c.bake.transport.channel(ch).t;
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      for (std::size_t j = 0; j < n; ++j) sum += double(t[i * n + j]) * b[j][ch];
      tb[i][ch] = static_cast<float>(sum);
    }
  }
  return tb;
}

// The scene mirrored in x (winding reversed so normals mirror too).
Scene mirrored(Scene s) {
  for (glm::vec3& p : s.positions) p.x = -p.x;
  for (glm::uvec3& t : s.triangles) std::swap(t[1], t[2]);
  for (Light& l : s.lights) {
    l.position.x = -l.position.x;
    l.direction.x = -l.direction.x;
  }
  s.camera.position.x = -s.camera.position.x;
  s.camera.target.x = -s.camera.target.x;
  s.camera.up.x = -s.camera.up.x;
  return s;
}

TEST_F(MeshTransferTest, CameraImagesOfTheCornellBox) {
  const Cornell& c = cornell();
  const RayTracer tracer(c.scene);
  const TransferGrid grid = TransferGrid::from(c.bake.voxels.grid);
  const std::vector<glm::vec3> indirect = cornell_indirect(c, tracer);
  const PatchGather gather(c.bake.patches.patches, indirect, grid, &tracer, GatherSettings{});
  CameraImageSettings settings;
  settings.width = 64;
  settings.height = 48;
  const CameraImages img = render_camera(tracer, gather, settings);
  std::printf("camera 64x48: %zu hit pixels, %zu dark hits, %zu back hits\n", img.hit_pixels,
              img.dark_hits, img.back_hits);

  std::size_t background = 0, lit = 0, with_indirect = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const std::size_t p = img.full.index(x, y);
      ASSERT_EQ(img.full.pixels[p], img.direct.pixels[p] + img.indirect.pixels[p]);
      if (img.coverage[p] == 0.0f) {
        ++background;
        EXPECT_EQ(img.full.pixels[p], glm::vec3(0.0f));
        EXPECT_EQ(img.direct.pixels[p], glm::vec3(0.0f));
        // Background means the camera ray really misses the scene.
        const glm::vec3 d =
            camera_ray_direction(c.scene.camera, settings.width, settings.height,
                                 static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        EXPECT_FALSE(tracer.intersect(c.scene.camera.position, d).hit) << x << ", " << y;
      }
      if (luminance(img.full.pixels[p]) > 0.0f) ++lit;
      if (luminance(img.indirect.pixels[p]) > 0.0f) ++with_indirect;
    }
  // The camera looks through the open front of the box: its outside is
  // background, its inside is lit, directly or by bounced light.
  EXPECT_GT(background, 0u);
  EXPECT_EQ(img.hit_pixels + background, img.full.pixels.size());
  EXPECT_GT(lit, img.hit_pixels * 9 / 10);
  EXPECT_GT(with_indirect, img.hit_pixels * 8 / 10);
  // The centre of the picture is the back wall: lit.
  EXPECT_GT(luminance(img.full.at(32, 24)), 0.0f);

  // Files: EXR exact, PNG tone-mapped and not black, nothing else left behind.
  const float exposure = write_camera_images(img, dir, "cornell");
  EXPECT_GT(exposure, 0.0f);
  for (const char* part : {"direct", "indirect", "full"}) {
    const RgbFloatImage exr = read_exr(dir / (std::string("cornell_") + part + ".exr"));
    const RgbFloatImage& mine = std::string(part) == "direct"     ? img.direct
                                : std::string(part) == "indirect" ? img.indirect
                                                                  : img.full;
    ASSERT_EQ(exr.width, 64);
    ASSERT_EQ(exr.height, 48);
    EXPECT_EQ(exr.pixels, mine.pixels) << part;
    const Rgb8Image png = read_png(dir / (std::string("cornell_") + part + ".png"));
    ASSERT_EQ(png.width, 64);
    EXPECT_GT(*std::max_element(png.pixels.begin(), png.pixels.end()), 100) << part;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 6);
}

TEST(MeshTransfer, CameraImageMirrorsWithTheScene) {
  // The same bake and light, the scene, its patches, grid and lights
  // mirrored in x: the picture must mirror. Emission is off in both so the
  // area lights' random jitter (seeded per pixel) does not differ.
  const Cornell& c = cornell();
  Scene scene = c.scene;
  for (Material& m : scene.materials) m.emission = glm::vec3(0.0f);
  const Scene mirror = mirrored(scene);
  ASSERT_EQ(scene.camera.position.x, 0.0f) << "the Cornell camera sits on the mirror plane";
  const RayTracer tracer(scene), mirror_tracer(mirror);
  const TransferGrid grid = TransferGrid::from(c.bake.voxels.grid);
  TransferGrid mirror_grid = grid;
  mirror_grid.origin.x = -(grid.origin.x + static_cast<float>(grid.dims.x) * grid.cell_size);
  std::vector<Patch> mirror_patches = c.bake.patches.patches;
  for (Patch& p : mirror_patches) {
    p.position.x = -p.position.x;
    p.normal.x = -p.normal.x;
  }
  const std::vector<glm::vec3> indirect = cornell_indirect(c, tracer);
  const PatchGather gather(c.bake.patches.patches, indirect, grid, &tracer, {});
  const PatchGather mirror_gather(mirror_patches, indirect, mirror_grid, &mirror_tracer, {});
  CameraImageSettings settings;
  settings.width = 48;
  settings.height = 36;
  const CameraImages a = render_camera(tracer, gather, settings);
  const CameraImages b = render_camera(mirror_tracer, mirror_gather, settings);
  std::size_t close = 0, hits = 0;
  double diff = 0.0, total = 0.0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const glm::vec3 p = a.full.at(x, y), q = b.full.at(settings.width - 1 - x, y);
      if (a.coverage[a.full.index(x, y)] == 0.0f) continue;
      ++hits;
      const float d = glm::length(p - q);
      diff += d;
      total += glm::length(p);
      if (d <= 1e-3f * glm::length(p) + 1e-6f) ++close;
    }
  std::printf("mirror: %zu of %zu hit pixels within 0.1%%, mean |difference| %.2e of the mean\n",
              close, hits, diff / total);
  // Silhouette pixels may flip with rounding; the rest agree.
  EXPECT_GT(close, hits * 97 / 100);
  EXPECT_LT(diff / total, 5e-3);
}

}  // namespace
}  // namespace bounce
