#include <cmath>
#include <functional>

#include <QComboBox>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QThread>

#include "bake/matrix_storage.h"
#include "error_view.h"
#include "io/npy.h"
#include "render_support.h"
#include "view_jobs.h"

namespace bounce::render_test {

class ErrorView : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    data_ = load_fixture();
    view_.resize(1200, 900);
    view_.show();
    settle();
    view_.set_data(data_);
    settle();
  }
  // Processes events until the view jobs have run and shown their results
  // (the error maps are computed there).
  void settle() {
    jobs_.wait_idle();
    render_test::settle();
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::ViewJobs jobs_;
  views::ErrorView view_{jobs_};
};

TEST_F(ErrorView, NumbersMatchTheManifest) {
  ASSERT_TRUE(view_.has_errors());
  // The bake measured its errors in memory; the view measures them again
  // from the files (T.npy against T.dds + kept entries read back).
  const nlohmann::json e = fixture_manifest()["compression"]["errors"];
  const MatrixError& m = view_.errors().matrix;
  EXPECT_NEAR(m.mean_abs, e["mean_abs"].get<double>(), 1e-6 * e["mean_abs"].get<double>());
  EXPECT_NEAR(m.max_abs, e["max_abs"].get<double>(), 1e-6 * e["max_abs"].get<double>());
  EXPECT_NEAR(m.sum_abs, e["sum_abs"].get<double>(), 1e-6 * e["sum_abs"].get<double>());
  EXPECT_NEAR(m.rel_frobenius, e["rel_frobenius"].get<double>(),
              1e-6 * e["rel_frobenius"].get<double>());
  EXPECT_NEAR(view_.errors().indirect.rel_rms_mean,
              e["indirect_light"]["rel_rms_mean"].get<double>(),
              1e-6 * e["indirect_light"]["rel_rms_mean"].get<double>());
  EXPECT_GT(non_uniform_share(view_.grab().toImage()), 0.2);
}

TEST_F(ErrorView, ClickedBlockShowsItsSixteenValues) {
  const NpyArray<float> t = read_npy_f32(fixture_bake() / "T.npy");
  const NpyArray<std::uint32_t> perm = read_npy_u32(fixture_bake() / "permutation.npy");
  const std::size_t channels = t.shape[0], n = t.shape[1];
  // Click the centre of block (1, 2) of the block heatmap.
  views::MatrixPanel* blocks = view_.block_panel();
  const views::MatrixPictureLayout& layout = blocks->layout();
  ASSERT_EQ(layout.n, (n + 3) / 4);
  const std::size_t br = 1, bc = 2;
  const auto px = layout.size * (static_cast<double>(bc) + 0.5) / static_cast<double>(layout.n);
  const auto py = layout.size * (static_cast<double>(br) + 0.5) / static_cast<double>(layout.n);
  const QPointF centre =
      blocks->viewportTransform().map(QPointF(layout.left + px, layout.top + py));
  const QPoint at(static_cast<int>(std::floor(centre.x())),
                  static_cast<int>(std::floor(centre.y())));
  QMouseEvent press(QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(blocks->viewport(), &press);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const std::size_t pi = perm.data[4 * br + static_cast<std::size_t>(r)];
      const std::size_t pj = perm.data[4 * bc + static_cast<std::size_t>(c)];
      double exact = 0.0;
      for (std::size_t ch = 0; ch < channels; ++ch) exact += t.data[(ch * n + pi) * n + pj];
      exact /= static_cast<double>(channels);
      const QString cell = view_.block_cell(r, c);
      ASSERT_TRUE(cell.contains(" -> ")) << "cell " << r << "," << c << ": " << cell.toStdString();
      EXPECT_NEAR(cell.section(" -> ", 0, 0).toDouble(), exact, 1e-3 * std::abs(exact))
          << cell.toStdString();
    }
}

namespace {

// Waits (processing events) until the view shows its comparison; false on
// failure or after two minutes.
bool wait_for_comparison(views::ErrorView& view, const std::function<void()>& start) {
  bool done = false, ok = false;
  const auto ready = QObject::connect(&view, &views::ErrorView::comparison_ready, [&] {
    done = true;
    ok = true;
  });
  const auto failed =
      QObject::connect(&view, &views::ErrorView::comparison_failed, [&] { done = true; });
  start();
  QElapsedTimer timer;
  timer.start();
  while (!done && timer.elapsed() < 120000) {
    QApplication::processEvents();
    QThread::msleep(5);
  }
  QObject::disconnect(ready);
  QObject::disconnect(failed);
  return ok;
}

// ||T~ - T||_F / ||T||_F over the stored channels, decoded here.
double relative_frobenius(const LoadedBake& b, const CompressedMatrix& c) {
  const std::size_t n = b.size();
  std::vector<float> decoded(n * n);
  double diff2 = 0.0, exact2 = 0.0;
  for (int ch = 0; ch < c.channels; ++ch) {
    decompress_channel(c, ch, decoded.data());
    const std::vector<float>& t = b.dense[static_cast<std::size_t>(ch)];
    for (std::size_t k = 0; k < n * n; ++k) {
      const double d = static_cast<double>(decoded[k]) - t[k];
      diff2 += d * d;
      exact2 += static_cast<double>(t[k]) * t[k];
    }
  }
  return std::sqrt(diff2 / exact2);
}

}  // namespace

TEST_F(ErrorView, CodecSwitchShowsTheCoresErrorForThatCodec) {
  const LoadedBake& b = data_->bake;
  ASSERT_TRUE(b.compressed);
  ASSERT_EQ(b.compressed->codec, "ours");
  // The core's compression stage with the paper's codec on the same exact
  // matrix and kept fraction: what the switch must show.
  BakeSettings s;
  s.codec = CodecChoice::LargestEntries;
  s.kept_fraction = b.compressed->kept_fraction;
  Diagnostics diagnostics;
  std::vector<const float*> exact;
  for (const auto& m : b.dense) exact.push_back(m.data());
  const MatrixStorage paper = store_matrices(exact, b.size(), b.probe, s, nullptr, diagnostics);

  QComboBox* codec = view_.codec_box();
  ASSERT_TRUE(wait_for_comparison(view_, [&] {
    codec->setCurrentIndex(codec->findData(static_cast<int>(CodecChoice::LargestEntries)));
  }));
  ASSERT_NE(view_.shown_matrix(), nullptr);
  EXPECT_EQ(view_.shown_matrix()->codec, "paper");
  EXPECT_EQ(view_.shown_matrix()->ordering, "paper-2-passes");
  EXPECT_EQ(view_.shown_matrix()->kept_fraction, b.compressed->kept_fraction);
  const MatrixError& shown = view_.errors().matrix;
  EXPECT_NEAR(shown.rel_frobenius, paper.errors.matrix.rel_frobenius,
              1e-9 * paper.errors.matrix.rel_frobenius);
  EXPECT_NEAR(shown.max_abs, paper.errors.matrix.max_abs, 1e-9 * paper.errors.matrix.max_abs);
  EXPECT_NEAR(view_.errors().indirect.rel_rms_mean, paper.errors.indirect.rel_rms_mean,
              1e-9 * paper.errors.indirect.rel_rms_mean);
  // Independent of the core's error code: decode the shown matrix here.
  EXPECT_NEAR(shown.rel_frobenius, relative_frobenius(b, *view_.shown_matrix()),
              1e-4 * shown.rel_frobenius);
  // The numbers on screen are these.
  EXPECT_TRUE(view_.figures_text().contains(QString::number(shown.rel_frobenius, 'g', 4)))
      << view_.figures_text().toStdString();
  EXPECT_TRUE(view_.figures_text().contains("paper")) << view_.figures_text().toStdString();
  EXPECT_NE(shown.rel_frobenius, fixture_manifest()["compression"]["errors"]["rel_frobenius"]);

  // A clicked block shows the paper matrix decoded, at its own permutation.
  view_.select_block(0, 1);
  const CompressedMatrix& c = *view_.shown_matrix();
  const std::size_t n = b.size();
  std::vector<double> decoded_mean(n * n, 0.0);
  std::vector<float> decoded(n * n);
  for (int ch = 0; ch < c.channels; ++ch) {
    decompress_channel(c, ch, decoded.data());
    for (std::size_t k = 0; k < n * n; ++k)
      decoded_mean[k] += static_cast<double>(decoded[k]) / c.channels;
  }
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) {
      const std::size_t k = c.permutation[static_cast<std::size_t>(r)] * n +
                            c.permutation[4 + static_cast<std::size_t>(col)];
      const QString cell = view_.block_cell(r, col);
      ASSERT_TRUE(cell.contains(" -> ")) << cell.toStdString();
      EXPECT_NEAR(cell.section(" -> ", 1, 1).toDouble(), decoded_mean[k],
                  1e-3 * std::abs(decoded_mean[k]) + 1e-12)
          << cell.toStdString();
    }

  // Ours at the bake's kept fraction re-compresses to the stored bake exactly.
  ASSERT_TRUE(wait_for_comparison(view_, [&] {
    codec->setCurrentIndex(codec->findData(static_cast<int>(CodecChoice::LightWeighted)));
  }));
  const nlohmann::json e = fixture_manifest()["compression"]["errors"];
  EXPECT_NEAR(view_.errors().matrix.rel_frobenius, e["rel_frobenius"].get<double>(),
              1e-6 * e["rel_frobenius"].get<double>());
  // And "as baked" brings back the stored matrix at once.
  ASSERT_TRUE(wait_for_comparison(view_, [&] { codec->setCurrentIndex(0); }));
  EXPECT_EQ(view_.shown_matrix(), &*b.compressed);
  EXPECT_GT(non_uniform_share(view_.grab().toImage()), 0.2);
}

}  // namespace bounce::render_test
