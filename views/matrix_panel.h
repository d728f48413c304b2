#pragma once
// One matrix picture (compress/matrix_picture.h: log colour map, colour bar
// with decade labels) in a zoomable, pannable view. Reports which matrix
// entry is under the mouse; zoom and scroll position can be mirrored onto
// another panel so two pictures move together. Rectangles of entries can be
// outlined on top of the picture (what another view points at).
#include <vector>

#include <QGraphicsView>

#include "bounce/pictures.h"

class QGraphicsPixmapItem;
class QGraphicsRectItem;

namespace bounce::views {

// Where the matrix sits inside a picture made by matrix_picture() for an
// n x n matrix: mirrors the layout arithmetic of compress/matrix_picture.cpp
// (the render tests compare the panel with the bake's PNG and check hover
// values against T.npy, so a drift shows).
struct MatrixPictureLayout {
  int size = 0;  // matrix pixels along a side
  int left = 0, top = 0;
  std::size_t n = 0;

  static MatrixPictureLayout of(std::size_t n, int max_size, const std::string& title);
  // Matrix rows/columns [first, last) drawn in pixel row/column `pixel`.
  std::pair<std::size_t, std::size_t> entries(int pixel) const;
  // The first pixel row/column that draws matrix row/column `entry` (the
  // inverse of entries()).
  int pixel(std::size_t entry) const;
};

// Matrix rows [row_first, row_last) x columns [col_first, col_last).
struct EntryRect {
  std::size_t row_first = 0, row_last = 0, col_first = 0, col_last = 0;
};

class MatrixPanel : public QGraphicsView {
  Q_OBJECT
 public:
  explicit MatrixPanel(QWidget* parent = nullptr);

  void set_picture(const Rgb8Image& picture, const MatrixPictureLayout& layout);
  void clear_picture(const QString& message);
  // Pixels of the picture per screen pixel is 1 / zoom.
  void set_zoom(double zoom);
  double zoom() const { return transform().m11(); }
  void fit();
  // Keeps `other` at this panel's zoom and scroll position, both ways.
  void mirror(MatrixPanel* other);
  // The picture's rectangle in viewport coordinates.
  QRect picture_rect() const;
  const MatrixPictureLayout& layout() const { return layout_; }
  // Outlines these entry rectangles (replacing the previous outlines; none
  // clears them) and, with `centre`, scrolls the first into view.
  void set_highlights(const std::vector<EntryRect>& rects, bool centre);
  // The outlines, in picture pixels (scene coordinates).
  std::vector<QRectF> highlight_rects() const;

 signals:
  // Stored row/column range under the mouse; first == last when off the matrix.
  void hovered(std::size_t row_first, std::size_t row_last, std::size_t col_first,
               std::size_t col_last);
  void zoom_changed(double zoom);
  // A left click on the matrix: the first stored row and column under it.
  void clicked(std::size_t row, std::size_t col);

 protected:
  void wheelEvent(QWheelEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;

 private:
  // The first matrix row and column under a viewport position, or false off the matrix.
  bool entry_at(const QPoint& pos, std::size_t& row, std::size_t& col) const;
  QGraphicsPixmapItem* item_ = nullptr;
  MatrixPictureLayout layout_;
  std::vector<QGraphicsRectItem*> highlights_;
};

QImage to_qimage(const Rgb8Image& picture);

}  // namespace bounce::views
