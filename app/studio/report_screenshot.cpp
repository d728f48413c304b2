#include "report_screenshot.h"

#include <memory>

#include <QApplication>

#include "bake_job.h"
#include "bounce/error.h"
#include "headless.h"
#include "report_controller.h"
#include "report_view.h"

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
  save_view_png(image, r.screenshot);
}

}  // namespace bounce::studio
