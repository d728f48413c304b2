#include <QMouseEvent>

#include "error_view.h"
#include "io/npy.h"
#include "render_support.h"

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
  std::shared_ptr<const views::BakeViewData> data_;
  views::ErrorView view_;
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

}  // namespace bounce::render_test
