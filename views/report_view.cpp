#include "report_view.h"

#include <cmath>
#include <limits>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <QEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPushButton>
#include <QVBoxLayout>

namespace bounce::views {

ReportView::ReportView(QWidget* parent)
    : QWidget(parent),
      vtk_widget_(new QVTKOpenGLNativeWidget(this)),
      run_button_(new QPushButton(tr("Run quick sweep"), this)),
      open_button_(new QPushButton(tr("Open report.json..."), this)),
      status_(new QLabel(this)) {
  run_button_->setToolTip(
      tr("Bake the current scene at a few small settings (virtual and voxel patches, 60 and 150 "
         "patches, bounces, codecs) and measure each against the path-traced reference, as "
         "`bounce report --quick` does; takes a minute or two"));
  open_button_->setToolTip(tr("Show a report.json written by `bounce report`"));
  status_->setWordWrap(true);
  status_->setText(
      tr("No report yet: run the quick sweep or open a report.json. Click a point "
         "to load its settings into the bake panel."));
  auto* layout = new QVBoxLayout(this);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(run_button_);
  buttons->addWidget(open_button_);
  buttons->addStretch(1);
  layout->addLayout(buttons);
  layout->addWidget(vtk_widget_, 1);
  layout->addWidget(status_);

  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  vtk_widget_->setRenderWindow(window);
  view_ = vtkSmartPointer<vtkContextView>::New();
  view_->SetRenderWindow(window);
  view_->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtk_widget_->installEventFilter(this);

  connect(run_button_, &QPushButton::clicked, this, &ReportView::run_requested);
  connect(open_button_, &QPushButton::clicked, this, &ReportView::open_requested);
}

ReportView::~ReportView() = default;

QWidget* ReportView::chart_widget() const { return vtk_widget_; }

void ReportView::set_status(const QString& text) { status_->setText(text); }

void ReportView::set_busy(bool busy) {
  run_button_->setEnabled(!busy);
  open_button_->setEnabled(!busy);
}

void ReportView::set_report(std::shared_ptr<const ReportData> report) {
  report_ = std::move(report);
  if (chart_) view_->GetScene()->RemoveItem(chart_);
  chart_ = nullptr;
  points_ = {};
  if (report_) {
    chart_ = make_error_runtime_chart(*report_, &points_);
    view_->GetScene()->AddItem(chart_);
    status_->setText(tr("%1: %2 settings. Click a point to load its settings.")
                         .arg(QString::fromStdString(report_->scene_name))
                         .arg(report_->rows.size()));
  }
  vtk_widget_->renderWindow()->Render();
  vtk_widget_->update();
}

std::optional<QPoint> ReportView::point_position(std::size_t row) const {
  if (!chart_ || !report_ || row >= report_->rows.size()) return std::nullopt;
  const ReportRow& r = report_->rows[row];
  if (!std::isfinite(r.indirect_error)) return std::nullopt;
  // The axes know where they were drawn (scene pixels, origin bottom left)
  // and which data range they show (linear axes here).
  vtkAxis* x_axis = chart_->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* y_axis = chart_->GetAxis(vtkAxis::LEFT);
  const float* x1 = x_axis->GetPoint1();
  const float* x2 = x_axis->GetPoint2();
  const float* y1 = y_axis->GetPoint1();
  const float* y2 = y_axis->GetPoint2();
  const double x_span = x_axis->GetMaximum() - x_axis->GetMinimum();
  const double y_span = y_axis->GetMaximum() - y_axis->GetMinimum();
  if (!(x_span > 0.0) || !(y_span > 0.0)) return std::nullopt;
  const double sx = x1[0] + (r.update_ms() - x_axis->GetMinimum()) / x_span * (x2[0] - x1[0]);
  const double sy = y1[1] + (r.indirect_error - y_axis->GetMinimum()) / y_span * (y2[1] - y1[1]);
  // Scene pixels are device pixels; Qt's are logical, top down.
  const double ratio = vtk_widget_->devicePixelRatioF();
  const double height = vtk_widget_->height() * ratio;
  return QPoint(static_cast<int>(std::lround(sx / ratio)),
                static_cast<int>(std::lround((height - 1.0 - sy) / ratio)));
}

std::optional<std::size_t> ReportView::row_at(QPoint p, double radius) const {
  if (!report_) return std::nullopt;
  std::optional<std::size_t> best;
  double best_d2 = radius * radius;
  for (const std::vector<std::size_t>* rows : {&points_.virtual_rows, &points_.voxel_rows})
    for (std::size_t row : *rows) {
      const std::optional<QPoint> q = point_position(row);
      if (!q) continue;
      const double dx = q->x() - p.x(), dy = q->y() - p.y();
      const double d2 = dx * dx + dy * dy;
      if (d2 <= best_d2) {
        best_d2 = d2;
        best = row;
      }
    }
  return best;
}

void ReportView::select_row(std::size_t row) {
  if (!report_ || row >= report_->rows.size()) return;
  const ReportRow& r = report_->rows[row];
  status_->setText(tr("%1 patches (%2), %3 bounces, codec %4: error %5, update %6 ms, bake %7 s "
                      "-- loaded into the bake settings")
                       .arg(r.patches)
                       .arg(QString::fromStdString(r.mode))
                       .arg(QString::fromStdString(r.bounces))
                       .arg(QString::fromStdString(r.codec))
                       .arg(r.indirect_error, 0, 'f', 4)
                       .arg(r.update_ms(), 0, 'f', 2)
                       .arg(r.bake_seconds, 0, 'f', 2));
  emit row_clicked(static_cast<int>(row));
}

bool ReportView::eventFilter(QObject* watched, QEvent* event) {
  // A click (press and release at about the same place) picks a point; a
  // drag stays the chart's own pan.
  if (watched == vtk_widget_) {
    if (event->type() == QEvent::MouseButtonPress) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton) press_ = e->pos();
    } else if (event->type() == QEvent::MouseButtonRelease) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton && (e->pos() - press_).manhattanLength() <= 3)
        if (const std::optional<std::size_t> row = row_at(e->pos())) select_row(*row);
    }
  }
  return QWidget::eventFilter(watched, event);
}

}  // namespace bounce::views
