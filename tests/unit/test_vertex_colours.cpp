// Per-vertex colours multiply the albedo: read from PLY (8-bit, sRGB-encoded
// by convention, decoded here with the transfer function written out
// independently) and glTF (COLOR_0, linear), then seen alike by the bake's
// samples and patches, the camera pictures and the reference path tracer.
// The glTF floor's colour runs linearly from A at x = -1 to B at x = +1 (both
// corners of each side share a colour, so interpolating over either triangle
// gives that line exactly), and its base colour factor is F: the albedo at x
// is F x lerp(A, B, (x + 1) / 2), known by construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "base/diagnostics.h"
#include "gltf_quad.h"
#include "raytrace/ray_tracer.h"
#include "reference/path_tracer.h"
#include "runtime/camera_image.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"
#include "test_scenes.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

const glm::dvec3 kA(0.2, 0.6, 1.0), kB(1.0, 0.4, 0.1), kF(0.9, 0.8, 0.5);

glm::dvec3 albedo_at_x(double x) { return kF * glm::mix(kA, kB, (x + 1.0) / 2.0); }

bool near(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::dvec3(tolerance)));
}

std::string text(const glm::dvec3& v) {
  return std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z);
}

std::string warnings_of(const Diagnostics& d) {
  std::string out;
  for (const Diagnostic& w : d.warnings()) out += w.where + ": " + w.message + "\n";
  return out;
}

// The floor y = 0 over [-1, 1]^2 facing +y as a .gltf: corners at x = -1
// coloured `left`, at x = +1 `right` (COLOR_0 as float VEC3), base colour
// factor kF.
std::string gltf_floor(const glm::vec3& left, const glm::vec3& right) {
  std::string buffer;
  const auto put = [&](const auto& value) {
    buffer.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  for (const float f : {-1.f, 0.f, -1.f, -1.f, 0.f, 1.f, 1.f, 0.f, 1.f, 1.f, 0.f, -1.f}) put(f);
  for (const glm::vec3& c : {left, left, right, right}) put(c);
  for (const int i : {0, 1, 2, 0, 2, 3}) put(static_cast<std::uint16_t>(i));
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "name": "floor"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"name": "painted", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.5, 1]}}],
  "buffers": [{"byteLength": 108, "uri": "data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

class VertexColours : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& content) {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }
  // The glTF floor under a vertical sun of irradiance 1, the camera above.
  Scene floor_scene() {
    Scene s = SceneLoader(diagnostics)
                  .load(write("floor.gltf", gltf_floor(glm::vec3(kA), glm::vec3(kB))));
    s.lights.clear();
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    s.lights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 3.0f, 0.0f);
    s.camera.target = glm::vec3(0.0f);
    s.camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    s.camera.fov_y_deg = 30.0f;
    return s;
  }
  test::ScratchDir dir{"vertex-colours"};
  Diagnostics diagnostics;
};

// The sRGB transfer function, written out here independently of the loader.
double decode(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST_F(VertexColours, PlyColoursAreDecodedFromSrgbAndMultiplyTheAlbedo) {
  const fs::path ply = write("coloured.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nproperty uchar red\n"
                             "property uchar green\nproperty uchar blue\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             "0 0 0 255 0 128\n1 0 0 0 255 64\n0 1 0 128 32 255\n3 0 1 2\n");
  const Scene s = SceneLoader(diagnostics).load(ply);
  // The only warning is the missing material colour, not the vertex colours.
  ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
  EXPECT_NE(diagnostics.warnings()[0].message.find("no diffuse colour"), std::string::npos);
  ASSERT_TRUE(s.has_vertex_colours());
  ASSERT_EQ(s.triangle_colour.size(), 1u);
  const glm::dvec3 expected[3] = {{decode(255), decode(0), decode(128)},
                                  {decode(0), decode(255), decode(64)},
                                  {decode(128), decode(32), decode(255)}};
  const double grey = SceneLoader::kDefaultAlbedo;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(
        near(glm::dvec3(s.triangle_colour[0][static_cast<std::size_t>(k)]), expected[k], 1e-6))
        << "corner " << k;
    EXPECT_TRUE(near(glm::dvec3(s.albedo_at(0, s.vertex(0, k))), grey * expected[k], 1e-6))
        << "corner " << k;
  }
  // Interpolated linearly, not in sRGB: the centre is the corners' mean.
  const glm::vec3 centre = (s.vertex(0, 0) + s.vertex(0, 1) + s.vertex(0, 2)) / 3.0f;
  EXPECT_TRUE(near(glm::dvec3(s.albedo_at(0, centre)),
                   grey * (expected[0] + expected[1] + expected[2]) / 3.0, 1e-6));
}

TEST_F(VertexColours, MeshWithoutColoursKeepsItsAlbedo) {
  const fs::path ply = write("plain.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const Scene s = SceneLoader(diagnostics).load(ply);
  EXPECT_FALSE(s.has_vertex_colours());
  EXPECT_EQ(s.albedo_at(0, s.vertex(0, 1)), glm::vec3(SceneLoader::kDefaultAlbedo));
}

TEST_F(VertexColours, GltfColour0IsLinearTimesTheBaseColourFactor) {
  const Scene s = floor_scene();
  EXPECT_TRUE(diagnostics.warnings().empty()) << warnings_of(diagnostics);
  ASSERT_TRUE(s.has_vertex_colours());
  ASSERT_EQ(s.triangle_count(), 2u);
  for (std::size_t t = 0; t < 2; ++t)
    for (const float x : {-1.0f, -0.5f, 0.0f, 0.25f, 1.0f}) {
      // On the line z = 0, which crosses both triangles; the colour is
      // linear in x over either, so their interpolations agree on it.
      const glm::vec3 p(x, 0.0f, 0.0f);
      EXPECT_TRUE(near(glm::dvec3(s.albedo_at(t, p)), albedo_at_x(x), 1e-6))
          << "triangle " << t << " x " << x << ": " << text(glm::dvec3(s.albedo_at(t, p)));
    }
}

TEST_F(VertexColours, ColourOutsideTheUnitRangeIsClampedWithOneWarning) {
  const fs::path gltf =
      write("bright.gltf", gltf_floor(glm::vec3(1.5f, 0.5f, 0.5f), glm::vec3(0.5f)));
  const Scene s = SceneLoader(diagnostics).load(gltf);
  ASSERT_EQ(diagnostics.warnings().size(), 1u) << warnings_of(diagnostics);
  const Diagnostic w = diagnostics.warnings()[0];
  EXPECT_NE(w.where.find("bright.gltf"), std::string::npos) << w.where;
  EXPECT_NE(w.message.find("vertex colours outside [0, 1] clamped in 1 mesh: 'floor' (2)"),
            std::string::npos)
      << w.message;
  // 1.5 clamped to 1; the channels in range as given (glTF: linear).
  EXPECT_EQ(s.colour_at(0, glm::vec3(-1.0f, 0.0f, -1.0f)), glm::vec3(1.0f, 0.5f, 0.5f));
}

// Each patch's albedo is the colour's mean over what it stands for, so the
// patches' area-weighted mean is the floor's: F x (A + B) / 2; and a patch
// follows the colour where it lies.
TEST_F(VertexColours, BakedPatchAlbedoIsFactorTimesTheColour) {
  Scene s = floor_scene();
  // A plain ceiling facing the floor, for light to bounce between; without
  // vertex colours of its own it is white, its albedo its material's.
  test_scenes::add_quad(s, "ceiling", {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});
  s.triangle_colour.resize(s.triangle_count(), {glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f)});
  const std::uint32_t floor_mesh = 0;
  BakeSettings settings;
  settings.voxel_resolution = 8;
  settings.codec = CodecChoice::Dense;
  settings.transport.backend = TransportSettings::Backend::OpenBLAS;
  settings.pictures = false;
  Diagnostics d;
  Progress progress;
  const BakeResult bake = Baker(s, settings, d).run(progress);
  ASSERT_GT(bake.patches.patches.size(), 8u);
  glm::dvec3 sum(0.0);
  double area = 0.0, spread = 0.0;
  for (const Patch& p : bake.patches.patches) {
    if (p.mesh != floor_mesh) {
      // (to float rounding: a patch's albedo is its samples' mean)
      EXPECT_TRUE(near(glm::dvec3(p.albedo), glm::dvec3(0.5), 1e-6)) << "ceiling patch";
      continue;
    }
    sum += static_cast<double>(p.area) * glm::dvec3(p.albedo);
    area += static_cast<double>(p.area);
    // A patch spans a quarter of the floor's width at most; its albedo is
    // the colour's mean there, near the colour at its position.
    EXPECT_TRUE(near(glm::dvec3(p.albedo), albedo_at_x(p.position.x), 0.03))
        << "patch at x " << p.position.x << ": " << text(glm::dvec3(p.albedo)) << " expected "
        << text(albedo_at_x(p.position.x));
    spread = std::max(spread, std::abs(static_cast<double>(p.albedo.r) - kF.r * kA.r));
  }
  ASSERT_NEAR(area, 4.0, 1e-3);
  EXPECT_TRUE(near(sum / area, kF * 0.5 * (kA + kB), 1e-4))
      << text(sum / area) << " expected " << text(kF * 0.5 * (kA + kB));
  // The patches do follow the colour (not one mean colour for the floor).
  EXPECT_GT(spread, 0.5 * kF.r * (kB.r - kA.r));
}

// Under the vertical sun (irradiance 1) the direct light of a pixel is the
// albedo where its ray lands, in the camera picture and the reference alike.
TEST_F(VertexColours, CameraAndReferencePicturesShowTheColour) {
  const Scene s = floor_scene();
  const RayTracer tracer(s);
  CameraImageSettings settings;
  settings.width = settings.height = 32;
  std::vector<CameraHit> hits;
  const CameraImages images = render_camera_direct(tracer, settings, hits);
  ReferenceSettings rs;
  rs.samples = 4;
  const ReferencePathTracer pt(tracer, rs);
  ReferenceRenderer renderer(pt, 32, 32);
  renderer.add_samples(4);
  const ReferenceImages ref = renderer.images();
  ASSERT_GT(hits.size(), 100u);
  std::size_t checked = 0;
  for (const CameraHit& h : hits) {
    const glm::dvec3 expected = albedo_at_x(h.position.x);
    EXPECT_TRUE(near(glm::dvec3(images.direct.pixels[h.pixel]), expected, 1e-3))
        << "camera pixel " << h.pixel;
    // The reference jitters within the pixel: a linear colour averages to
    // its value near the centre, within a pixel's width of change.
    const glm::dvec3 ref_direct(ref.full.pixels[h.pixel] - ref.indirect.pixels[h.pixel]);
    if (ref.coverage[h.pixel] < 1.0f) continue;  // the floor's edge
    EXPECT_TRUE(near(ref_direct, expected, 2e-2))
        << "reference pixel " << h.pixel << ": " << text(ref_direct) << " expected "
        << text(expected);
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

// A point 5 cm above the floor facing down sees floor around x = -0.5
// almost only: its indirect light is the albedo there (the floor's colour
// is linear, so what it sees averages to the colour below it), not the
// colour at the middle nor the material's factor alone.
TEST_F(VertexColours, ReferenceBouncesOffTheColouredAlbedo) {
  const Scene s = floor_scene();
  const RayTracer tracer(s);
  ReferenceSettings rs;
  rs.samples = 4000;
  const ReferencePathTracer pt(tracer, rs);
  ReferencePoint p;
  p.position = glm::vec3(-0.5f, 0.05f, 0.0f);
  p.normal = glm::vec3(0.0f, -1.0f, 0.0f);
  const glm::dvec3 e(pt.estimate_points({p}).indirect_irradiance[0]);
  const glm::dvec3 expected = albedo_at_x(-0.5);
  EXPECT_TRUE(near(e, expected, 0.03)) << text(e) << " expected " << text(expected);
}

}  // namespace
}  // namespace bounce
