#pragma once
// Runs the report sweep (core run_report_sweep at `bounce report --quick`
// settings) on a worker thread for the report tab, with the reference cached
// where `bounce report` caches it, so the window never freezes. Shared with
// headless screenshots (run_quick_report) so both produce the same rows.
#include <memory>

#include <QObject>
#include <QString>

#include "bounce/progress.h"
#include "bounce/report.h"
#include "worker_thread.h"

namespace bounce::studio {

// The quick sweep of `bounce report --quick` on a scene, reference cached in
// ReferenceCache::default_dir(). Throws bounce::Error, Cancelled.
ReportData run_quick_report(const std::string& scene_path, Progress& progress);

class ReportController : public QObject {
  Q_OBJECT
 public:
  explicit ReportController(QObject* parent = nullptr);
  ~ReportController() override;

  bool busy() const { return worker_.busy(); }
  void start(const QString& scene_path);
  void cancel() { worker_.cancel(); }

 signals:
  void progress(const QString& stage, double fraction);
  void finished(std::shared_ptr<const ReportData> report);
  void failed(const QString& message);

 private:
  WorkerThread worker_{this};
};

}  // namespace bounce::studio
