#include "report_controller.h"

#include "bounce/report.h"
#include "bounce/scene.h"
#include "view_jobs.h"

namespace bounce::studio {

ReportData run_quick_report(const std::string& scene_path, Progress& progress) {
  Diagnostics diag;
  const Scene scene = SceneLoader(diag).load(scene_path);
  ReportSweepSettings sweep;
  sweep.fill_defaults(/*quick=*/true);
  const ReferenceCache cache(ReferenceCache::default_dir());
  return run_report_sweep(scene, sweep, &cache, progress, diag);
}

ReportController::ReportController(views::ViewJobs& jobs, QObject* parent)
    : QObject(parent), jobs_(&jobs) {
  qRegisterMetaType<std::shared_ptr<const ReportData>>("std::shared_ptr<const ReportData>");
}

ReportController::~ReportController() {
  if (jobs_) jobs_->forget(this);
}

void ReportController::cancel() {
  if (jobs_) jobs_->cancel(this);
}

void ReportController::start(const QString& scene_path) {
  if (busy_ || !jobs_) return;
  busy_ = true;
  const std::string scene = scene_path.toStdString();
  // The work touches nothing of this controller: its progress and outcome
  // reach it on the UI thread, and only while it exists.
  // The outcome: the report, or null when the sweep was cancelled.
  using Outcome = std::shared_ptr<const ReportData>;
  jobs_->run_task<Outcome>(
      this,
      [this, scene](const views::ViewJobs::Task& task) -> Outcome {
        Progress progress([&](const std::string& stage, double fraction) {
          task.on_ui_thread([this, stage = QString::fromStdString(stage), fraction] {
            emit this->progress(stage, fraction);
          });
          return task.keep_going();
        });
        try {
          return std::make_shared<const ReportData>(run_quick_report(scene, progress));
        } catch (const Cancelled&) {
          return nullptr;
        }
      },
      [this](Outcome report) {
        busy_ = false;
        if (report)
          emit finished(std::move(report));
        else
          emit failed(tr("Report cancelled"));
      },
      [this](const QString& message) {
        busy_ = false;
        emit failed(message);
      });
}

}  // namespace bounce::studio
