#pragma once
// View 3: the multi-bounce matrix T as a picture before and after the codec's
// row/column reordering, side by side, with one log colour map and its
// legend (compress/matrix_picture.h, the pictures the bake writes), zoom and
// pan shared by both sides, a channel selector, and the entry under the mouse
// (row, column, value, patch ids) in a status line.
#include <memory>

#include <QWidget>

#include "bake_view_data.h"
#include "matrix_panel.h"

class QComboBox;
class QLabel;

namespace bounce::views {

class MatrixView : public QWidget {
  Q_OBJECT
 public:
  enum class Channel { Mean = 0, R = 1, G = 2, B = 3 };

  explicit MatrixView(QWidget* parent = nullptr);

  void set_data(std::shared_ptr<const BakeViewData> bake);
  void set_channel(Channel channel);
  MatrixPanel* before_panel() const { return before_; }
  MatrixPanel* after_panel() const { return after_; }
  // The status line's text (the hovered entry).
  QString hover_text() const;
  // Both sides fitted into their panels.
  void fit();

 private:
  void rebuild();
  void show_hover(bool after, std::size_t r0, std::size_t r1, std::size_t c0, std::size_t c1);
  float value(std::size_t row, std::size_t col) const;

  std::shared_ptr<const BakeViewData> data_;
  std::vector<float> shown_;  // the matrix shown (patch order), n x n
  bool exact_ = true;         // shown_ is the exact T, not the decoded one
  QComboBox* channel_box_;
  QLabel* source_;
  QLabel* hover_;
  MatrixPanel* before_;
  MatrixPanel* after_;
};

}  // namespace bounce::views
