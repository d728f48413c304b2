#include <QVTKOpenGLNativeWidget.h>
#include <QMouseEvent>
#include <set>

#include "compress/matrix_picture.h"
#include "patch_view.h"
#include "render_support.h"

namespace bounce::render_test {

class PatchView : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    data_ = load_fixture();
    view_.resize(640, 480);
    view_.show();
    settle();
    view_.set_data(data_);
    settle();
  }
  // Patches whose normal points at the camera: their disc centre is in view
  // unless something stands in front of it.
  std::vector<int> patches_facing_camera() const {
    const glm::vec3 eye = data_->scene->camera.position;
    std::vector<int> facing;
    for (std::size_t p = 0; p < data_->patch_count(); ++p) {
      const Patch& patch = data_->bake.patches.patches[p];
      if (glm::dot(patch.normal, glm::normalize(eye - patch.position)) > 0.95f)
        facing.push_back(static_cast<int>(p));
    }
    return facing;
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::PatchView view_;
};

TEST_F(PatchView, DiscsShowTheWallColours) {
  const QImage image = view_.render_image().convertToFormat(QImage::Format_RGB32);
  EXPECT_EQ(view_.patch_colours().size(), data_->patch_count());
  // The Cornell box has a red and a green wall: coloured by albedo, both show.
  std::size_t red = 0, green = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QRgb c = image.pixel(x, y);
      // Hue dominance: the walls' albedos are far from grey in sRGB.
      red += qRed(c) > 60 && qRed(c) * 2 > qGreen(c) * 3 && qRed(c) * 2 > qBlue(c) * 3;
      green += qGreen(c) > 60 && qGreen(c) * 2 > qRed(c) * 3 && qGreen(c) * 2 > qBlue(c) * 3;
    }
  const std::size_t total = static_cast<std::size_t>(image.width() * image.height());
  EXPECT_GT(red, total / 100);
  EXPECT_GT(green, total / 100);
}

TEST_F(PatchView, ClickPicksThePatchUnderTheMouse) {
  ASSERT_TRUE(data_->scene);
  const std::vector<int> facing = patches_facing_camera();
  ASSERT_GE(facing.size(), 4u);
  std::size_t exact = 0;
  for (int p : facing) {
    const QPoint at = view_.project_patch(p);
    const int q = view_.patch_at(at.x(), at.y());
    ASSERT_GE(q, 0) << "nothing picked at the centre of patch " << p;
    // Another disc may overlap the centre (a neighbour, or a box in front),
    // but most centres are their own patch's.
    exact += q == p ? 1 : 0;
  }
  EXPECT_GE(exact * 2, facing.size());

  // A real click goes through VTK's interactor to the same pick.
  auto* gl = view_.findChild<QVTKOpenGLNativeWidget*>();
  ASSERT_NE(gl, nullptr);
  const int p = facing[facing.size() / 2];
  const QPoint in_view = view_.project_patch(p);
  const int expected = view_.patch_at(in_view.x(), in_view.y());
  // project_patch gives the VTK widget's own coordinates (below the control
  // bar), which is where the mouse event goes.
  const QPoint local = in_view;
  QMouseEvent press(QEvent::MouseButtonPress, local, Qt::LeftButton, Qt::LeftButton,
                    Qt::NoModifier);
  QMouseEvent release(QEvent::MouseButtonRelease, local, Qt::LeftButton, Qt::NoButton,
                      Qt::NoModifier);
  QApplication::sendEvent(gl, &press);
  QApplication::sendEvent(gl, &release);
  settle();
  EXPECT_EQ(view_.selected_patch(), expected);
}

TEST_F(PatchView, PickedPatchColoursItsFormFactorRow) {
  ASSERT_FALSE(data_->form_factors.empty()) << "the fixture bake keeps F.npy";
  const std::size_t n = data_->patch_count();
  const int p = patches_facing_camera().front();
  view_.select_patch(p);
  ASSERT_EQ(view_.selected_patch(), p);
  const float* row = &data_->form_factors[static_cast<std::size_t>(p) * n];
  const std::size_t best = static_cast<std::size_t>(std::max_element(row, row + n) - row);
  ASSERT_GT(row[best], 0.0f);
  const auto& colours = view_.patch_colours();
  // The patch it sends most light to is at the top of the colour map
  // (viridis yellow, 253 231 37); patches it does not see are black.
  EXPECT_EQ(colours[best], (std::array<unsigned char, 3>{253, 231, 37}));
  std::size_t unseen = 0;
  for (std::size_t q = 0; q < n; ++q)
    if (row[q] == 0.0f) {
      ++unseen;
      EXPECT_EQ(colours[q], (std::array<unsigned char, 3>{0, 0, 0})) << "patch " << q;
    }
  EXPECT_GT(unseen, 0u) << "a patch on a wall does not see its own wall";
  EXPECT_GT(non_uniform_share(view_.render_image()), 0.2);
}

TEST_F(PatchView, ClosureAndBalancingScaleColourEachPatch) {
  // The Cornell box is open at the front: patches facing it lose light there
  // (closure below 1), patches deep inside keep nearly all of it.
  ASSERT_EQ(data_->closure.size(), data_->patch_count()) << "the fixture bake has closure.npy";
  const std::size_t n = data_->patch_count();
  view_.set_colour_by(views::PatchView::ColourBy::Closure);
  settle();
  const auto most_open = static_cast<std::size_t>(
      std::min_element(data_->closure.begin(), data_->closure.end()) - data_->closure.begin());
  const auto most_closed = static_cast<std::size_t>(
      std::max_element(data_->closure.begin(), data_->closure.end()) - data_->closure.begin());
  ASSERT_LT(data_->closure[most_open], data_->closure[most_closed]);
  for (std::size_t p : {most_open, most_closed}) {
    std::uint8_t expected[3];
    colormap(static_cast<double>(data_->closure[p]), expected);
    EXPECT_EQ(view_.patch_colours()[p],
              (std::array<unsigned char, 3>{expected[0], expected[1], expected[2]}))
        << "patch " << p << " closure " << data_->closure[p];
  }
  EXPECT_GT(non_uniform_share(view_.render_image()), 0.2);

  // Balancing scale: white where the row kept its sum, red where it was
  // scaled up, blue where down.
  view_.set_colour_by(views::PatchView::ColourBy::RowScale);
  settle();
  for (std::size_t p = 0; p < n; ++p) {
    const float s = data_->row_scale[p];
    const auto& c = view_.patch_colours()[p];
    if (s > 1.01f) {
      EXPECT_EQ(c[0], 255) << "scaled up, patch " << p;
      EXPECT_LT(c[2], 255) << "scaled up, patch " << p;
    } else if (s < 0.99f) {
      EXPECT_EQ(c[2], 255) << "scaled down, patch " << p;
      EXPECT_LT(c[0], 255) << "scaled down, patch " << p;
    }
  }
}

}  // namespace bounce::render_test

namespace bounce::render_test {

// The indirect-light error on the scene: the figure the view shows for the
// scene's lights is `bounce solve --compare-exact`'s for the same bake, each
// patch is coloured from the error map by its own relative error, and a
// picked patch names its exact and compressed light and the entries behind
// the difference.
TEST_F(PatchView, IndirectErrorOnTheSceneMatchesTheCli) {
  ASSERT_TRUE(view_.can_show_indirect_error()) << "the fixture is compressed, with T.npy";
  view_.set_colour_by(views::PatchView::ColourBy::IndirectError);
  view_.set_error_light(0);
  settle();
  const double shown = view_.indirect_error_rms();
  EXPECT_GT(shown, 0.0);
  const std::filesystem::path out = work_dir("indirect-error");
  const CommandRun r = run_command(std::string(BOUNCE_CLI) + " solve " + fixture_bake().string() +
                                   " --compare-exact --multiply cpp --float32 --no-mesh "
                                   "--no-images --json --quiet --out " +
                                   out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json summary = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  const double cli = summary.at("compare_exact").at("patch_indirect_rel_rms").get<double>();
  // The view multiplies the decoded matrix with sgemv, the CLI runs the
  // compressed loop: float rounding apart, one figure.
  EXPECT_NEAR(shown, cli, 1e-3 * cli);
  EXPECT_TRUE(view_.status_text().contains(QString::number(shown, 'g', 4)))
      << view_.status_text().toStdString();
  // The colours come from the error map: not all one colour.
  std::set<std::array<unsigned char, 3>> colours(view_.patch_colours().begin(),
                                                 view_.patch_colours().end());
  EXPECT_GT(colours.size(), 3u);
  const QImage image = view_.render_image();
  EXPECT_GT(non_uniform_share(image), 0.01);
  // Another light, another figure.
  view_.set_error_light(2);
  settle();
  EXPECT_NE(view_.indirect_error_rms(), shown);
  // Picking a patch keeps the mode and explains it.
  view_.select_patch(0);
  settle();
  EXPECT_TRUE(view_.status_text().contains("patch 0: exact")) << view_.status_text().toStdString();
  EXPECT_TRUE(view_.status_text().contains("from columns")) << view_.status_text().toStdString();
}

}  // namespace bounce::render_test
