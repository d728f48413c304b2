#pragma once
// Shared by the live preview's render tests: a preview at 400 x 300 without
// its text overlay on a bake folder, and the mean colour of a spot of its
// picture.
#include <algorithm>
#include <memory>

#include <QApplication>
#include <QElapsedTimer>
#include <QImage>
#include <QPointF>

#include "preview_widget.h"
#include "render_support.h"
#include "view_jobs.h"

namespace bounce::render_test {

struct Rgb {
  double r = 0, g = 0, b = 0;
  double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
  double red_share() const { return r / std::max(1.0, r + g + b); }
};

// Mean 8-bit colour of the (2h+1)^2 pixels around `at`.
inline Rgb mean_around(const QImage& image, QPointF at, int h = 3) {
  Rgb sum;
  int n = 0;
  const QImage im = image.convertToFormat(QImage::Format_RGB32);
  for (int y = static_cast<int>(at.y()) - h; y <= static_cast<int>(at.y()) + h; ++y)
    for (int x = static_cast<int>(at.x()) - h; x <= static_cast<int>(at.x()) + h; ++x) {
      if (x < 0 || y < 0 || x >= im.width() || y >= im.height()) continue;
      const QRgb c = im.pixel(x, y);
      sum.r += qRed(c);
      sum.g += qGreen(c);
      sum.b += qBlue(c);
      ++n;
    }
  if (n > 0) sum = {sum.r / n, sum.g / n, sum.b / n};
  return sum;
}

// The preview at 400 x 300 without overlay (text would land on the pixels
// compared) on the bake folder `bake`.
class PreviewOfBake : public RenderTest {
 protected:
  void open(const char* bake) {
    data_ = views::load_bake_view_data(bake);
    ASSERT_TRUE(data_->scene) << "the scene of " << bake << " is not on disk";
    view_.resize(400, 300);
    view_.set_overlay(false);
    view_.show();
    settle();
    view_.set_data(data_);
    settle();
  }
  // Waits (up to a minute) until the preview has solved the light at
  // `position` with its spread shadow rays and gather rows settled there.
  void wait_until_settled_at(const glm::vec3& position) {
    QElapsedTimer waited;
    waited.start();
    while ((view_.solved_light_position() != position || !view_.solved_settled()) &&
           waited.elapsed() < 60'000)
      QApplication::processEvents(QEventLoop::AllEvents, 50);
  }
  QImage shot(views::PreviewWidget::Passes passes) {
    view_.set_passes(passes);
    const QImage image = view_.render_image();
    EXPECT_TRUE(view_.gl_error().isEmpty()) << view_.gl_error().toStdString();
    return image;
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::ViewJobs jobs_;
  views::PreviewWidget view_{jobs_};
};

}  // namespace bounce::render_test
