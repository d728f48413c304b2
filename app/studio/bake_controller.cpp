#include "bake_controller.h"

namespace bounce::studio {

BakeController::BakeController(QObject* parent) : QObject(parent) {
  qRegisterMetaType<std::shared_ptr<const BakeJobResult>>("std::shared_ptr<const BakeJobResult>");
}

BakeController::~BakeController() { worker_.cancel_and_wait(); }

void BakeController::start(const QString& scene_path, const BakeSettings& settings,
                           const QString& folder, std::shared_ptr<const BakeJobResult> previous,
                           std::vector<float> patch_density) {
  const std::string scene = scene_path.toStdString(), out = folder.toStdString();
  worker_.start([this, scene, settings, out, previous, patch_density] {
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
      emit stage_progress(QString::fromStdString(name), fraction, eta);
      return worker_.keep_going();
    });
    try {
      auto job = std::make_shared<const BakeJobResult>(
          run_bake_job(scene, settings, out, progress, previous, patch_density));
      emit finished(job);
    } catch (const Cancelled&) {
      emit cancelled();
    } catch (const std::exception& e) {
      emit failed(QString::fromStdString(e.what()));
    }
  });
}

}  // namespace bounce::studio
