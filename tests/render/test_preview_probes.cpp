// The preview's light probes on the Cornell box baked with them (x from -1
// to 1 with the red wall at -x and the green wall at +x, floor y = 0,
// ceiling y = 2, back wall z = -1; the scene camera looks down -z, so -x is
// the picture's left): the probe-lit sphere and the probes' overlay.
#include <algorithm>
#include <cmath>
#include <string>

#include "bounce/error.h"
#include "bounce/relight.h"
#include "preview_test_support.h"

namespace bounce::render_test {

namespace {

views::PreviewWidget::Passes indirect_only() {
  views::PreviewWidget::Passes p;
  p.direct = false;
  p.ao = false;
  return p;
}

}  // namespace

class ProbePreview : public PreviewOfBake {
 protected:
  void SetUp() override {
    PreviewOfBake::SetUp();
    open(BOUNCE_RENDER_PROBE_BAKE);
    ASSERT_TRUE(view_.has_probes()) << "the fixture was baked without --light-probes";
  }
};

TEST_F(ProbePreview, SphereBesideTheRedWallIsRedderOnThatSide) {
  view_.set_light_position({0.0f, 1.4f, 0.2f}, true);
  const glm::vec3 centre(-0.55f, 1.0f, 0.2f);
  view_.set_sphere_shown(true);
  view_.set_sphere_position(centre);
  const QImage image = shot(indirect_only());
  // The core's SH first: the irradiance arriving from the red wall's side
  // is redder than from the green wall's.
  const auto& sh = view_.sphere_sh();
  const glm::vec3 from_red = sh_irradiance(sh.data(), {-1.0f, 0.0f, 0.0f});
  const glm::vec3 from_green = sh_irradiance(sh.data(), {1.0f, 0.0f, 0.0f});
  ASSERT_GT(from_red.x + from_red.y, 0.0f) << "the sphere gets no light from the probes";
  EXPECT_GT(from_red.x / from_red.y, 1.2f * from_green.x / from_green.y);

  // Then the picture: the sphere's left side (facing the red wall) against
  // its right side, each 0.7 of the radius off the centre.
  const float r = view_.sphere_radius();
  const Rgb left = mean_around(image, view_.project(centre - glm::vec3(0.7f * r, 0.0f, 0.0f)));
  const Rgb right = mean_around(image, view_.project(centre + glm::vec3(0.7f * r, 0.0f, 0.0f)));
  ASSERT_GT(left.luminance(), 8.0) << "the sphere's left side is too dark to judge";
  ASSERT_GT(right.luminance(), 8.0) << "the sphere's right side is too dark to judge";
  EXPECT_GT(left.red_share(), 1.1 * right.red_share())
      << "left " << left.r << " " << left.g << " " << left.b << ", right " << right.r << " "
      << right.g << " " << right.b;

  // Without the sphere the same pixel shows the wall behind it instead.
  view_.set_sphere_shown(false);
  const Rgb behind = mean_around(shot(indirect_only()), view_.project(centre));
  const Rgb sphere = mean_around(image, view_.project(centre));
  EXPECT_GT(std::abs(sphere.luminance() - behind.luminance()) + std::abs(sphere.r - behind.r), 3.0)
      << "the sphere is not drawn";
}

TEST_F(ProbePreview, TheSphereFollowsTheLight) {
  view_.set_sphere_shown(true);
  const glm::vec3 centre(0.0f, 1.0f, 0.3f);
  view_.set_sphere_position(centre);
  const QPointF at = view_.project(centre - glm::vec3(0.5f * view_.sphere_radius(), 0, 0));
  view_.set_light_position({-0.7f, 1.2f, 0.3f}, true);
  const Rgb near_left = mean_around(shot(indirect_only()), at);
  view_.set_light_position({0.7f, 1.2f, -0.6f}, true);
  const Rgb far_right = mean_around(shot(indirect_only()), at);
  // The sphere's left side, seen with the light beside it and then across
  // the box: the probes' bounced light there changes with the light.
  EXPECT_GT(std::abs(near_left.luminance() - far_right.luminance()), 2.0);
}

TEST_F(ProbePreview, ProbeOverlayChangesWhenTheLightMoves) {
  const glm::vec3 left(-0.7f, 1.4f, 0.3f), right(0.7f, 1.4f, 0.3f);
  auto pictures = [&](const glm::vec3& light) {
    view_.set_light_position(light, true);
    view_.set_probes_shown(true);
    const QImage with = shot(indirect_only());
    view_.set_probes_shown(false);
    return std::pair{with, shot(indirect_only())};
  };
  const auto [left_with, left_without] = pictures(left);
  const auto [right_with, right_without] = pictures(right);
  // The probes' pixels: where the overlay changes the picture.
  const QImage a = left_with.convertToFormat(QImage::Format_RGB32);
  const QImage b = left_without.convertToFormat(QImage::Format_RGB32);
  const QImage c = right_with.convertToFormat(QImage::Format_RGB32);
  double left_half[2] = {0, 0}, right_half[2] = {0, 0};
  std::size_t probe_pixels = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      if (a.pixel(x, y) == b.pixel(x, y)) continue;
      ++probe_pixels;
      const double lum_left = qGray(a.pixel(x, y)), lum_right = qGray(c.pixel(x, y));
      double* half = x < a.width() / 2 ? left_half : right_half;
      half[0] += lum_left;
      half[1] += lum_right;
    }
  ASSERT_GT(probe_pixels, 200u) << "the overlay draws no probes";
  // Each half's probes are brighter with the light on their side.
  EXPECT_GT(left_half[0], 1.1 * left_half[1]);
  EXPECT_GT(right_half[1], 1.1 * right_half[0]);
}

TEST_F(ProbePreview, ALoadedMeshTakesTheSpheresPlace) {
  // Settled first: no later solve changes the light between the pictures.
  view_.set_light_position({0.0f, 1.4f, 0.2f}, true);
  view_.set_sphere_shown(true);
  const glm::vec3 centre(0.0f, 1.0f, 0.3f);
  view_.set_sphere_position(centre);
  const QImage sphere = shot({});
  const std::string bunny =
      std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-bunny/stanford-bunny.obj";
  view_.load_object(bunny);
  EXPECT_EQ(view_.object_name(), "stanford-bunny");
  const QImage loaded = shot({});
  // The pixels around the object's place change (with the screen-space
  // occlusion it casts, up to 5% of the scene's diagonal around it); the
  // rest of the picture not.
  const QPointF at = view_.project(centre);
  const double r =
      4.0 * (view_.project(centre + glm::vec3(view_.sphere_radius(), 0, 0)).x() - at.x());
  std::size_t inside = 0, outside = 0;
  const QImage a = sphere.convertToFormat(QImage::Format_RGB32);
  const QImage b = loaded.convertToFormat(QImage::Format_RGB32);
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      if (a.pixel(x, y) == b.pixel(x, y)) continue;
      const bool near = std::hypot(x - at.x(), y - at.y()) <= r;
      ++(near ? inside : outside);
    }
  EXPECT_GT(inside, 20u) << "the bunny looks like the sphere";
  EXPECT_LT(outside, inside / 10 + 5)
      << "the object changed pixels far from its place: " << outside << " of " << inside + outside;

  // A file that is not a mesh: one error naming it, the object unchanged.
  try {
    view_.load_object("/nonexistent/object.obj");
    ADD_FAILURE() << "a missing file was loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/object.obj"), std::string::npos) << e.what();
  }
  EXPECT_EQ(view_.object_name(), "stanford-bunny");
  view_.use_sphere();
  EXPECT_EQ(view_.object_name(), "sphere");
}

}  // namespace bounce::render_test
