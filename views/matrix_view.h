#pragma once
// View 3: the multi-bounce matrix T as a picture before and after the codec's
// row/column reordering, side by side, with one log colour map and its
// legend (compress/matrix_picture.h, the pictures the bake writes), zoom and
// pan shared by both sides, a channel selector, and the entry under the mouse
// (row, column, value, patch ids) in a status line. One patch's row can be
// marked (another view asks for it, or a click on an entry picks its row):
// the row in patch order, one 4x4 block of the reordered matrix, and a
// button that asks to show that patch elsewhere.
#include <memory>

#include <QWidget>

#include "bake_view_data.h"
#include "matrix_panel.h"

class QComboBox;
class QLabel;
class QPushButton;

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
  // Marks patch `patch`'s row: the whole row in patch order, and in the
  // reordered picture the block of stored row `stored_row` and stored columns
  // [stored_col_first, stored_col_last) (the row alone when the range is
  // empty), scrolled into view. -1 clears the mark.
  void mark_row(int patch, std::size_t stored_row = 0, std::size_t stored_col_first = 0,
                std::size_t stored_col_last = 0);
  int marked_patch() const { return marked_patch_; }
  QString mark_text() const;
  // The button that emits patch_requested for the marked patch.
  QPushButton* back_button() const { return back_; }

 signals:
  // The user asks to see this patch in the patch view.
  void patch_requested(int patch);

 private:
  void restore_mark();
  void pick_entry(bool after, std::size_t row, std::size_t col);
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
  QLabel* mark_;
  QPushButton* back_;
  int marked_patch_ = -1;
  std::size_t marked_row_ = 0, marked_col_first_ = 0, marked_col_last_ = 0;
};

}  // namespace bounce::views
