#pragma once
// Runs a bake job (bake_job.h) on a worker thread so the window never
// freezes: reports each stage's progress with an ETA, and cancels through
// the core's progress callback (returning false stops the bake at its next
// poll; core/base/progress.h).
#include <chrono>
#include <memory>
#include <vector>

#include <QObject>
#include <QString>

#include "bake_job.h"
#include "worker_thread.h"

namespace bounce::studio {

class BakeController : public QObject {
  Q_OBJECT
 public:
  explicit BakeController(QObject* parent = nullptr);
  ~BakeController() override;

  bool busy() const { return worker_.busy(); }
  // Starts a bake into `folder` (replaced when the bake succeeds). With
  // `previous` (an earlier job of the same scene), only the stages the
  // settings change affects run (run_bake_job).
  // `patch_density`: the meshes' densities (empty: the scene's own).
  void start(const QString& scene_path, const BakeSettings& settings, const QString& folder,
             std::shared_ptr<const BakeJobResult> previous = {},
             std::vector<float> patch_density = {});
  void cancel() { worker_.cancel(); }

 signals:
  // fraction in [0,1]; eta_seconds < 0 while unknown.
  void stage_progress(const QString& stage, double fraction, double eta_seconds);
  void finished(std::shared_ptr<const BakeJobResult> job);
  void failed(const QString& message);
  void cancelled();

 private:
  WorkerThread worker_{this};
};

}  // namespace bounce::studio
