#pragma once
// Histogram of |error| per matrix entry on a log axis (one bar per
// tenth of a decade), for the compression error view. Exact zeros (kept
// entries) are counted apart and named in the caption.
#include <QWidget>
#include <vector>

namespace bounce::views {

class ErrorHistogram : public QWidget {
  Q_OBJECT
 public:
  explicit ErrorHistogram(QWidget* parent = nullptr);
  void set_values(const std::vector<float>& abs_error);
  QSize sizeHint() const override { return {360, 160}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  std::vector<std::size_t> bins_;
  int first_decade_ = 0;  // log10 of the left edge
  std::size_t zeros_ = 0;
};

}  // namespace bounce::views
