// SceneLoader: the shipped scenes load as documented (counts, exact MTL
// colours, orientation of the analytic scenes), and every bad input either
// fails with a LoadError naming the file and the problem or loads with a
// warning saying what was repaired. Format: docs/scene-format.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "runtime/probe_volume.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

const fs::path kScenes = fs::path(BOUNCE_RESOURCE_DIR) / "scenes";

Scene load_quietly(const fs::path& path, Diagnostics& diagnostics) {
  return SceneLoader(diagnostics).load(path);
}

glm::vec3 unit_normal(const Scene& s, std::size_t tri) {
  return glm::normalize(s.triangle_cross(tri));
}

glm::vec3 centroid(const Scene& s, std::size_t tri) {
  return (s.vertex(tri, 0) + s.vertex(tri, 1) + s.vertex(tri, 2)) / 3.0f;
}

const MeshInfo* find_mesh(const Scene& s, const std::string& name) {
  for (const MeshInfo& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

const Material* find_material(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return &m;
  return nullptr;
}

std::string all_warnings(const Diagnostics& d) {
  std::string text;
  for (const Diagnostic& w : d.warnings()) text += w.where + ": " + w.message + "\n";
  return text;
}

// Number of warnings whose message contains every one of `words`.
std::size_t count_warnings(const Diagnostics& d, std::initializer_list<std::string> words) {
  std::size_t n = 0;
  for (const Diagnostic& w : d.warnings()) {
    bool all = true;
    for (const std::string& word : words) all = all && w.message.find(word) != std::string::npos;
    n += all ? 1 : 0;
  }
  return n;
}

}  // namespace

// ---------------------------------------------------------------- shipped scenes

TEST(SceneLoaderShipped, CornellBoxHasExactMtlColoursAndAnAreaLight) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "cornell-box", d);
  // Each box's "Bottom Face" in the OBJ repeats its right face (same corners,
  // same winding): both copies are skipped, summed up in one warning that
  // names both meshes, with the full list in its detail.
  ASSERT_EQ(d.warnings().size(), 1u) << all_warnings(d);
  EXPECT_EQ(count_warnings(d, {"skipped 4 duplicate triangles in 2 meshes",
                               "'leftWall/shortBox' (2)", "'shortBox' (2)"}),
            1u)
      << all_warnings(d);
  EXPECT_EQ(d.warnings()[0].detail.size(), 2u);
  EXPECT_EQ(s.name, "cornell-box");
  // 18 quads in the OBJ (5 walls, 6 + 6 box faces, 1 light), 2 triangles
  // each, less the two duplicated quads.
  EXPECT_EQ(s.triangle_count(), 32u);
  EXPECT_EQ(s.triangle_material.size(), 32u);
  EXPECT_EQ(s.triangle_mesh.size(), 32u);
  EXPECT_EQ(s.materials.size(), 8u);

  const Material* left = find_material(s, "leftWall");
  ASSERT_NE(left, nullptr);
  EXPECT_EQ(left->albedo, glm::vec3(0.63f, 0.065f, 0.05f));  // exact, not 8-bit quantised
  EXPECT_FALSE(left->is_emissive());
  const Material* right = find_material(s, "rightWall");
  ASSERT_NE(right, nullptr);
  EXPECT_EQ(right->albedo, glm::vec3(0.14f, 0.45f, 0.091f));
  const Material* light = find_material(s, "light");
  ASSERT_NE(light, nullptr);
  EXPECT_EQ(light->emission, glm::vec3(17.0f, 12.0f, 4.0f));  // Ke 17 12 4
  EXPECT_EQ(light->albedo, glm::vec3(0.78f));
  std::size_t emissive = 0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) emissive += s.material_of(t).is_emissive();
  EXPECT_EQ(emissive, 2u);

  const Bounds b = s.bounds();
  EXPECT_NEAR(b.lo.x, -1.02f, 1e-6f);
  EXPECT_NEAR(b.hi.x, 1.0f, 1e-6f);
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.hi.y, 1.99f, 1e-6f);
  EXPECT_NEAR(b.lo.z, -1.04f, 1e-6f);
  EXPECT_NEAR(b.hi.z, 0.99f, 1e-6f);

  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  EXPECT_LT(s.lights[0].position.y, 1.98f);  // below the ceiling light
  EXPECT_EQ(s.camera.position, glm::vec3(0.0f, 1.0f, 3.4f));
  EXPECT_EQ(s.camera.target, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 40.0f);
  EXPECT_EQ(s.defaults.voxel_resolution, 16);
  EXPECT_EQ(s.defaults.patches_per_voxel, 3);
  EXPECT_FALSE(s.defaults.patches_total.has_value());

  // Mesh ranges tile the triangle list in order.
  std::uint32_t next = 0;
  for (std::size_t m = 0; m < s.meshes.size(); ++m) {
    EXPECT_EQ(s.meshes[m].first_triangle, next);
    for (std::uint32_t t = 0; t < s.meshes[m].triangle_count; ++t)
      EXPECT_EQ(s.triangle_mesh[next + t], m);
    next += s.meshes[m].triangle_count;
  }
  EXPECT_EQ(next, 32u);

  // The floor faces up into the box.
  const MeshInfo* floor = find_mesh(s, "floor");
  ASSERT_NE(floor, nullptr);
  EXPECT_GT(unit_normal(s, floor->first_triangle).y, 0.99f);
}

TEST(SceneLoaderShipped, CornellBunnyStandsOnTheFloor) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "cornell-bunny", d);
  EXPECT_EQ(d.warnings().size(), 1u) << all_warnings(d);  // the box's duplicated faces
  const MeshInfo* bunny = find_mesh(s, "bunny");
  ASSERT_NE(bunny, nullptr);
  EXPECT_EQ(bunny->triangle_count, 69451u);  // bun_zipper: no degenerate triangles
  EXPECT_EQ(s.triangle_count(), 32u + 69451u);

  Bounds b;
  for (std::uint32_t t = bunny->first_triangle; t < bunny->first_triangle + bunny->triangle_count;
       ++t) {
    for (int c = 0; c < 3; ++c) b.extend(s.vertex(t, c));
    EXPECT_EQ(s.material_of(t).name, "bunny");
  }
  EXPECT_NEAR(b.lo.y, 0.0f, 1e-5f);
  EXPECT_NEAR(b.hi.y - b.lo.y, 0.6f, 0.01f);
  // Inside the box, clear of the walls.
  EXPECT_GT(b.lo.x, -0.99f);
  EXPECT_LT(b.hi.x, 1.0f);
  EXPECT_GT(b.lo.z, -1.04f);
  EXPECT_LT(b.hi.z, 0.99f);

  const Material* mat = find_material(s, "bunny");
  ASSERT_NE(mat, nullptr);
  EXPECT_EQ(mat->albedo, glm::vec3(0.7f));
  // The box's materials still come from the shared MTL.
  const Material* left = find_material(s, "leftWall");
  ASSERT_NE(left, nullptr);
  EXPECT_EQ(left->albedo, glm::vec3(0.63f, 0.065f, 0.05f));
}

TEST(SceneLoaderShipped, ParallelSquaresFaceEachOther) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "parallel-squares", d);
  EXPECT_EQ(d.warnings().size(), 0u) << all_warnings(d);
  ASSERT_EQ(s.triangle_count(), 4u);
  const MeshInfo* bottom = find_mesh(s, "bottom");
  const MeshInfo* top = find_mesh(s, "top");
  ASSERT_NE(bottom, nullptr);
  ASSERT_NE(top, nullptr);
  EXPECT_EQ(bottom->triangle_count, 2u);
  EXPECT_EQ(top->triangle_count, 2u);
  for (std::uint32_t i = 0; i < 2; ++i) {
    const std::size_t tb = bottom->first_triangle + i, tt = top->first_triangle + i;
    EXPECT_EQ(unit_normal(s, tb), glm::vec3(0, 0, 1));
    EXPECT_EQ(unit_normal(s, tt), glm::vec3(0, 0, -1));
    EXPECT_GT(glm::dot(unit_normal(s, tb), centroid(s, tt) - centroid(s, tb)), 0.f);
    EXPECT_GT(glm::dot(unit_normal(s, tt), centroid(s, tb) - centroid(s, tt)), 0.f);
    EXPECT_FLOAT_EQ(s.triangle_area(tb), 0.5f);
    EXPECT_EQ(s.material_of(tb).name, "bottom");
    EXPECT_EQ(s.material_of(tt).name, "top");
    EXPECT_EQ(s.material_of(tb).albedo, glm::vec3(0.5f));
    EXPECT_FALSE(s.material_of(tt).is_emissive());
  }
  EXPECT_EQ(s.defaults.voxel_resolution, 8);
}

TEST(SceneLoaderShipped, PerpendicularSquaresShareAnEdgeAndFaceEachOther) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "perpendicular-squares", d);
  EXPECT_EQ(d.warnings().size(), 0u) << all_warnings(d);
  ASSERT_EQ(s.triangle_count(), 4u);
  const MeshInfo* floor = find_mesh(s, "floor");
  const MeshInfo* wall = find_mesh(s, "wall");
  ASSERT_NE(floor, nullptr);
  ASSERT_NE(wall, nullptr);
  for (std::uint32_t i = 0; i < 2; ++i) {
    const std::size_t tf = floor->first_triangle + i, tw = wall->first_triangle + i;
    EXPECT_EQ(unit_normal(s, tf), glm::vec3(0, 1, 0));
    EXPECT_EQ(unit_normal(s, tw), glm::vec3(0, 0, 1));
    EXPECT_GT(glm::dot(unit_normal(s, tf), centroid(s, tw) - centroid(s, tf)), 0.f);
    EXPECT_GT(glm::dot(unit_normal(s, tw), centroid(s, tf) - centroid(s, tw)), 0.f);
  }
  const Bounds b = s.bounds();
  EXPECT_EQ(b.lo, glm::vec3(0.0f));
  EXPECT_EQ(b.hi, glm::vec3(1.0f));
}

TEST(SceneLoaderShipped, CoaxialDisksAreFansFacingEachOther) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "coaxial-disks", d);
  EXPECT_EQ(d.warnings().size(), 0u) << all_warnings(d);
  const MeshInfo* small = find_mesh(s, "small");
  const MeshInfo* large = find_mesh(s, "large");
  ASSERT_NE(small, nullptr);
  ASSERT_NE(large, nullptr);
  EXPECT_EQ(small->triangle_count, 128u);
  EXPECT_EQ(large->triangle_count, 128u);
  auto check = [&](const MeshInfo& m, float radius, float z, float nz) {
    double area = 0.0;
    for (std::uint32_t t = m.first_triangle; t < m.first_triangle + m.triangle_count; ++t) {
      EXPECT_NEAR(unit_normal(s, t).z, nz, 1e-6f);
      area += s.triangle_area(t);
      for (int c = 0; c < 3; ++c) {
        const glm::vec3 p = s.vertex(t, c);
        EXPECT_EQ(p.z, z);
        EXPECT_LE(std::hypot(p.x, p.y), radius * (1.0f + 1e-6f));
      }
    }
    // A 128-gon inscribed in the circle: area = (n/2) r^2 sin(2 pi / n).
    const double expected = 64.0 * radius * radius * std::sin(2.0 * std::numbers::pi / 128.0);
    EXPECT_NEAR(area, expected, 1e-6);
  };
  check(*small, 0.1f, 0.0f, 1.0f);
  check(*large, 0.2f, 0.5f, -1.0f);
}

TEST(SceneLoaderShipped, FurnaceIsAClosedCubeFacingInward) {
  Diagnostics d;
  const Scene s = load_quietly(kScenes / "furnace", d);
  EXPECT_EQ(d.warnings().size(), 0u) << all_warnings(d);
  ASSERT_EQ(s.triangle_count(), 12u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "box");
  const glm::vec3 centre(0.5f);
  float total_area = 0.f;
  for (std::size_t t = 0; t < 12; ++t) {
    const glm::vec3 n = unit_normal(s, t);
    // Axis-aligned and pointing to the centre.
    EXPECT_GT(glm::dot(n, centre - centroid(s, t)), 0.f) << "triangle " << t;
    EXPECT_FLOAT_EQ(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.f);
    total_area += s.triangle_area(t);
    EXPECT_EQ(s.material_of(t).name, "wall");
    EXPECT_EQ(s.material_of(t).albedo, glm::vec3(0.5f));
    EXPECT_EQ(s.material_of(t).emission, glm::vec3(1.0f));
  }
  EXPECT_FLOAT_EQ(total_area, 6.f);
  EXPECT_TRUE(s.lights.empty());  // emissive walls are the light
}

TEST(SceneLoaderShipped, EveryShippedSceneLoadsWithoutOtherWarnings) {
  std::size_t scenes = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (!entry.is_directory()) continue;
    Diagnostics d;
    const Scene s = load_quietly(entry.path(), d);
    EXPECT_GT(s.triangle_count(), 0u) << entry.path();
    // The Cornell OBJ's duplicated box faces are the one known, reported flaw.
    EXPECT_EQ(d.warnings().size(), count_warnings(d, {"duplicate triangles"}))
        << entry.path() << "\n"
        << all_warnings(d);
    EXPECT_EQ(s.name, entry.path().filename().string());
    for (const Material& m : s.materials) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(m.albedo[c], 0.f);
        EXPECT_LT(m.albedo[c], 1.f);
      }
    }
    ++scenes;
  }
  EXPECT_GE(scenes, 6u);
}

// ---------------------------------------------------------------- bad inputs

class SceneLoaderInput : public ::testing::Test {
 protected:
  test::ScratchDir scratch{"bounce-scene"};
  const fs::path dir = scratch.path();

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  // A unit right triangle in z=0 facing +z, with an MTL giving it a colour.
  fs::path write_triangle_obj(const std::string& name = "tri.obj") const {
    write("tri.mtl", "newmtl grey\nKd 0.25 0.5 0.75\n");
    return write(name, "mtllib tri.mtl\no tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n");
  }

  // Expects load(path) to throw a LoadError whose where() is `where` and whose
  // message contains every one of `words`; returns the message.
  std::string expect_error(const fs::path& path, const fs::path& where,
                           const std::vector<std::string>& words) {
    try {
      (void)SceneLoader(diagnostics).load(path);
    } catch (const SceneLoader::LoadError& e) {
      EXPECT_EQ(e.where(), where.string());
      const std::string what = e.what();
      for (const std::string& word : words)
        EXPECT_NE(what.find(word), std::string::npos) << "missing '" << word << "' in: " << what;
      return what;
    }
    ADD_FAILURE() << "no LoadError for " << path;
    return {};
  }

  Scene load(const fs::path& path) { return SceneLoader(diagnostics).load(path); }

  Diagnostics diagnostics;
};

TEST_F(SceneLoaderInput, MissingPathFolderWithoutSceneJsonAndNonRegularFile) {
  expect_error(dir / "nope", dir / "nope", {"no such file"});
  fs::create_directories(dir / "empty");
  expect_error(dir / "empty", dir / "empty", {"no scene.json"});
  fs::create_directories(dir / "odd" / "scene.json");
  expect_error(dir / "odd", dir / "odd" / "scene.json", {"not a regular file"});
}

TEST_F(SceneLoaderInput, MalformedJsonGivesLineAndColumn) {
  write_triangle_obj();
  // Line 4 lacks its comma; the parser notices at the string on line 5.
  const fs::path json = write("scene.json",
                              "{\n"
                              "  \"meshes\": [\n"
                              "    { \"file\": \"tri.obj\" }\n"
                              "  ]\n"
                              "  \"bake\": { \"voxel\": 8 }\n"
                              "}\n");
  const std::string what = expect_error(json, json, {"scene.json:5:8:", "expected '}'"});
  // The same position nlohmann reports itself.
  EXPECT_NE(what.find("unexpected string literal"), std::string::npos) << what;

  const fs::path eof = write("eof/scene.json", "{\n  \"meshes\": [\n");
  expect_error(eof, eof, {"scene.json:3:1:", "unexpected end of input"});

  const fs::path overflow = write("big/scene.json", "{\n  \"meshes\": [],\n  \"x\": 1e999\n}\n");
  expect_error(overflow, overflow, {"scene.json:3:8:", "1e999"});
}

TEST_F(SceneLoaderInput, WrongTypesNameTheKeyPath) {
  write_triangle_obj();
  struct Case {
    std::string json;
    std::vector<std::string> words;
  };
  const std::string mesh = R"("meshes": [{"file": "tri.obj"}])";
  const Case cases[] = {
      {"{" + mesh + R"(, "materials": {"leftWall": {"albedo": "red"}}})",
       {"materials.leftWall.albedo", "expected an array of 3 numbers", "a string (\"red\")"}},
      {"{" + mesh + R"(, "materials": {"leftWall": {"albedo": [1, 2]}}})",
       {"materials.leftWall.albedo", "an array of 2 elements"}},
      {"{" + mesh + R"(, "materials": {"grey": {"emission": [1, -1, 0]}}})",
       {"materials.grey.emission", "negative"}},
      {R"({"meshes": [{"file": 3}]})", {"meshes[0].file", "expected a string"}},
      {R"({"meshes": [{"name": "x"}]})", {"meshes[0]", "missing key `file`"}},
      {R"({"meshes": {"file": "tri.obj"}})", {"meshes", "expected an array"}},
      {R"({"meshes": []})", {"meshes", "is empty"}},
      {R"({"bake": {}})", {"meshes", "missing"}},
      {"[1, 2]", {"top level must be an object"}},
      {"{" + mesh + R"(, "camera": {"position": [0, 0, 1], "target": [0, 0, 1]}})",
       {"camera", "same point"}},
      {"{" + mesh + R"(, "camera": {"position": [0, 0, 1], "target": [0, 0, 0], "up": [0, 0, 2]}})",
       {"camera.up", "parallel"}},
      {"{" + mesh +
           R"(, "camera": {"position": [0, 0, 1], "target": [0, 0, 0], "fov_y_deg": 180}})",
       {"camera.fov_y_deg", "(0, 180)"}},
      {R"({"meshes": [{"file": "tri.obj", "transform": {"scale": [1, 0, 1]}}]})",
       {"meshes[0].transform", "singular"}},
      {R"({"meshes": [{"file": "tri.obj", "transform": {"scale": "big"}}]})",
       {"meshes[0].transform.scale", "a number or an array of 3 numbers"}},
      {R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}}]})",
       {"meshes[0].transform.matrix", "4 rows of 4 numbers"}},
      {R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]}}]})",
       {"meshes[0].transform.matrix[3]", "[0, 0, 0, 1]"}},
      {R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], "scale": 2}}]})",
       {"meshes[0].transform", "not both"}},
      {R"({"meshes": [{"file": "tri.obj", "two_sided": "yes"}]})",
       {"meshes[0].two_sided", "expected true or false"}},
      {R"({"meshes": [{"file": "tri.obj", "material": 7}]})",
       {"meshes[0].material", "a material name or a material object"}},
      {R"({"meshes": [{"file": "tri.obj", "material": "nosuch"}]})",
       {"meshes[0].material", "unknown material 'nosuch'"}},
      {R"({"meshes": [{"file": "tri.obj", "material": {"name": "m"}}], "materials": {"m": {}}})",
       {"meshes[0].material", "already defined at materials.m"}},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE("case " + std::to_string(i) + ": " + cases[i].json);
    const fs::path json = write("case" + std::to_string(i) + "/scene.json", cases[i].json);
    // Mesh files are resolved next to the scene.json.
    fs::copy_file(dir / "tri.obj", json.parent_path() / "tri.obj");
    fs::copy_file(dir / "tri.mtl", json.parent_path() / "tri.mtl");
    expect_error(json, json, cases[i].words);
  }
}

TEST_F(SceneLoaderInput, AbsurdBakeDefaultsAreFatalNamingTheKey) {
  write_triangle_obj();
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {R"("voxel": 0)", {"bake.voxel", "between 1 and 4096", "got 0"}},
      {R"("voxel": -3)", {"bake.voxel", "got -3"}},
      {R"("voxel": 5000)", {"bake.voxel", "got 5000"}},
      {R"("voxel": 16.5)", {"bake.voxel", "non-integer 16.5"}},
      {R"("voxel": "16")", {"bake.voxel", "a string"}},
      {R"("patches_total": 0)", {"bake.patches_total", "got 0"}},
      {R"("patches_per_voxel": -1)", {"bake.patches_per_voxel", "got -1"}},
      {R"("samples_per_face": 2.5)", {"bake.samples_per_face", "non-integer"}},
      {R"("samples_per_face": 18446744073709551615)", {"bake.samples_per_face"}},
      {R"("error_budget": 0)", {"bake.error_budget", "between 0 and 1"}},
      {R"("error_budget": 1.5)", {"bake.error_budget", "between 0 and 1"}},
      {R"("error_budget": "2%")", {"bake.error_budget"}},
      {R"("light_probes": "some")", {"bake.light_probes", "\"volumes\""}},
      {R"("light_probes": 1)", {"bake.light_probes"}},
      {R"("light_probe_volumes": {"min": [0, 0, 0]})", {"bake.light_probe_volumes", "array"}},
      {R"("light_probe_volumes": [{"min": [0, 0, 0], "max": [1, 1, 1]}])",
       {"bake.light_probe_volumes[0].spacing", "missing"}},
      {R"("light_probe_volumes": [{"min": [0, 0, 0], "max": [1, 1, 1], "spacing": 0}])",
       {"bake.light_probe_volumes[0].spacing", "positive"}},
      {R"("light_probe_volumes": [{"min": [0, 0, 0], "max": [1, 1, 1], "spacing": -1}])",
       {"bake.light_probe_volumes[0].spacing", "positive"}},
      {R"("light_probe_volumes": [{"min": [1, 0, 0], "max": [0, 1, 1], "spacing": 0.5}])",
       {"bake.light_probe_volumes[0]", "below"}},
      {R"("light_probe_volumes": [{"min": [0, 0], "max": [1, 1, 1], "spacing": 0.5}])",
       {"bake.light_probe_volumes[0].min"}},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].first);
    const fs::path json =
        write("scene" + std::to_string(i) + ".json",
              R"({"meshes": [{"file": "tri.obj"}], "bake": {)" + cases[i].first + "}}");
    expect_error(json, json, cases[i].second);
  }
  // An integer written as a float is an integer.
  const fs::path ok = write(
      "ok.json",
      R"({"meshes": [{"file": "tri.obj"}], "bake": {"voxel": 16.0, "patches_total": 4000, "patches_per_voxel": 3, "samples_per_face": 64, "error_budget": 0.03}})");
  const Scene s = load(ok);
  EXPECT_EQ(s.defaults.voxel_resolution, 16);
  EXPECT_EQ(s.defaults.patches_total, 4000);
  EXPECT_EQ(s.defaults.patches_per_voxel, 3);
  EXPECT_EQ(s.defaults.samples_per_face, 64);
  EXPECT_NEAR(s.defaults.error_budget.value_or(0.0), 0.03, 1e-7);
  // Light probes: a switch (a bool counts) and volumes as the setting's text.
  const fs::path probes = write(
      "probes.json",
      R"({"meshes": [{"file": "tri.obj"}], "bake": {"light_probes": false, "light_probe_volumes": [{"min": [0, 0, 0], "max": [1, 2, 3], "spacing": 0.25}, {"min": [-1, -1, -1], "max": [1, 1, 1], "spacing": 0.1}]}})");
  const Scene p = load(probes);
  EXPECT_EQ(p.defaults.light_probes, "off");
  const std::vector<ProbeVolume> v =
      parse_probe_volumes(p.defaults.light_probe_volumes, "light_probe_volumes");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].hi, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(v[0].spacing, 0.25f);
  EXPECT_EQ(v[1].lo, glm::vec3(-1.0f));
  EXPECT_EQ(v[1].spacing, 0.1f);
}

TEST_F(SceneLoaderInput, PatchDensityIsAPositiveBoundedNumberNamedInErrors) {
  write_triangle_obj();
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"0", {"meshes[0].patch_density", "> 0 and <= 64", "got 0"}},
      {"-1", {"meshes[0].patch_density", "> 0 and <= 64", "got -1"}},
      {"65", {"meshes[0].patch_density", "got 65"}},
      {"1e300", {"meshes[0].patch_density", "got 1e+300"}},
      {R"("x")", {"meshes[0].patch_density", "a string"}},
      {R"("NaN")", {"meshes[0].patch_density", "a string"}},
      {"null", {"meshes[0].patch_density", "null"}},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].first);
    const fs::path json =
        write("density" + std::to_string(i) + ".json",
              R"({"meshes": [{"file": "tri.obj", "patch_density": )" + cases[i].first + "}]}");
    const std::string what = expect_error(json, json, cases[i].second);
    // One error, about this key only.
    EXPECT_EQ(what.find("patch_density"), what.rfind("patch_density")) << what;
  }
  // JSON has no NaN literal: a bare NaN is a syntax error at its position.
  const fs::path nan = write("nan.json",
                             "{\"meshes\": [{\"file\": \"tri.obj\",\n"
                             "  \"patch_density\": NaN}]}");
  expect_error(nan, nan, {"nan.json:2:"});
  // Default 1; every mesh of the entry gets the entry's density.
  write("two.obj",
        "o a\nv 0 0 2\nv 1 0 2\nv 0 1 2\nf 1 2 3\n"
        "o b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n");
  const fs::path ok = write("ok.json", R"({"meshes": [{"file": "tri.obj"},
      {"file": "two.obj", "patch_density": 2.5}]})");
  const Scene s = load(ok);
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].patch_density, 1.0f);
  EXPECT_EQ(s.meshes[1].patch_density, 2.5f);
  EXPECT_EQ(s.meshes[2].patch_density, 2.5f);
}

TEST_F(SceneLoaderInput, ObjectDensitySetsOneObjectOfAFileApart) {
  write("two.obj",
        "o statue\nv 0 0 2\nv 1 0 2\nv 0 1 2\nf 1 2 3\n"
        "o wall\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n");
  // The named object gets its own density; the file's other objects the
  // entry's.
  const fs::path ok = write("ok.json", R"({"meshes": [{"file": "two.obj", "patch_density": 0.5,
      "object_density": {"statue": 8}}]})");
  const Scene s = load(ok);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "statue");
  EXPECT_EQ(s.meshes[0].patch_density, 8.0f);
  EXPECT_EQ(s.meshes[1].name, "wall");
  EXPECT_EQ(s.meshes[1].patch_density, 0.5f);
  // An object the file does not hold, or a bad density, is one error naming
  // the key (and the objects the file does hold).
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {R"({"statu": 2})",
       {"meshes[0].object_density.statu", "no object named 'statu'", "'statue', 'wall'"}},
      {R"({"statue": 0})", {"meshes[0].object_density.statue", "> 0 and <= 64", "got 0"}},
      {R"({"statue": "x"})", {"meshes[0].object_density.statue", "a string"}},
      {R"([2])", {"meshes[0].object_density"}},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].first);
    const fs::path json =
        write("objects" + std::to_string(i) + ".json",
              R"({"meshes": [{"file": "two.obj", "object_density": )" + cases[i].first + "}]}");
    expect_error(json, json, cases[i].second);
  }
}

TEST_F(SceneLoaderInput, BadLightsAreFatalNamingTheLight) {
  write_triangle_obj();
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {R"({"position": [0, 1, 0], "intensity": -2})", {"lights[0].intensity", "negative"}},
      {R"({"type": "directional", "direction": [0, 0, 0]})", {"lights[0].direction", "zero"}},
      {R"({"type": "directional"})", {"lights[0]", "missing key `direction`"}},
      {R"({"type": "point"})", {"lights[0]", "missing key `position`"}},
      {R"({"type": "area", "position": [0, 1, 0]})", {"lights[0].type", "\"area\""}},
      {R"({"position": [0, "up", 0]})", {"lights[0].position", "element 1 is a string"}},
      {R"({"position": [0, 1, 0], "color": [1, -1, 1]})", {"lights[0].color", "negative"}},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "inner_deg": 50, "outer_deg": 40})",
       {"lights[0].inner_deg", "[0, outer_deg]"}},
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].first);
    const fs::path json =
        write("scene" + std::to_string(i) + ".json",
              R"({"meshes": [{"file": "tri.obj"}], "lights": [)" + cases[i].first + "]}");
    expect_error(json, json, cases[i].second);
  }
  // The second light is named by its index too.
  const fs::path json = write(
      "second.json",
      R"({"meshes": [{"file": "tri.obj"}], "lights": [{"position": [0, 1, 0]}, {"type": "directional", "direction": [0, 0, 0]}]})");
  expect_error(json, json, {"lights[1].direction"});
}

TEST_F(SceneLoaderInput, LightsAreReadWithDefaultsAndNormalisedDirections) {
  write_triangle_obj();
  const fs::path json = write("scene.json", R"({
    "meshes": [{"file": "tri.obj"}],
    "lights": [
      {"position": [0, 1, 0]},
      {"name": "sun", "type": "directional", "direction": [0, -2, 0], "color": [1, 0.9, 0.8], "intensity": 3},
      {"type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0], "inner_deg": 10, "outer_deg": 20}
    ]})");
  const Scene s = load(json);
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  EXPECT_EQ(s.lights[0].name, "light0");
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f));
  EXPECT_EQ(s.lights[0].intensity, 1.0f);
  EXPECT_EQ(s.lights[1].type, Light::Type::Directional);
  EXPECT_EQ(s.lights[1].name, "sun");
  EXPECT_EQ(s.lights[1].direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(s.lights[1].color, glm::vec3(1.0f, 0.9f, 0.8f));
  EXPECT_EQ(s.lights[1].intensity, 3.0f);
  EXPECT_EQ(s.lights[2].type, Light::Type::Spot);
  EXPECT_EQ(s.lights[2].spot_inner_deg, 10.0f);
  EXPECT_EQ(s.lights[2].spot_outer_deg, 20.0f);
  EXPECT_EQ(diagnostics.warnings().size(), 0u) << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, UnknownAndDuplicateKeysWarnAndTheSceneLoads) {
  write_triangle_obj();
  const fs::path json = write("scene.json", R"({
    "meshes": [{"file": "tri.obj", "name": "x", "name": "y", "colour": "red", "transform": {"translate": [0, 0, 1], "spin": 3}}],
    "materials": {"grey": {"albedo": [0.1, 0.2, 0.3], "shiny": true}},
    "lights": [{"position": [0, 0, 2], "power": 5}],
    "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "zoom": 2},
    "bake": {"voxel": 4, "voxels": 8, "voxel": 6},
    "extra": 1
  })");
  const Scene s = load(json);
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.vertex(0, 0).z, 1.0f);  // the transform was applied
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.defaults.voxel_resolution, 6);  // the last duplicate wins, as warned
  for (const char* key : {"meshes[0].colour", "meshes[0].transform.spin", "materials.grey.shiny",
                          "lights[0].power", "camera.zoom", "bake.voxels", "extra"}) {
    EXPECT_EQ(count_warnings(diagnostics, {std::string(key) + ": unknown key"}), 1u)
        << key << "\n"
        << all_warnings(diagnostics);
  }
  EXPECT_EQ(count_warnings(diagnostics, {"bake.voxel: duplicate key"}), 1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(count_warnings(diagnostics, {"meshes[0].name: duplicate key"}), 1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(s.meshes[0].name, "y");
  EXPECT_EQ(diagnostics.warnings().size(), 9u) << all_warnings(diagnostics);
  for (const Diagnostic& w : diagnostics.warnings()) EXPECT_EQ(w.where, json.string());
}

TEST_F(SceneLoaderInput, NonFiniteVerticesAreFatalNamingMeshIndexAndCount) {
  const fs::path obj = write("nan.obj",
                             "o good\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                             "o bad\nv 0 0 0\nv nan 0 0\nv 0 1 0\nv 1 1 inf\nf 4 5 6\nf 4 6 7\n");
  expect_error(obj, obj, {"mesh 'bad'", "2 vertices", "NaN or Inf", "vertex 1", "nan"});

  // Finite in the file, infinite after the scene.json transform.
  write("big.obj", "o big\nv 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n");
  const fs::path json =
      write("scene.json",
            R"({"meshes": [{"file": "big.obj", "name": "huge", "transform": {"scale": 1e20}}]})");
  expect_error(json, dir / "big.obj", {"mesh 'huge'", "1 vertex has", "after the transform"});
}

TEST_F(SceneLoaderInput, DegenerateTrianglesOfAllMeshesAreSkippedWithOneWarning) {
  const fs::path obj = write("degenerate.obj",
                             "o good\n"
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 1 1e-9 0\n"
                             "f 1 2 3\nf 1 3 4\n"
                             "f 1 1 2\n"  // repeated index
                             "f 1 2 5\n"  // collinear: zero area
                             "f 1 2 6\n"  // thin sliver, but not degenerate (below)
                             "o flat\n"
                             "v 0 0 1\nv 1 0 1\nv 2 0 1\n"
                             "f 7 8 9\n");  // all degenerate: the mesh is left out
  const Scene s = load(obj);
  // The sliver 1e-9 high has area 5e-10 > 1e-12 * diagonal^2 = 6e-12: kept.
  EXPECT_EQ(s.triangle_count(), 3u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "good");
  EXPECT_EQ(count_warnings(diagnostics, {"skipped 3 degenerate triangles in 2 meshes",
                                         "'good' (2 of 5)", "'flat' (1 of 1, nothing is left"}),
            1u)
      << all_warnings(diagnostics);
  // Only vertices of kept triangles remain.
  EXPECT_EQ(s.positions.size(), 5u);
  for (const auto& w : diagnostics.warnings()) {
    if (w.message.find("degenerate") != std::string::npos) {
      EXPECT_EQ(w.where, obj.string());
    }
  }
}

TEST_F(SceneLoaderInput, ManyMeshesWithOneProblemMakeOneLineNamingTheFirstFew) {
  std::string text;
  for (int m = 0; m < 5; ++m) {
    const int base = 4 * m;
    text += "o mesh" + std::to_string(m) + "\n";
    text += "v 0 0 " + std::to_string(m) + "\nv 1 0 " + std::to_string(m) + "\nv 1 1 " +
            std::to_string(m) + "\nv 2 0 " + std::to_string(m) + "\n";
    text += "f " + std::to_string(base + 1) + " " + std::to_string(base + 2) + " " +
            std::to_string(base + 3) + "\n";
    text += "f " + std::to_string(base + 1) + " " + std::to_string(base + 2) + " " +
            std::to_string(base + 4) + "\n";  // collinear
  }
  const fs::path obj = write("many.obj", text);
  load(obj);
  // One line for the five meshes (the other warning: no material).
  std::vector<Diagnostic> degenerate;
  for (const Diagnostic& w : diagnostics.warnings())
    if (w.message.find("degenerate") != std::string::npos) degenerate.push_back(w);
  ASSERT_EQ(degenerate.size(), 1u) << all_warnings(diagnostics);
  const Diagnostic& w = degenerate[0];
  EXPECT_EQ(count_warnings(diagnostics, {"skipped 5 degenerate triangles in 5 meshes",
                                         "'mesh0' (1 of 2), 'mesh1' (1 of 2), 'mesh2' (1 of 2) "
                                         "and 2 more"}),
            1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(w.message.find("mesh3"), std::string::npos) << w.message;
  ASSERT_EQ(w.detail.size(), 5u);
  EXPECT_EQ(w.detail[4], "'mesh4' (1 of 2)");
}

TEST_F(SceneLoaderInput, TinyTrianglesRelativeToTheSceneAreDegenerate) {
  // Scene diagonal ~ 1e3: area <= 1e-12 * 1e6 = 1e-6 is degenerate.
  const fs::path obj = write("tiny.obj",
                             "v 0 0 0\nv 1000 0 0\nv 0 1000 0\n"
                             "v 0 0 5\nv 1e-3 0 5\nv 0 1e-3 5\n"
                             "f 1 2 3\nf 4 5 6\n");
  const Scene s = load(obj);
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(count_warnings(diagnostics, {"skipped 1 degenerate triangle in 1 mesh", "(1 of 2)"}),
            1u)
      << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, NoGeometryLeftIsFatal) {
  const fs::path obj = write("flat.obj", "o flat\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 1\n");
  expect_error(obj, obj, {"no geometry left", "all 2 triangles are degenerate"});
  const fs::path lines = write("lines.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nl 1 2\nl 2 3\n");
  const std::string what = expect_error(lines, lines, {"no geometry"});
  EXPECT_EQ(count_warnings(diagnostics, {"point and line primitives"}), 1u)
      << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, UnreadableMeshFilesAreFatalWithAssimpsError) {
  const fs::path unknown = write("mesh.xyzq", "hello\n");
  expect_error(unknown, unknown, {"Assimp cannot read", "No suitable reader"});
  const fs::path empty = write("empty.obj", "");
  expect_error(empty, empty, {"Assimp cannot read"});
  const fs::path json = write("scene.json", R"({"meshes": [{"file": "models/missing.obj"}]})");
  expect_error(json, dir / "models" / "missing.obj",
               {"no such file", "meshes[0].file", json.string()});
}

TEST_F(SceneLoaderInput, MaterialsWithoutDiffuseGetTheDefaultWithAWarning) {
  write("mats.mtl", "newmtl nokd\nKe 0 0 0\nnewmtl withkd\nKd 0.6 0.6 0.6\n");
  const fs::path obj = write("m.obj",
                             "mtllib mats.mtl\nmtllib gone.mtl\n"
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                             "usemtl nokd\nf 1 2 3\nusemtl withkd\nf 1 2 4\n"
                             "usemtl undefined\nf 1 3 4\n");
  const Scene s = load(obj);
  ASSERT_EQ(s.materials.size(), 3u);
  // Assimp invents 0.6 grey for missing Kd; Bounce uses its documented default instead.
  EXPECT_EQ(s.materials[0].name, "nokd");
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(SceneLoader::kDefaultAlbedo));
  EXPECT_EQ(s.materials[1].name, "withkd");
  EXPECT_EQ(s.materials[1].albedo, glm::vec3(0.6f));
  EXPECT_EQ(s.materials[2].name, "undefined");
  EXPECT_EQ(s.materials[2].albedo, glm::vec3(SceneLoader::kDefaultAlbedo));
  EXPECT_EQ(count_warnings(diagnostics, {"material 'nokd'", "no diffuse colour"}), 1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(count_warnings(diagnostics, {"material 'undefined'", "no diffuse colour"}), 1u);
  EXPECT_EQ(count_warnings(diagnostics, {"material 'withkd'"}), 0u);
  EXPECT_EQ(count_warnings(diagnostics, {"'gone.mtl' not found"}), 1u);
  for (const auto& w : diagnostics.warnings()) {
    if (w.message.find("no diffuse") != std::string::npos) {
      EXPECT_EQ(w.where, obj.string());
    }
  }
}

TEST_F(SceneLoaderInput, AlbedoOutsideRangeIsClampedWithAWarning) {
  write("c.mtl", "newmtl bright\nKd 1.0 0.5 1.2\nKe 1 1 1\n");
  write("c.obj", "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl bright\nf 1 2 3\n");
  Scene s = load(dir / "c.obj");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.9999f, 0.5f, 0.9999f));
  EXPECT_EQ(count_warnings(diagnostics, {"material 'bright'", "clamped", "diverge"}), 1u)
      << all_warnings(diagnostics);

  const fs::path json = write("scene.json", R"({"meshes": [{"file": "c.obj"}],
      "materials": {"bright": {"albedo": [-0.5, 0.2, 3]}}})");
  Diagnostics d2;
  s = SceneLoader(d2).load(json);
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.0f, 0.2f, 0.9999f));
  EXPECT_EQ(s.materials[0].emission, glm::vec3(1.0f));  // kept from the MTL
  ASSERT_EQ(count_warnings(d2, {"clamped"}), 1u) << all_warnings(d2);
  EXPECT_EQ(d2.warnings()[0].where, json.string());
}

TEST_F(SceneLoaderInput, SceneJsonOverridesMaterialsByName) {
  const fs::path box = fs::absolute(kScenes / "cornell-box" / "CornellBox-Original.obj");
  const fs::path json = write("scene.json", R"({"meshes": [{"file": ")" + box.string() + R"("}],
      "materials": {"leftWall": {"albedo": [0.1, 0.2, 0.3]}, "light": {"emission": [5, 5, 5]}}})");
  const Scene s = load(json);
  EXPECT_EQ(s.name, dir.filename().string());
  const Material* left = find_material(s, "leftWall");
  ASSERT_NE(left, nullptr);
  EXPECT_EQ(left->albedo, glm::vec3(0.1f, 0.2f, 0.3f));
  const Material* light = find_material(s, "light");
  ASSERT_NE(light, nullptr);
  EXPECT_EQ(light->emission, glm::vec3(5.0f));
  EXPECT_EQ(light->albedo, glm::vec3(0.78f));  // not overridden: from the MTL
  EXPECT_EQ(count_warnings(diagnostics, {"duplicate"}), diagnostics.warnings().size())
      << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, MeshMaterialOverridesAndInlineMaterials) {
  write_triangle_obj();
  const fs::path json = write("scene.json", R"({"meshes": [
      {"file": "tri.obj", "name": "a", "material": "paint"},
      {"file": "tri.obj", "name": "b", "material": {"albedo": [0.3, 0.3, 0.3], "emission": [2, 2, 2]},
       "transform": {"translate": [0, 0, 1]}, "two_sided": true},
      {"file": "tri.obj", "name": "c", "transform": {"translate": [0, 0, 2]}}],
      "materials": {"paint": {"albedo": [0.9, 0.1, 0.1]}, "unused": {"albedo": [0.5, 0.5, 0.5]}}})");
  const Scene s = load(json);
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].name, "a");
  EXPECT_EQ(s.material_of(0).name, "paint");
  EXPECT_EQ(s.material_of(0).albedo, glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_FALSE(s.two_sided(0));
  EXPECT_EQ(s.material_of(1).name, "b");  // inline material named after its mesh
  EXPECT_EQ(s.material_of(1).emission, glm::vec3(2.0f));
  EXPECT_TRUE(s.two_sided(1));
  EXPECT_EQ(s.material_of(2).name, "grey");  // from tri.mtl
  EXPECT_EQ(s.material_of(2).albedo, glm::vec3(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(s.meshes[1].source, (dir / "tri.obj").string());
  EXPECT_EQ(count_warnings(diagnostics, {"materials.unused", "no mesh uses"}), 1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(diagnostics.warnings().size(), 1u) << all_warnings(diagnostics);
  // No explicit camera: derived from the bounds.
  EXPECT_EQ(s.camera.fov_y_deg, 45.0f);
}

TEST_F(SceneLoaderInput, TransformsApplyScaleThenRotationThenTranslation) {
  write_triangle_obj();
  const fs::path json = write("scene.json", R"({"meshes": [
      {"file": "tri.obj", "name": "trs", "transform": {"scale": 2, "rotate_deg": [0, 0, 90], "translate": [10, 0, 0]}},
      {"file": "tri.obj", "name": "matrix", "transform": {"matrix": [[0, -2, 0, 10], [2, 0, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]}},
      {"file": "tri.obj", "name": "mirror", "transform": {"scale": [-1, 1, 1]}},
      {"file": "tri.obj", "name": "xyz", "transform": {"rotate_deg": [90, 90, 0]}}]})");
  const Scene s = load(json);
  ASSERT_EQ(s.triangle_count(), 4u);
  // (1,0,0) -> scale 2 -> rotate 90 about z -> (0,2,0) -> translate -> (10,2,0).
  for (std::size_t t : {0u, 1u}) {
    EXPECT_NEAR(s.vertex(t, 0).x, 10.f, 1e-6f);
    EXPECT_NEAR(s.vertex(t, 1).x, 10.f, 1e-6f);
    EXPECT_NEAR(s.vertex(t, 1).y, 2.f, 1e-6f);
    EXPECT_NEAR(s.vertex(t, 2).x, 8.f, 1e-6f);
    EXPECT_NEAR(unit_normal(s, t).z, 1.f, 1e-6f);
  }
  // A mirror keeps the front side: the normal stays +z (winding is swapped).
  EXPECT_NEAR(unit_normal(s, 2).z, 1.f, 1e-6f);
  EXPECT_FLOAT_EQ(s.triangle_area(2), 0.5f);
  // XYZ Euler: first 90 about x takes +z to -y, then 90 about y leaves -y alone.
  EXPECT_NEAR(unit_normal(s, 3).y, -1.f, 1e-6f);
  // (1,0,0): about x stays, about y goes to (0,0,-1).
  EXPECT_NEAR(glm::length(s.positions[s.triangles[3][1]] - glm::vec3(0, 0, -1)), 0.f, 1e-6f);
}

TEST_F(SceneLoaderInput, BareMeshGetsDerivedLightAndCamera) {
  const fs::path obj = write("Box Model.obj",
                             "v -1 0 -2\nv 3 0 -2\nv 3 4 -2\nv -1 4 -2\nv -1 0 2\n"
                             "f 1 2 3\nf 1 3 4\nf 1 5 4\n");
  const Scene s = load(obj);
  EXPECT_EQ(s.name, "Box Model");
  EXPECT_EQ(s.path, obj.string());
  EXPECT_EQ(s.triangle_count(), 3u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "Box Model");
  // Bounds [-1,3] x [0,4] x [-2,2]: centre (1,2,0), height 4, diagonal^2 = 48.
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1.0f, 3.2f, 0.0f));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 48.0f);
  EXPECT_EQ(s.camera.target, glm::vec3(1.0f, 2.0f, 0.0f));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 45.0f);
  EXPECT_FLOAT_EQ(s.camera.position.x, 1.0f);
  EXPECT_FLOAT_EQ(s.camera.position.y, 2.0f);
  // The bounding sphere (radius sqrt(48)/2) just fits the vertical field of view.
  const float distance = s.camera.position.z;
  EXPECT_NEAR(std::asin(std::sqrt(48.0f) / 2.0f / distance), glm::radians(22.5f), 1e-5f);
  // No MTL: the default material gets the default albedo, with a warning.
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(SceneLoader::kDefaultAlbedo));
  EXPECT_EQ(count_warnings(diagnostics, {"material 'DefaultMaterial'", "no diffuse colour"}), 1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(diagnostics.warnings().size(), 1u) << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, BarePlyAndGltfLoad) {
  const fs::path ply = write("tri.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  Scene s = load(ply);
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(SceneLoader::kDefaultAlbedo));
  EXPECT_EQ(count_warnings(diagnostics, {"no diffuse colour"}), 1u) << all_warnings(diagnostics);

  // glTF: one triangle under a translated node; baseColorFactor and emissiveFactor
  // arrive as albedo and emission.
  const fs::path gltf = write("tri.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0, "name": "node", "translation": [0, 5, 0]},
              {"mesh": 0, "name": "mirrored", "scale": [-1, 1, 1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"name": "red", "emissiveFactor": [1, 0.5, 0],
                   "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1]}}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
  Diagnostics d2;
  s = SceneLoader(d2).load(gltf);
  ASSERT_EQ(s.triangle_count(), 2u);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "node");
  EXPECT_EQ(s.vertex(0, 0), glm::vec3(0.0f, 5.0f, 0.0f));  // node transform applied
  EXPECT_EQ(s.meshes[1].name, "mirrored");
  EXPECT_EQ(s.bounds().lo.x, -1.0f);
  // The mirroring node keeps the front side: both triangles face +z.
  EXPECT_EQ(unit_normal(s, 0), glm::vec3(0, 0, 1));
  EXPECT_EQ(unit_normal(s, 1), glm::vec3(0, 0, 1));
  EXPECT_EQ(s.materials[0].name, "red");
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.8f, 0.1f, 0.1f));
  EXPECT_EQ(s.materials[0].emission, glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_EQ(d2.warnings().size(), 0u) << all_warnings(d2);
}

TEST_F(SceneLoaderInput, DarkScenesAreWarnedAbout) {
  write_triangle_obj();
  const fs::path json = write("scene.json", R"({"meshes": [{"file": "tri.obj"}]})");
  const Scene s = load(json);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(
      count_warnings(diagnostics, {"no lights and no emissive surfaces: the bake will be dark"}),
      1u)
      << all_warnings(diagnostics);
  EXPECT_EQ(diagnostics.warnings().size(), 1u) << all_warnings(diagnostics);
}

TEST_F(SceneLoaderInput, PiecesOfOneFileTakeTheEntryNameAsPrefix) {
  // Two pieces from one OBJ under one scene.json name: "<name>/<piece>".
  write("two.obj",
        "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
        "o second\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n");
  const fs::path json = write(
      "scene.json",
      R"({"meshes": [{"file": "two.obj", "name": "pair"}], "lights": [{"position": [0, 0, 3]}]})");
  const Scene s = load(json);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "pair/first");
  EXPECT_EQ(s.meshes[1].name, "pair/second");
  EXPECT_EQ(s.meshes[1].first_triangle, 1u);
}

}  // namespace bounce
