#include "report_screenshot.h"

#include <memory>

#include <QApplication>
#include <QSaveFile>

#include "bake_job.h"
#include "base/error.h"
#include "report_controller.h"
#include "report_view.h"
#include "vtk_error_capture.h"

namespace bounce::studio {

void take_report_screenshot(const ScreenshotRequest& r) {
  std::shared_ptr<const ReportData> report;
  if (!r.report.isEmpty()) {
    report = std::make_shared<const ReportData>(read_report(r.report.toStdString()));
  } else {
    if (is_bake_folder(r.input.toStdString()))
      throw Error("--view report",
                  "needs a scene to sweep (or --report report.json), got the bake folder " +
                      r.input.toStdString());
    Progress progress;
    report = std::make_shared<const ReportData>(run_quick_report(r.input.toStdString(), progress));
  }
  views::ReportView view;
  view.resize(r.width, r.height);
  view.show();
  view.set_report(report);
  for (int k = 0; k < 5; ++k) QApplication::processEvents();
  const QImage image = view.grab().toImage();
  const std::vector<std::string> vtk = views::VtkErrorCapture::messages();
  if (!vtk.empty()) throw Error("render", "VTK reported: " + vtk.front());
  QSaveFile file(r.screenshot);
  if (!file.open(QIODevice::WriteOnly) || !image.save(&file, "PNG") || !file.commit())
    throw Error(r.screenshot.toStdString(),
                "cannot write the PNG: " + file.errorString().toStdString());
}

}  // namespace bounce::studio
