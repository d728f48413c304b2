#include "error_histogram.h"

#include <algorithm>
#include <cmath>

#include <QPainter>

namespace bounce::views {

namespace {
constexpr int kBinsPerDecade = 10;
}

ErrorHistogram::ErrorHistogram(QWidget* parent) : QWidget(parent) {
  setMinimumHeight(120);
  setToolTip(
      tr("How many matrix entries have each |error|, log scale; kept entries (exact) are "
         "counted apart"));
}

void ErrorHistogram::set_values(const std::vector<float>& abs_error) {
  bins_.clear();
  zeros_ = 0;
  float vmax = 0.0f, vmin = 0.0f;
  for (float e : abs_error) {
    if (!(e > 0.0f)) continue;
    vmax = std::max(vmax, e);
    vmin = vmin > 0.0f ? std::min(vmin, e) : e;
  }
  if (vmax > 0.0f) {
    // At most 8 decades below the largest error.
    const int top = static_cast<int>(std::ceil(std::log10(static_cast<double>(vmax))));
    first_decade_ =
        std::max(top - 8, static_cast<int>(std::floor(std::log10(static_cast<double>(vmin)))));
    bins_.assign(static_cast<std::size_t>((top - first_decade_) * kBinsPerDecade), 0);
  }
  for (float e : abs_error) {
    if (!(e > 0.0f)) {
      ++zeros_;
      continue;
    }
    const double t = (std::log10(static_cast<double>(e)) - first_decade_) * kBinsPerDecade;
    const auto k =
        static_cast<std::size_t>(std::clamp(t, 0.0, static_cast<double>(bins_.size()) - 1.0));
    ++bins_[k];
  }
  update();
}

void ErrorHistogram::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), Qt::white);
  const int label = fontMetrics().height() + 4;
  const QRect plot = rect().adjusted(8, label, -8, -label);
  painter.setPen(Qt::black);
  painter.drawText(QRect(0, 0, width(), label), Qt::AlignCenter,
                   tr("|error| per entry (%1 exact zeros not shown)").arg(zeros_));
  if (bins_.empty()) return;
  const std::size_t most = *std::max_element(bins_.begin(), bins_.end());
  const double bar = static_cast<double>(plot.width()) / static_cast<double>(bins_.size());
  for (std::size_t k = 0; k < bins_.size(); ++k) {
    const int h = most ? static_cast<int>(static_cast<double>(plot.height()) *
                                          static_cast<double>(bins_[k]) / static_cast<double>(most))
                       : 0;
    painter.fillRect(QRectF(plot.left() + bar * static_cast<double>(k), plot.bottom() - h,
                            std::max(1.0, bar - 1.0), h),
                     QColor(59, 81, 139));
  }
  const int decades = static_cast<int>(bins_.size()) / kBinsPerDecade;
  for (int d = 0; d <= decades; ++d) {
    const int x = plot.left() + static_cast<int>(bar * d * kBinsPerDecade);
    painter.drawLine(x, plot.bottom(), x, plot.bottom() + 3);
    painter.drawText(QRect(x - 30, plot.bottom() + 3, 60, label), Qt::AlignHCenter,
                     QString("1e%1").arg(first_decade_ + d));
  }
}

}  // namespace bounce::views
