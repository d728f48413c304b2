#pragma once
// The studio's report tab: the error-against-run-time chart
// of a report (report/report_data.h; the same VTK chart as `bounce report`'s
// error_vs_runtime.png). Clicking a point selects its row; the main window
// loads that row's bake settings into the settings panel. The sweep itself is
// run by the application (core run_report_sweep), not here.
#include <memory>
#include <optional>

#include <vtkSmartPointer.h>
#include <QPoint>
#include <QWidget>

#include "bounce/report.h"
#include "report_charts.h"

class QLabel;
class QPushButton;
class QVTKOpenGLNativeWidget;
class vtkChartXY;
class vtkContextView;

namespace bounce::views {

class ReportView : public QWidget {
  Q_OBJECT
 public:
  explicit ReportView(QWidget* parent = nullptr);
  ~ReportView() override;

  void set_report(std::shared_ptr<const ReportData> report);
  const std::shared_ptr<const ReportData>& report() const { return report_; }
  // A line under the chart (what is running, what went wrong).
  void set_status(const QString& text);
  void set_busy(bool busy);

  // Where row `row`'s point is drawn, in the chart widget's coordinates
  // (after a render); nothing for rows not drawn (non-finite error).
  std::optional<QPoint> point_position(std::size_t row) const;
  // The drawn row nearest to `p` (chart widget coordinates) within `radius` pixels.
  std::optional<std::size_t> row_at(QPoint p, double radius = 10.0) const;
  QWidget* chart_widget() const;
  // Selects a row as a click on its point does (emits row_clicked).
  void select_row(std::size_t row);

 signals:
  void row_clicked(int row);
  void run_requested();
  void open_requested();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  QVTKOpenGLNativeWidget* vtk_widget_;
  QPushButton* run_button_;
  QPushButton* open_button_;
  QLabel* status_;
  vtkSmartPointer<vtkContextView> view_;
  vtkSmartPointer<vtkChartXY> chart_;
  ReportChartPoints points_;
  std::shared_ptr<const ReportData> report_;
  QPoint press_;
};

}  // namespace bounce::views
