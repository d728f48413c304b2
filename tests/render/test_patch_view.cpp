#include <QVTKOpenGLNativeWidget.h>
#include <QMouseEvent>
#include <set>

#include <QPushButton>
#include <QTableWidget>

#include "compress/codec.h"
#include "compress/matrix_picture.h"
#include "compress/row_error_contributions.h"
#include "error_source_link.h"
#include "io/npy.h"
#include "matrix_view.h"
#include "patch_view.h"
#include "render_support.h"
#include "runtime/dense_transport.h"
#include "view_jobs.h"

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
  // Processes events until the view jobs have run and shown their results
  // (the radiosity and error colourings are computed there).
  void settle() {
    jobs_.wait_idle();
    render_test::settle();
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::ViewJobs jobs_;
  views::PatchView view_{jobs_};
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
  EXPECT_NE(view_.row_explanation(), nullptr);
}

// A picked patch in the error mode: its exact and compressed indirect light
// are T.npy and the decoded matrix times the light at that patch (computed
// here), the panel lists the core's ranked sources of the difference, and
// picking one marks its block in the matrix view, which can pick the patch
// back.
TEST_F(PatchView, PickedPatchExplainsItsErrorAndLinksToTheMatrix) {
  ASSERT_TRUE(view_.can_show_indirect_error());
  view_.set_colour_by(views::PatchView::ColourBy::IndirectError);
  view_.set_error_light(1);  // evaluation light 0
  settle();
  const LoadedBake& b = data_->bake;
  const std::size_t n = data_->patch_count();
  const NpyArray<float> t = read_npy_f32(fixture_bake() / "T.npy");
  ASSERT_EQ(t.shape[1], n);
  std::vector<const float*> exact, approx;
  std::vector<std::vector<float>> decoded(t.shape[0], std::vector<float>(n * n));
  for (std::size_t c = 0; c < t.shape[0]; ++c) {
    exact.push_back(&t.data[c * n * n]);
    decompress_channel(*b.compressed, static_cast<int>(c), decoded[c].data());
    approx.push_back(decoded[c].data());
  }
  const std::vector<glm::vec3>& light = b.probe.first_hit[0];
  std::vector<glm::vec3> want_exact, want_approx;
  dense_indirect(exact, n, b.channel_of_rgb, light, want_exact);
  dense_indirect(approx, n, b.channel_of_rgb, light, want_approx);
  // The patch the compression hurts most.
  std::size_t p = 0;
  for (std::size_t q = 1; q < n; ++q)
    if (glm::length(want_approx[q] - want_exact[q]) > glm::length(want_approx[p] - want_exact[p]))
      p = q;
  EXPECT_EQ(view_.row_explanation(), nullptr) << "nothing picked yet";
  EXPECT_FALSE(view_.sources_table()->isVisible());
  view_.select_patch(static_cast<int>(p));
  settle();
  const RowErrorContributions* r = view_.row_explanation();
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(view_.sources_table()->isVisible());
  EXPECT_EQ(r->patch, p);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r->exact[k], want_exact[p][k], 1e-4 * std::abs(want_exact[p][k]) + 1e-9);
    EXPECT_NEAR(r->compressed[k], want_approx[p][k], 1e-4 * std::abs(want_approx[p][k]) + 1e-9);
  }
  // The panel shows the core function's result for this bake, patch and light.
  const RowErrorContributions core =
      row_error_contributions(*b.compressed, exact, b.channel_of_rgb, light, p);
  ASSERT_EQ(r->sources.size(), core.sources.size());
  double shares = 0.0;
  for (const RowErrorSource& s : core.sources) shares += s.share;
  EXPECT_NEAR(shares, 1.0, 1e-6);
  const QTableWidget* table = view_.sources_table();
  ASSERT_EQ(table->rowCount(),
            std::min<int>(views::PatchView::kSourcesShown, static_cast<int>(core.sources.size())));
  for (int row = 0; row < table->rowCount(); ++row) {
    const RowErrorSource& s = core.sources[static_cast<std::size_t>(row)];
    EXPECT_EQ(table->item(row, 0)->text(), QString("%1%").arg(100.0 * s.share, 0, 'f', 1));
    EXPECT_EQ(table->item(row, 1)->text().startsWith("block"),
              s.kind == RowErrorSource::Kind::Block);
    EXPECT_TRUE(table->item(row, 3)->text().contains(QString::number(s.entries.front().column)));
  }
  const QString text = view_.explanation_text();
  EXPECT_TRUE(text.contains(QString("Patch %1 (stored row %2").arg(p).arg(core.stored_row)))
      << text.toStdString();
  EXPECT_TRUE(text.contains(QString::number(core.exact.r, 'g', 4))) << text.toStdString();
  EXPECT_TRUE(text.contains(QString::number(core.compressed.g, 'g', 4))) << text.toStdString();

  // Cross-link: the picked source is marked in the matrix view, and back.
  views::MatrixView matrix;
  matrix.resize(1200, 700);
  matrix.show();
  matrix.set_data(data_);
  settle();
  int matrix_shown = 0, patches_shown = 0;
  views::link_error_sources(
      &view_, &matrix, [&] { ++matrix_shown; }, [&] { ++patches_shown; });
  view_.select_source(0);
  settle();
  const RowErrorSource& top = core.sources.front();
  EXPECT_EQ(matrix.marked_patch(), static_cast<int>(p));
  EXPECT_TRUE(matrix.mark_text().contains(QString("stored row %1").arg(core.stored_row)))
      << matrix.mark_text().toStdString();
  const views::MatrixPictureLayout& layout = matrix.after_panel()->layout();
  const std::vector<QRectF> marks = matrix.after_panel()->highlight_rects();
  ASSERT_FALSE(marks.empty());
  // The first mark outlines the source's block (or kept entry) in stored order.
  const std::size_t first_col =
      top.kind == RowErrorSource::Kind::Block ? top.block_col * 4 : top.entries.front().stored_col;
  EXPECT_EQ(marks.front().left(), layout.left + layout.pixel(first_col));
  EXPECT_EQ(marks.front().top(), layout.top + layout.pixel(core.stored_row / 4 * 4));
  EXPECT_EQ(matrix.before_panel()->highlight_rects().front().top(), layout.top + layout.pixel(p));
  view_.matrix_button()->click();
  EXPECT_EQ(matrix_shown, 1);
  // Back: another row marked in the matrix view picks its patch here.
  const int other = static_cast<int>((p + 1) % n);
  matrix.mark_row(other);
  ASSERT_TRUE(matrix.back_button()->isEnabled());
  matrix.back_button()->click();
  settle();
  EXPECT_EQ(patches_shown, 1);
  EXPECT_EQ(view_.selected_patch(), other);
  ASSERT_NE(view_.row_explanation(), nullptr);
  EXPECT_EQ(view_.row_explanation()->patch, static_cast<std::size_t>(other));
}

}  // namespace bounce::render_test
