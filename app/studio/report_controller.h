#pragma once
// Runs the report sweep (core run_report_sweep at `bounce report --quick`
// settings) as a task on the studio's one background thread
// (views/view_jobs.h) for the report tab, with the reference cached where
// `bounce report` caches it, so the window never freezes. Shared with
// headless screenshots (run_quick_report) so both produce the same rows.
#include <memory>

#include <QObject>
#include <QPointer>
#include <QString>

#include "bounce/progress.h"
#include "bounce/report.h"

namespace bounce::views {
class ViewJobs;
}

namespace bounce::studio {

// The quick sweep of `bounce report --quick` on a scene, reference cached in
// ReferenceCache::default_dir(). Throws bounce::Error, Cancelled.
ReportData run_quick_report(const std::string& scene_path, Progress& progress);

class ReportController : public QObject {
  Q_OBJECT
 public:
  // Sweeps on `jobs`, which may go before this controller (its end stops
  // the sweep, whose outcome is then dropped).
  explicit ReportController(views::ViewJobs& jobs, QObject* parent = nullptr);
  // Stops a queued or running sweep and drops its outcome; does not wait.
  ~ReportController() override;

  // From start() until finished or failed was emitted.
  bool busy() const { return busy_; }
  // Does nothing while busy.
  void start(const QString& scene_path);
  // Stops the sweep at its next poll; failed("Report cancelled") follows.
  void cancel();

 signals:
  void progress(const QString& stage, double fraction);
  void finished(std::shared_ptr<const ReportData> report);
  void failed(const QString& message);

 private:
  QPointer<views::ViewJobs> jobs_;
  bool busy_ = false;
};

}  // namespace bounce::studio
