// Finely meshed curved surfaces: most of their tiny triangles get no sampling
// ray and are carried whole by the nearest sample facing their way, and the
// form factors lump the parts one sample carries into one point. A sphere of
// 8064 triangles sits in the middle of a closed cube: the cube's faces see
// only the sphere and each other, and the sphere sees only the cube, so every
// patch's form-factor row adds up to 1 (closure of an enclosure), whatever
// the patches.
//
// Regression: the lumped point stood at the area mean of the carried parts,
// which on a convex surface lies inside it. Visibility rays started there and
// hit the sphere from inside: the sphere's patches saw nothing (rows ~0 against
// the expected 1). On cornell-bunny this cut the bunny's indirect light to 0.37
// of the reference in both patch modes (docs/benchmarks.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bake/bake.h"
#include "test_scenes.h"

namespace bounce {

namespace {

// The unit cube (faces inward) with an outward UV sphere of radius 0.3 in its middle.
Scene sphere_in_cube() {
  Scene s = test_scenes::furnace_box(glm::vec3(0.5f), glm::vec3(0.0f));
  s.name = "sphere-in-cube";
  constexpr std::uint32_t rings = 64, segments = 64;
  const float pi = std::numbers::pi_v<float>;
  std::vector<glm::vec3> v;
  for (std::uint32_t i = 0; i <= rings; ++i)
    for (std::uint32_t j = 0; j < segments; ++j) {
      const float theta = pi * static_cast<float>(i) / rings;
      const float phi = 2.0f * pi * static_cast<float>(j) / segments;
      v.push_back(glm::vec3(0.5f) + 0.3f * glm::vec3(std::sin(theta) * std::cos(phi),
                                                     std::cos(theta),
                                                     std::sin(theta) * std::sin(phi)));
    }
  std::vector<glm::uvec3> t;
  for (std::uint32_t i = 0; i < rings; ++i)
    for (std::uint32_t j = 0; j < segments; ++j) {
      const std::uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
      const std::uint32_t c = a + segments, d = b + segments;
      // Counter-clockwise seen from outside; the poles' degenerate halves are skipped.
      if (i > 0) t.push_back({a, b, c});
      if (i + 1 < rings) t.push_back({b, d, c});
    }
  test_scenes::add_mesh(s, "sphere", v, t, glm::vec3(0.5f));
  return s;
}

}  // namespace

TEST(LumpedPartsVisibility, FinelyMeshedSphereInACubeKeepsClosure) {
  const Scene scene = sphere_in_cube();
  for (PatchMode mode : {PatchMode::Virtual, PatchMode::Voxel}) {
    BakeSettings s;
    s.voxel_resolution = 4;
    s.samples_per_face = 2;  // few rays: most of the sphere's triangles are carried whole
    s.patch_mode = mode;
    s.codec = CodecChoice::Dense;
    s.pictures = false;
    Diagnostics d;
    Progress p;
    const BakeResult r = Baker(scene, s, d).run(p);
    std::size_t whole = 0;
    for (const CarriedArea& c : r.samples.carried) whole += c.whole_part ? 1 : 0;
    ASSERT_GT(whole, r.samples.samples.size()) << "the sphere must be mostly carried whole";
    const std::uint32_t sphere = 1;
    double sphere_area = 0.0, sphere_rows = 0.0;
    for (std::size_t q = 0; q < r.patches.size(); ++q) {
      double row = 0.0;
      for (std::size_t k = 0; k < r.patches.size(); ++k) row += r.form_factors(q, k);
      if (r.patches.patches[q].mesh != sphere) continue;
      sphere_area += r.patches.patches[q].area;
      sphere_rows += r.patches.patches[q].area * row;
    }
    ASSERT_GT(sphere_area, 0.0);
    // Closure is 1; the near-field quadrature and 8 visibility rays per pair
    // stay within a few percent of it (the bug gave ~0.1).
    EXPECT_NEAR(sphere_rows / sphere_area, 1.0, 0.1)
        << (mode == PatchMode::Virtual ? "virtual" : "voxel") << " patches";
  }
}

}  // namespace bounce
