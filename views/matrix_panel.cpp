#include "matrix_panel.h"

#include <algorithm>
#include <cmath>

#include <QGraphicsPixmapItem>
#include <QGraphicsRectItem>
#include <QGraphicsScene>
#include <QGraphicsSimpleTextItem>
#include <QMouseEvent>
#include <QScrollBar>
#include <QWheelEvent>

#include "bounce/pictures.h"

namespace bounce::views {

MatrixPictureLayout MatrixPictureLayout::of(std::size_t n, int max_size, const std::string& title) {
  MatrixPictureLayout l;
  l.n = n;
  l.size = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(max_size)));
  const int margin = std::max(4, l.size / 64);
  const int font = std::max(10, l.size / 48);
  l.left = margin;
  l.top = title.empty() || text_width(title, font) == 0 ? margin : margin + 2 * font;
  return l;
}

std::pair<std::size_t, std::size_t> MatrixPictureLayout::entries(int pixel) const {
  const auto p = static_cast<std::size_t>(pixel), s = static_cast<std::size_t>(size);
  const std::size_t first = p * n / s;
  return {first, std::max(first + 1, (p + 1) * n / s)};
}

int MatrixPictureLayout::pixel(std::size_t entry) const {
  // The smallest pixel p with floor((p + 1) n / size) > entry.
  const auto s = static_cast<std::size_t>(size);
  return n == 0 ? 0 : static_cast<int>(((entry + 1) * s + n - 1) / n - 1);
}

QImage to_qimage(const Rgb8Image& picture) {
  QImage image(picture.pixels.data(), picture.width, picture.height, picture.width * 3,
               QImage::Format_RGB888);
  return image.copy();  // own the pixels
}

MatrixPanel::MatrixPanel(QWidget* parent) : QGraphicsView(parent) {
  setScene(new QGraphicsScene(this));
  setDragMode(QGraphicsView::ScrollHandDrag);
  setMouseTracking(true);
  setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
  setBackgroundBrush(QColor(90, 90, 96));
  // Single entries must stay sharp squares when zoomed in.
  setRenderHint(QPainter::SmoothPixmapTransform, false);
}

void MatrixPanel::set_picture(const Rgb8Image& picture, const MatrixPictureLayout& layout) {
  scene()->clear();
  highlights_.clear();
  layout_ = layout;
  item_ = scene()->addPixmap(QPixmap::fromImage(to_qimage(picture)));
  scene()->setSceneRect(item_->boundingRect());
}

void MatrixPanel::clear_picture(const QString& message) {
  scene()->clear();
  highlights_.clear();
  item_ = nullptr;
  layout_ = {};
  auto* text = scene()->addSimpleText(message);
  text->setBrush(Qt::white);
  scene()->setSceneRect(text->boundingRect());
}

void MatrixPanel::set_highlights(const std::vector<EntryRect>& rects, bool centre) {
  for (QGraphicsRectItem* r : highlights_) {
    scene()->removeItem(r);
    delete r;
  }
  highlights_.clear();
  if (!item_ || layout_.n == 0) return;
  for (const EntryRect& e : rects) {
    if (e.row_first >= e.row_last || e.col_first >= e.col_last || e.row_last > layout_.n ||
        e.col_last > layout_.n)
      continue;
    const int x0 = layout_.pixel(e.col_first), x1 = layout_.pixel(e.col_last - 1) + 1;
    const int y0 = layout_.pixel(e.row_first), y1 = layout_.pixel(e.row_last - 1) + 1;
    // A cosmetic pen: two screen pixels wide at any zoom, white over black so
    // it shows on every colour of the map.
    QPen pen(Qt::white, 2.0);
    pen.setCosmetic(true);
    auto* item = scene()->addRect(QRectF(layout_.left + x0, layout_.top + y0, x1 - x0, y1 - y0),
                                  pen, Qt::NoBrush);
    item->setZValue(1.0);
    highlights_.push_back(item);
  }
  if (centre && !highlights_.empty()) centerOn(highlights_.front());
}

std::vector<QRectF> MatrixPanel::highlight_rects() const {
  std::vector<QRectF> out;
  for (const QGraphicsRectItem* r : highlights_) out.push_back(r->rect());
  return out;
}

void MatrixPanel::set_zoom(double zoom) {
  setTransform(QTransform::fromScale(zoom, zoom));
  // Shrunk pictures are filtered; enlarged ones keep sharp square entries.
  setRenderHint(QPainter::SmoothPixmapTransform, zoom < 1.0);
  emit zoom_changed(zoom);
}

void MatrixPanel::fit() {
  if (!item_) return;
  fitInView(item_, Qt::KeepAspectRatio);
  setRenderHint(QPainter::SmoothPixmapTransform, zoom() < 1.0);
  emit zoom_changed(zoom());
}

void MatrixPanel::mirror(MatrixPanel* other) {
  connect(this, &MatrixPanel::zoom_changed, other, [other](double z) {
    if (other->zoom() != z) other->set_zoom(z);
  });
  connect(horizontalScrollBar(), &QScrollBar::valueChanged, other->horizontalScrollBar(),
          &QScrollBar::setValue);
  connect(verticalScrollBar(), &QScrollBar::valueChanged, other->verticalScrollBar(),
          &QScrollBar::setValue);
}

QRect MatrixPanel::picture_rect() const {
  if (!item_) return {};
  const QRectF r = item_->sceneBoundingRect();
  const QPoint top_left = mapFromScene(r.topLeft());
  return {top_left, QSize(static_cast<int>(std::lround(r.width() * zoom())),
                          static_cast<int>(std::lround(r.height() * zoom())))};
}

void MatrixPanel::wheelEvent(QWheelEvent* event) {
  // Down to single entries: up to 64 screen pixels per picture pixel.
  const double factor = event->angleDelta().y() > 0 ? 1.25 : 0.8;
  set_zoom(std::clamp(zoom() * factor, 0.02, 64.0));
  event->accept();
}

bool MatrixPanel::entry_at(const QPoint& pos, std::size_t& row, std::size_t& col) const {
  if (!item_ || layout_.size == 0) return false;
  // The scene point under the centre of the mouse's pixel.
  const QPointF p = viewportTransform().inverted().map(QPointF(pos) + QPointF(0.5, 0.5));
  const int x = static_cast<int>(std::floor(p.x())) - layout_.left;
  const int y = static_cast<int>(std::floor(p.y())) - layout_.top;
  if (x < 0 || y < 0 || x >= layout_.size || y >= layout_.size) return false;
  row = layout_.entries(y).first;
  col = layout_.entries(x).first;
  return true;
}

void MatrixPanel::mouseMoveEvent(QMouseEvent* event) {
  QGraphicsView::mouseMoveEvent(event);
  std::size_t row = 0, col = 0;
  if (!entry_at(event->pos(), row, col)) {
    if (item_) emit hovered(0, 0, 0, 0);
    return;
  }
  const QPointF p = viewportTransform().inverted().map(QPointF(event->pos()) + QPointF(0.5, 0.5));
  const auto rows = layout_.entries(static_cast<int>(std::floor(p.y())) - layout_.top);
  const auto cols = layout_.entries(static_cast<int>(std::floor(p.x())) - layout_.left);
  emit hovered(rows.first, rows.second, cols.first, cols.second);
}

void MatrixPanel::mousePressEvent(QMouseEvent* event) {
  std::size_t row = 0, col = 0;
  if (event->button() == Qt::LeftButton && entry_at(event->pos(), row, col)) emit clicked(row, col);
  QGraphicsView::mousePressEvent(event);
}

}  // namespace bounce::views
