#pragma once
// Runs a bake job (bake_job.h) as a task on the studio's one background
// thread (views/view_jobs.h) so the window never freezes: reports each
// stage's progress with an ETA, and cancels through the core's progress
// callback (returning false stops the bake at its next poll;
// core/base/progress.h).
#include <chrono>
#include <memory>
#include <vector>

#include <QObject>
#include <QPointer>
#include <QString>

#include "bake_job.h"

namespace bounce::views {
class ViewJobs;
}

namespace bounce::studio {

class BakeController : public QObject {
  Q_OBJECT
 public:
  // Bakes on `jobs`, which may go before this controller (its end stops the
  // bake, whose outcome is then dropped).
  explicit BakeController(views::ViewJobs& jobs, QObject* parent = nullptr);
  // Stops a queued or running bake and drops its outcome; does not wait.
  ~BakeController() override;

  // From start() until one of finished, failed or cancelled was emitted.
  bool busy() const { return busy_; }
  // Starts a bake into `folder` (replaced when the bake succeeds); does
  // nothing while busy. With `previous` (an earlier job of the same scene),
  // only the stages the settings change affects run (run_bake_job).
  // `patch_density`: the meshes' densities (empty: the scene's own).
  // With `cache`, `folder` is the bake cache (BakeJobOptions::cache): a bake
  // of the same contents and settings there is shown instead of baking.
  void start(const QString& scene_path, const BakeSettings& settings, const QString& folder,
             std::shared_ptr<const BakeJobResult> previous = {},
             std::vector<float> patch_density = {}, bool cache = false);
  // Stops the bake at its next poll (or before it starts, if it waits for
  // the jobs queued before it); cancelled() follows.
  void cancel();

 signals:
  // fraction in [0,1]; eta_seconds < 0 while unknown.
  void stage_progress(const QString& stage, double fraction, double eta_seconds);
  // What the running bake has made so far (BakeJobOptions::partial).
  void partial(std::shared_ptr<const views::BakeViewData> data);
  void finished(std::shared_ptr<const BakeJobResult> job);
  void failed(const QString& message);
  void cancelled();

 private:
  QPointer<views::ViewJobs> jobs_;
  bool busy_ = false;
};

}  // namespace bounce::studio
