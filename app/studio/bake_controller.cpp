#include "bake_controller.h"

#include "view_jobs.h"

namespace bounce::studio {

BakeController::BakeController(views::ViewJobs& jobs, QObject* parent)
    : QObject(parent), jobs_(&jobs) {
  qRegisterMetaType<std::shared_ptr<const BakeJobResult>>("std::shared_ptr<const BakeJobResult>");
  qRegisterMetaType<std::shared_ptr<const views::BakeViewData>>(
      "std::shared_ptr<const views::BakeViewData>");
}

BakeController::~BakeController() {
  if (jobs_) jobs_->forget(this);
}

void BakeController::cancel() {
  if (jobs_) jobs_->cancel(this);
}

void BakeController::start(const QString& scene_path, const BakeSettings& settings,
                           const QString& folder, std::shared_ptr<const BakeJobResult> previous,
                           std::vector<float> patch_density, bool cache) {
  if (busy_ || !jobs_) return;
  busy_ = true;
  const std::string scene = scene_path.toStdString(), out = folder.toStdString();
  // The work touches nothing of this controller: its progress and outcome
  // reach it on the UI thread, and only while it exists.
  // The outcome: the job, or null when the bake was cancelled.
  using Outcome = std::shared_ptr<const BakeJobResult>;
  jobs_->run_task<Outcome>(
      this,
      [this, scene, settings, out, previous, patch_density,
       cache](const views::ViewJobs::Task& task) -> Outcome {
        std::string stage;
        auto stage_start = std::chrono::steady_clock::now();
        Progress progress([&](const std::string& name, double fraction) {
          const auto now = std::chrono::steady_clock::now();
          if (name != stage) {
            stage = name;
            stage_start = now;
          }
          const double elapsed = std::chrono::duration<double>(now - stage_start).count();
          // Remaining time of the stage at its rate so far; unknown at the start.
          const double eta = fraction > 0.02 ? elapsed * (1.0 - fraction) / fraction : -1.0;
          task.on_ui_thread([this, name = QString::fromStdString(name), fraction, eta] {
            emit stage_progress(name, fraction, eta);
          });
          return task.keep_going();
        });
        BakeJobOptions options;
        options.cache = cache;
        options.partial = [this, &task](std::shared_ptr<const views::BakeViewData> data) {
          task.on_ui_thread([this, data = std::move(data)] { emit partial(data); });
        };
        try {
          return std::make_shared<const BakeJobResult>(
              run_bake_job(scene, settings, out, progress, previous, patch_density, options));
        } catch (const Cancelled&) {
          return nullptr;
        }
      },
      [this](Outcome job) {
        busy_ = false;
        if (job)
          emit finished(std::move(job));
        else
          emit cancelled();
      },
      [this](const QString& message) {
        busy_ = false;
        emit failed(message);
      });
}

}  // namespace bounce::studio
