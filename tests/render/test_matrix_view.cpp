#include <QMouseEvent>
#include <QPushButton>
#include <QScrollBar>

#include "io/npy.h"
#include "matrix_view.h"
#include "render_support.h"

namespace bounce::render_test {

class MatrixView : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    data_ = load_fixture();
    view_.resize(1600, 900);
    view_.show();
    settle();
    view_.set_data(data_);
    // One picture pixel per screen pixel, as the bake wrote it.
    view_.after_panel()->set_zoom(1.0);
    settle();
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::MatrixView view_;
};

TEST_F(MatrixView, ReorderedPictureMatchesTheBakePng) {
  views::MatrixPanel* after = view_.after_panel();
  ASSERT_DOUBLE_EQ(view_.before_panel()->zoom(), 1.0) << "zoom is shared by both sides";
  const QRect rect = after->picture_rect();
  ASSERT_TRUE(after->viewport()->rect().contains(rect)) << "the picture must fit the panel";
  const QImage shown =
      after->viewport()->grab(rect).toImage().convertToFormat(QImage::Format_RGB32);
  const QImage png = QImage(QString::fromStdString((fixture_bake() / "T_reordered.png").string()))
                         .convertToFormat(QImage::Format_RGB32);
  ASSERT_FALSE(png.isNull());
  ASSERT_EQ(shown.size(), png.size());
  std::size_t close = 0;
  for (int y = 0; y < png.height(); ++y)
    for (int x = 0; x < png.width(); ++x) {
      const QRgb a = shown.pixel(x, y), b = png.pixel(x, y);
      close += std::abs(qRed(a) - qRed(b)) <= 2 && std::abs(qGreen(a) - qGreen(b)) <= 2 &&
               std::abs(qBlue(a) - qBlue(b)) <= 2;
    }
  const auto total = static_cast<std::size_t>(png.width() * png.height());
  EXPECT_GE(close, total * 99 / 100) << close << " of " << total << " pixels match";
  // And the "before" side is a different picture (the reordering moved entries).
  const QImage before = view_.before_panel()
                            ->viewport()
                            ->grab(view_.before_panel()->picture_rect())
                            .toImage()
                            .convertToFormat(QImage::Format_RGB32);
  ASSERT_EQ(before.size(), png.size());
  EXPECT_NE(before, shown);
}

TEST_F(MatrixView, HoverShowsTheEntryOfTNpy) {
  const NpyArray<float> t = read_npy_f32(fixture_bake() / "T.npy");
  const NpyArray<std::uint32_t> perm = read_npy_u32(fixture_bake() / "permutation.npy");
  const std::size_t channels = t.shape[0], n = t.shape[1];
  views::MatrixPanel* after = view_.after_panel();
  const views::MatrixPictureLayout& layout = after->layout();
  ASSERT_EQ(layout.n, n);
  ASSERT_EQ(layout.size, static_cast<int>(n)) << "one pixel per entry at this size";
  for (const auto& [i, j] : {std::pair<std::size_t, std::size_t>{n / 3, n / 2},
                             {0, n - 1},
                             {n - 1, 0},
                             {n / 2, n / 2}}) {
    // The viewport pixel holding the centre of entry (i, j)'s picture pixel.
    const QPointF centre = after->viewportTransform().map(
        QPointF(static_cast<double>(layout.left) + static_cast<double>(j) + 0.5,
                static_cast<double>(layout.top) + static_cast<double>(i) + 0.5));
    const QPoint at(static_cast<int>(std::floor(centre.x())),
                    static_cast<int>(std::floor(centre.y())));
    QMouseEvent move(QEvent::MouseMove, at, Qt::NoButton, Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(after->viewport(), &move);
    const QString text = view_.hover_text();
    ASSERT_FALSE(text.isEmpty()) << "no hover text at " << at.x() << "," << at.y();
    const std::size_t pi = perm.data[i], pj = perm.data[j];
    EXPECT_TRUE(text.contains(QString("i = %1, j = %2").arg(i).arg(j))) << text.toStdString();
    EXPECT_TRUE(text.contains(QString("patches %1 -> %2").arg(pi).arg(pj))) << text.toStdString();
    // The mean of the stored channels of T.npy at (perm[i], perm[j]).
    double expected = 0.0;
    for (std::size_t c = 0; c < channels; ++c) expected += t.data[(c * n + pi) * n + pj];
    expected /= static_cast<double>(channels);
    const double shown = text.section("T = ", 1).toDouble();
    EXPECT_NEAR(shown, expected, 1e-5 * std::abs(expected) + 1e-12) << text.toStdString();
  }
}

// A click on an entry of the reordered picture marks its row: the patch it
// belongs to (permutation.npy), the entry's 4x4 block outlined, and the
// button that picks the patch in the patch view.
TEST_F(MatrixView, ClickMarksTheEntrysRowAndBlock) {
  const NpyArray<std::uint32_t> perm = read_npy_u32(fixture_bake() / "permutation.npy");
  views::MatrixPanel* after = view_.after_panel();
  const views::MatrixPictureLayout& layout = after->layout();
  const std::size_t n = layout.n, i = n / 3, j = n / 2 + 1;
  EXPECT_FALSE(view_.back_button()->isEnabled()) << "nothing marked yet";
  const QPointF centre = after->viewportTransform().map(
      QPointF(static_cast<double>(layout.left) + static_cast<double>(j) + 0.5,
              static_cast<double>(layout.top) + static_cast<double>(i) + 0.5));
  const QPoint at(static_cast<int>(std::floor(centre.x())),
                  static_cast<int>(std::floor(centre.y())));
  QMouseEvent press(QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(after->viewport(), &press);
  QMouseEvent release(QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton, Qt::NoModifier);
  QApplication::sendEvent(after->viewport(), &release);
  settle();
  EXPECT_EQ(view_.marked_patch(), static_cast<int>(perm.data[i]));
  EXPECT_TRUE(view_.back_button()->isEnabled());
  const std::vector<QRectF> marks = after->highlight_rects();
  ASSERT_EQ(marks.size(), 2u) << "the block and the stored row";
  EXPECT_EQ(marks[0], QRectF(layout.left + static_cast<double>(j / 4 * 4),
                             layout.top + static_cast<double>(i / 4 * 4), 4, 4));
  EXPECT_EQ(marks[1],
            QRectF(layout.left, layout.top + static_cast<double>(i), static_cast<double>(n), 1));
  int requested = -1;
  QObject::connect(&view_, &views::MatrixView::patch_requested, [&](int p) { requested = p; });
  view_.back_button()->click();
  EXPECT_EQ(requested, static_cast<int>(perm.data[i]));
  // A new picture (another channel) keeps the mark.
  view_.set_channel(views::MatrixView::Channel::G);
  settle();
  EXPECT_EQ(after->highlight_rects().size(), 2u);
}

}  // namespace bounce::render_test
