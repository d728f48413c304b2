// The live preview (view 5) on the fixture bake of the Cornell box (x from
// -1 to 1 with the red wall at -x and the green wall at +x, floor y = 0,
// ceiling y = 2, back wall z = -1; the scene camera looks down -z from
// z = 3.4, so -x is the picture's left).
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "preview_test_support.h"

namespace bounce::render_test {

namespace {

// Mean luminance of the columns [x0, x1) of the picture.
double mean_luminance(const QImage& image, int x0, int x1) {
  const QImage im = image.convertToFormat(QImage::Format_RGB32);
  double sum = 0;
  for (int y = 0; y < im.height(); ++y)
    for (int x = x0; x < x1; ++x) {
      const QRgb c = im.pixel(x, y);
      sum += 0.2126 * qRed(c) + 0.7152 * qGreen(c) + 0.0722 * qBlue(c);
    }
  return sum / (static_cast<double>(x1 - x0) * im.height());
}

}  // namespace

namespace {

// A lit mesh's vertex colours, read back from a binary glTF.
std::vector<aiColor4D> vertex_colours(const std::filesystem::path& glb) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(glb.string(), 0);
  EXPECT_NE(scene, nullptr) << glb << ": " << importer.GetErrorString();
  if (!scene || scene->mNumMeshes == 0) return {};
  std::vector<aiColor4D> colours;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const aiMesh* m = scene->mMeshes[k];
    if (!m->HasVertexColors(0)) return {};
    colours.insert(colours.end(), m->mColors[0], m->mColors[0] + m->mNumVertices);
  }
  return colours;
}

// Largest difference of any channel of any vertex.
float largest_difference(const std::vector<aiColor4D>& a, const std::vector<aiColor4D>& b) {
  float d = 0.0f;
  for (std::size_t v = 0; v < std::min(a.size(), b.size()); ++v)
    d = std::max(
        {d, std::abs(a[v].r - b[v].r), std::abs(a[v].g - b[v].g), std::abs(a[v].b - b[v].b)});
  return d;
}

}  // namespace

class Preview : public PreviewOfBake {
 protected:
  void SetUp() override {
    PreviewOfBake::SetUp();
    open(BOUNCE_RENDER_BAKE);
  }
};

TEST_F(Preview, RendersTheLitBox) {
  const QImage image = shot({});
  ASSERT_EQ(image.size(), QSize(400, 300));
  EXPECT_GT(non_uniform_share(image), 0.5) << "the preview looks blank";
  EXPECT_GT(view_.vertex_count(), data_->patch_count()) << "the refined mesh is too coarse";
  // The light is where the scene puts it and the indirect light on screen
  // belongs to it.
  EXPECT_EQ(view_.solved_light_position(), data_->scene->lights.front().position);

  const double ms = view_.measure_frame_ms(20);
  EXPECT_GT(ms, 0.0);
  std::cout << "[ measured ] preview 400x300, " << data_->patch_count() << " patches, "
            << view_.vertex_count() << " vertices: " << ms << " ms per frame (shadow map "
            << "included), solve " << view_.last_solve_ms() << " ms (frame graph "
            << view_.last_frame_graph_ms() << ", to vertices " << view_.last_transfer_ms()
            << ") on the " << (view_.solve_on_worker() ? "worker" : "UI thread") << "\n";
}

TEST_F(Preview, MovingTheLightBrightensTheNearSide) {
  const glm::vec3 left(-0.6f, 1.0f, 0.0f), right(0.6f, 1.0f, 0.0f);
  view_.set_light_position(left, true);
  const QImage lit_left = shot({});
  view_.set_light_position(right, true);
  const QImage lit_right = shot({});
  EXPECT_EQ(view_.solved_light_position(), right);

  // Beyond a threshold: the mean change per pixel is several 8-bit levels
  // (the light crosses the box: every wall sees it from another side).
  double change = 0;
  const QImage a = lit_left.convertToFormat(QImage::Format_RGB32);
  const QImage b = lit_right.convertToFormat(QImage::Format_RGB32);
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
      change += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) +
                std::abs(qBlue(p) - qBlue(q));
    }
  change /= 3.0 * a.width() * a.height();
  EXPECT_GT(change, 5.0);

  // In the expected direction: each half is brighter with the light on its side.
  const int w = a.width();
  EXPECT_GT(mean_luminance(lit_left, 0, w / 2), mean_luminance(lit_right, 0, w / 2) + 5.0);
  EXPECT_GT(mean_luminance(lit_right, w / 2, w), mean_luminance(lit_left, w / 2, w) + 5.0);
}

TEST_F(Preview, TheLatestLightPositionWins) {
  // As a drag does: several moves without waiting. Whichever thread the
  // policy picked for this bake, the indirect light on screen ends up being
  // the last position's, and once its spread shadow rays have settled there
  // the frame equals a solve made there directly.
  const glm::vec3 last(0.3f, 0.8f, 0.2f);
  for (const float x : {-0.4f, -0.2f, 0.0f, 0.1f}) view_.set_light_position({x, 1.2f, 0.1f});
  view_.set_light_position(last);
  wait_until_settled_at(last);
  ASSERT_EQ(view_.solved_light_position(), last) << "the last light position was never solved";
  ASSERT_TRUE(view_.solved_settled()) << "the preview did not solve again where the light stopped";
  const QImage dragged = shot({});
  view_.set_light_position(last, true);
  const QImage direct = shot({});
  EXPECT_EQ(dragged, direct);
}

// File > Export: the lit mesh as binary glTF, read back with Assimp. Its
// vertices are the preview's; a wall with the light beside it comes out in
// its own colour and brighter than with the light across the box.
TEST_F(Preview, ExportsTheLitMeshAsGltf) {
  const std::filesystem::path dir = work_dir("preview-export");
  struct Walls {
    Rgb left, right;
  };
  auto export_at = [&](const glm::vec3& light, const std::string& name) {
    view_.set_light_position(light, true);
    const std::filesystem::path path = dir / name;
    view_.export_lit_glb(path.string());
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    EXPECT_NE(scene, nullptr) << importer.GetErrorString();
    Walls w;
    if (!scene || scene->mNumMeshes != 1) return w;
    const aiMesh* m = scene->mMeshes[0];
    EXPECT_EQ(m->mNumVertices, view_.vertex_count());
    EXPECT_TRUE(m->HasVertexColors(0));
    if (!m->HasVertexColors(0)) return w;
    int nl = 0, nr = 0;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D p = m->mVertices[v];
      if (p.y < 0.2f || p.y > 1.8f || p.z < -0.8f || p.z > 0.8f) continue;  // wall middles
      if (std::abs(p.x) < 0.98f) continue;                                  // not on a side wall
      const aiColor4D c = m->mColors[0][v];
      Rgb& side = p.x < 0.0f ? w.left : w.right;
      side.r += c.r;
      side.g += c.g;
      side.b += c.b;
      ++(p.x < 0.0f ? nl : nr);
    }
    EXPECT_GT(nl, 0);
    EXPECT_GT(nr, 0);
    if (nl > 0) w.left = {w.left.r / nl, w.left.g / nl, w.left.b / nl};
    if (nr > 0) w.right = {w.right.r / nr, w.right.g / nr, w.right.b / nr};
    return w;
  };
  const Walls at_left = export_at({-0.6f, 1.0f, 0.0f}, "left.glb");
  const Walls at_right = export_at({0.6f, 1.0f, 0.0f}, "right.glb");
  // Each wall with the light beside it shows its own colour (the far wall
  // then takes much of its light from the near one: colour bleeding).
  EXPECT_GT(at_left.left.r, 2.0 * at_left.left.g) << "the red wall is not red";
  EXPECT_GT(at_right.right.g, 2.0 * at_right.right.r) << "the green wall is not green";
  EXPECT_GT(at_left.left.luminance(), 1.2 * at_right.left.luminance())
      << "the left wall is not brighter with the light beside it";
  EXPECT_GT(at_right.right.luminance(), 1.2 * at_left.right.luminance())
      << "the right wall is not brighter with the light beside it";
}

TEST_F(Preview, IndirectLightBleedsTheWallColours) {
  // Light in the middle, indirect light only: the white back wall and
  // ceiling next to the red wall are redder than next to the green wall.
  view_.set_light_position({0.0f, 1.2f, 0.0f}, true);
  views::PreviewWidget::Passes indirect_only;
  indirect_only.direct = false;
  indirect_only.ao = false;
  const QImage image = shot(indirect_only);
  for (const float y : {1.6f, 1.95f}) {  // back wall above the tall box; under the ceiling
    const Rgb near_red = mean_around(image, view_.project({-0.85f, y, -1.0f}));
    const Rgb near_green = mean_around(image, view_.project({0.85f, y, -1.0f}));
    ASSERT_GT(near_red.luminance(), 10.0) << "too dark to judge colour at y = " << y;
    ASSERT_GT(near_green.luminance(), 10.0) << "too dark to judge colour at y = " << y;
    // The light is orange, so every white surface has r > g; the red wall
    // raises r / g near it, the green wall lowers it near itself.
    const double red_ratio = near_red.r / std::max(1.0, near_red.g);
    const double green_ratio = near_green.r / std::max(1.0, near_green.g);
    EXPECT_GT(red_ratio, 1.15 * green_ratio) << "at y = " << y;
  }
  // The floor too, in front of the boxes.
  const Rgb floor_red = mean_around(image, view_.project({-0.85f, 0.0f, 0.7f}));
  const Rgb floor_green = mean_around(image, view_.project({0.85f, 0.0f, 0.7f}));
  EXPECT_GT(floor_red.r / std::max(1.0, floor_red.g),
            1.15 * floor_green.r / std::max(1.0, floor_green.g));
}

TEST_F(Preview, AmbientOcclusionDarkensCorners) {
  views::PreviewWidget::Passes with_ao, without_ao;
  with_ao.direct = without_ao.direct = false;
  without_ao.ao = false;
  const QImage on = shot(with_ao);
  const QImage off = shot(without_ao);
  // The middle of the back wall: a flat stretch with no other surface within
  // the kernel radius (5% of the diagonal), where only the kernel's own
  // sampling noise can darken.
  const QPointF middle = view_.project({0.3f, 1.4f, -1.0f});
  const double flat = mean_around(on, middle).luminance() / mean_around(off, middle).luminance();
  EXPECT_GT(flat, 0.95) << "the occlusion darkens a flat wall";
  // The back wall where it meets the ceiling and the side walls, a few
  // hundredths in from the edge: part of each sample hemisphere lies inside
  // the other wall, so these darken clearly more than the flat wall.
  const glm::vec3 corners[] = {
      {-0.5f, 1.95f, -1.0f}, {0.5f, 1.95f, -1.0f}, {-0.97f, 1.7f, -1.0f}, {0.96f, 1.7f, -1.0f}};
  for (const glm::vec3& c : corners) {
    const QPointF at = view_.project(c);
    const double lit = mean_around(off, at, 1).luminance();
    ASSERT_GT(lit, 10.0) << "corner at " << c.x << ", " << c.y << " too dark to judge";
    const double ratio = mean_around(on, at, 1).luminance() / lit;
    std::cout << "[ measured ] AO on / off at (" << c.x << ", " << c.y << "): " << ratio
              << " (flat wall " << flat << ")\n";
    EXPECT_LT(ratio, 0.95) << "no occlusion in the corner at " << c.x << ", " << c.y;
    EXPECT_LT(ratio, flat - 0.03) << "the corner at " << c.x << ", " << c.y
                                  << " is not darker than the flat wall";
  }
}

// The textured preview on resources/scenes/textured-floor with a lamp and a
// green backdrop behind the fence (tests/render/scenes/textured-floor-lamp):
// the camera by the wall looks over the far half of the checker floor at the
// fence. The floor is checker.png (8 x 8 squares of sRGB (224, 96, 64),
// orange, and (48, 128, 192), blue, orange at the texture's top left, i.e.
// x = -1, z = -1) times Kd 0.9; the fence (z = 1, x in [-1, 1], y in [0, 1])
// is cut by fence-mask.png into 4 x 4 squares, solid where column + row
// (counted from the top left) is even.
class TexturedPreview : public PreviewOfBake {
 protected:
  void SetUp() override {
    PreviewOfBake::SetUp();
    open(BOUNCE_RENDER_TEXTURED_BAKE);
  }
  // Whether a world point lands inside the picture, `margin` pixels clear
  // of its edges.
  bool inside(QPointF p, double margin = 6.0) const {
    return p.x() >= margin && p.y() >= margin && p.x() < view_.width() - margin &&
           p.y() < view_.height() - margin;
  }
};

// The lamp dragged in the preview and let go: once its spread shadow rays
// and gather rows have settled there, the lit mesh the preview exports is
// `bounce solve`'s for the lamp at that position (this scene's only light:
// the preview lights with its lamp alone). Both multiply as `--multiply
// auto` does (this bake is dense); float rounding apart (the two may sum in
// another order), they agree to 1% of the brightest colour, while the
// light with the lamp half a metre away differs by more.
TEST_F(TexturedPreview, WhereTheLampStopsItsLightIsBounceSolves) {
  ASSERT_EQ(data_->scene->lights.size(), 1u);
  const std::string name = data_->scene->lights.front().name;
  const glm::vec3 last(0.2f, 1.2f, 0.0f);
  for (const float x : {-0.3f, -0.1f, 0.1f}) view_.set_light_position({x, 1.3f, -0.5f});
  view_.set_light_position(last);
  wait_until_settled_at(last);
  ASSERT_TRUE(view_.solved_settled());
  const std::filesystem::path dir = work_dir("preview-against-solve");
  view_.export_lit_glb((dir / "preview.glb").string());
  const auto solve_at = [&](const std::string& position, const std::string& out) {
    const CommandRun r = run_command(
        std::string(BOUNCE_CLI) + " solve " + std::string(BOUNCE_RENDER_TEXTURED_BAKE) +
        " --light '" + name + ":" + position +
        "' --no-images --multiply auto --float32 --quiet --out " + (dir / out).string());
    EXPECT_EQ(r.code, 0) << r.output;
    return vertex_colours(dir / out / "lit.glb");
  };
  const std::vector<aiColor4D> preview = vertex_colours(dir / "preview.glb");
  const std::vector<aiColor4D> solved = solve_at("0.2,1.2,0.0", "here");
  const std::vector<aiColor4D> elsewhere = solve_at("-0.3,0.7,0.5", "elsewhere");
  ASSERT_FALSE(preview.empty());
  ASSERT_EQ(preview.size(), solved.size());
  ASSERT_EQ(preview.size(), elsewhere.size());
  float brightest = 0.0f;
  for (const aiColor4D& c : solved) brightest = std::max({brightest, c.r, c.g, c.b});
  ASSERT_GT(brightest, 0.0f);
  const float here = largest_difference(preview, solved);
  const float there = largest_difference(preview, elsewhere);
  std::printf("preview against bounce solve: %.3g of the brightest colour here, %.3g there\n",
              here / brightest, there / brightest);
  EXPECT_LE(here, 0.01f * brightest);
  EXPECT_GT(there, 0.05f * brightest);
}

namespace {

// (R - B) / (R + B) of a pixel's 8-bit colour: the texture's orange is
// clearly positive, its blue clearly negative, their mean (what a surface
// without its texture shows) near zero. A ratio, so it holds whatever the
// exposure makes of the light.
double warmth(const Rgb& c) { return (c.r - c.b) / std::max(1.0, c.r + c.b); }

}  // namespace

TEST_F(TexturedPreview, FloorShowsTheCheckerInPlace) {
  const QImage image = view_.render_image();
  ASSERT_TRUE(view_.gl_error().isEmpty()) << view_.gl_error().toStdString();
  int orange = 0, blue = 0;
  for (int i = 0; i < 8; ++i)      // column, along +x
    for (int j = 0; j < 8; ++j) {  // row, along +z (row 0 at z = -1)
      const glm::vec3 centre(-1.0f + (static_cast<float>(i) + 0.5f) / 4.0f, 0.0f,
                             -1.0f + (static_cast<float>(j) + 0.5f) / 4.0f);
      const QPointF at = view_.project(centre);
      if (!inside(at)) continue;
      const Rgb c = mean_around(image, at, 1);
      const bool expect_orange = (i + j) % 2 == 0;
      if (expect_orange) {
        EXPECT_GT(warmth(c), 0.3) << "square " << i << "," << j << " should be orange: " << c.r
                                  << " " << c.g << " " << c.b;
        EXPECT_GT(c.r, c.g) << "square " << i << "," << j;
        ++orange;
      } else {
        EXPECT_LT(warmth(c), -0.3)
            << "square " << i << "," << j << " should be blue: " << c.r << " " << c.g << " " << c.b;
        EXPECT_GT(c.b, c.g) << "square " << i << "," << j;
        ++blue;
      }
    }
  // The camera sees the far half of the floor: several squares of each.
  EXPECT_GE(orange, 6);
  EXPECT_GE(blue, 6);
}

TEST_F(TexturedPreview, FenceHolesShowTheBackdrop) {
  const QImage image = view_.render_image();
  ASSERT_TRUE(view_.gl_error().isEmpty()) << view_.gl_error().toStdString();
  int solid = 0, holes = 0;
  for (int sx = 0; sx < 4; ++sx)      // along +x
    for (int sy = 0; sy < 4; ++sy) {  // from the top (y = 1) down
      const glm::vec3 centre(-1.0f + 0.5f * static_cast<float>(sx) + 0.25f,
                             1.0f - 0.25f * static_cast<float>(sy) - 0.125f, 1.0f);
      const QPointF at = view_.project(centre);
      if (!inside(at)) continue;
      const Rgb c = mean_around(image, at, 2);
      if ((sx + sy) % 2 == 0) {
        // The fence's grey (Kd 0.5 under a white light): no channel far
        // above the others.
        EXPECT_LT(c.g, 1.2 * std::max(c.r, c.b) + 4.0)
            << "solid square " << sx << "," << sy << ": " << c.r << " " << c.g << " " << c.b;
        EXPECT_GT(c.luminance(), 20.0) << "solid square " << sx << "," << sy;
        ++solid;
      } else {
        // Cut away: the green backdrop behind it.
        EXPECT_GT(c.g, 1.5 * std::max(c.r, c.b))
            << "hole " << sx << "," << sy << ": " << c.r << " " << c.g << " " << c.b;
        EXPECT_GT(c.g, 20.0) << "hole " << sx << "," << sy;
        ++holes;
      }
    }
  EXPECT_GE(solid, 6);
  EXPECT_GE(holes, 6);
  const double ms = view_.measure_frame_ms(10);
  std::cout << "[ measured ] textured preview 400x300, " << data_->patch_count() << " patches, "
            << view_.vertex_count() << " vertices: " << ms << " ms per frame (shadow map "
            << "included)\n";
}

// The preview on resources/scenes/textured-floor's normal-mapped wall
// (tests/render/scenes/ridged-wall): the wall (z = -1, x in [-1, 1], y in
// [0, 2]) is mapped once onto wall-ridges.png, whose 8 columns are facets
// tilted 30 degrees about the vertical, alternately towards -x (even
// columns, from x = -1) and +x (odd). The lamp at (0.95, 1.2, -0.3) lights
// the wall's left part from its +x side, 55 to 70 degrees from the normal,
// so a facet turned towards it gets cos 25-40 degrees and one turned away
// cos 80-100 (little or nothing): alternating columns. The flat wall, drawn
// without its map, only brightens towards the lamp (the irradiance
// cos / r^2 grows as x does), without a ripple.
class NormalMappedPreview : public PreviewOfBake {
 protected:
  void SetUp() override {
    PreviewOfBake::SetUp();
    open(BOUNCE_RENDER_RIDGED_BAKE);
  }
  // Luminance of the centre of each of the wall's columns 0 to 5 at the
  // lamp's height (columns 6 and 7 are beside and behind the lamp).
  std::vector<double> columns(bool normal_maps) {
    views::PreviewWidget::Passes passes;
    passes.normal_maps = normal_maps;
    view_.set_passes(passes);
    const QImage image = view_.render_image();
    EXPECT_TRUE(view_.gl_error().isEmpty()) << view_.gl_error().toStdString();
    std::vector<double> out;
    for (int k = 0; k < 6; ++k) {
      const glm::vec3 centre(-1.0f + 0.25f * static_cast<float>(k) + 0.125f, 1.2f, -1.0f);
      out.push_back(mean_around(image, view_.project(centre), 2).luminance());
    }
    return out;
  }
};

TEST_F(NormalMappedPreview, FacetsTurnedToTheLightAreBrighterOnlyWithTheMap) {
  const std::vector<double> mapped = columns(true), flat = columns(false);
  for (int k = 0; k < 6; ++k)
    std::cout << "[ measured ] wall column " << k << ": " << mapped[static_cast<std::size_t>(k)]
              << " with the normal map, " << flat[static_cast<std::size_t>(k)] << " without\n";
  for (std::size_t k = 0; k + 1 < 6; ++k) {
    const std::size_t towards = k % 2 == 1 ? k : k + 1, away = k % 2 == 1 ? k + 1 : k;
    // With the map: each facet turned towards the lamp is much brighter than
    // its neighbours turned away.
    EXPECT_GT(mapped[towards], 1.5 * mapped[away] + 5.0)
        << "columns " << k << " and " << k + 1 << " with the normal map";
    // Without it the wall is flat: each column at least as bright as the
    // one farther from the lamp (within 8-bit rounding).
    EXPECT_GT(flat[k + 1], flat[k] - 2.0)
        << "columns " << k << " and " << k + 1 << " without the normal map";
  }
  // The map turns light towards and away: brighter and darker than flat.
  EXPECT_GT(mapped[1], flat[1]);
  EXPECT_LT(mapped[2], flat[2]);
}

// The preview of tests/render/scenes/lit-lamp: the lamp (x and z in
// [-0.5, 0.5] at y = 1, facing down) emits Ke = 4 through half-lit.png, on
// its half over x < 0 only; a dim bulb below lights both halves alike.
class EmissiveTexturePreview : public PreviewOfBake {
 protected:
  void SetUp() override {
    PreviewOfBake::SetUp();
    open(BOUNCE_RENDER_LAMP_BAKE);
  }
};

TEST_F(EmissiveTexturePreview, OnlyTheLitHalfOfTheLampGlows) {
  const QImage image = view_.render_image();
  ASSERT_TRUE(view_.gl_error().isEmpty()) << view_.gl_error().toStdString();
  for (const float z : {-0.25f, 0.0f, 0.25f}) {
    const double lit = mean_around(image, view_.project({-0.25f, 1.0f, z}), 2).luminance();
    const double dark = mean_around(image, view_.project({0.25f, 1.0f, z}), 2).luminance();
    std::cout << "[ measured ] lamp at z = " << z << ": lit half " << lit << ", dark half " << dark
              << "\n";
    EXPECT_GT(lit, 2.0 * dark + 20.0) << "z = " << z;
  }
}

}  // namespace bounce::render_test
