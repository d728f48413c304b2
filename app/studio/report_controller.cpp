#include "report_controller.h"

#include "bounce/report.h"
#include "bounce/scene.h"

namespace bounce::studio {

ReportData run_quick_report(const std::string& scene_path, Progress& progress) {
  Diagnostics diag;
  const Scene scene = SceneLoader(diag).load(scene_path);
  ReportSweepSettings sweep;
  sweep.fill_defaults(/*quick=*/true);
  const ReferenceCache cache(ReferenceCache::default_dir());
  return run_report_sweep(scene, sweep, &cache, progress, diag);
}

ReportController::ReportController(QObject* parent) : QObject(parent) {
  qRegisterMetaType<std::shared_ptr<const ReportData>>("std::shared_ptr<const ReportData>");
}

ReportController::~ReportController() { worker_.cancel_and_wait(); }

void ReportController::start(const QString& scene_path) {
  const std::string scene = scene_path.toStdString();
  worker_.start([this, scene] {
    Progress progress([this](const std::string& stage, double fraction) {
      emit this->progress(QString::fromStdString(stage), fraction);
      return worker_.keep_going();
    });
    try {
      emit finished(std::make_shared<const ReportData>(run_quick_report(scene, progress)));
    } catch (const Cancelled&) {
      emit failed(tr("Report cancelled"));
    } catch (const std::exception& e) {
      emit failed(QString::fromStdString(e.what()));
    }
  });
}

}  // namespace bounce::studio
