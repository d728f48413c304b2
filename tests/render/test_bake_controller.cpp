// The studio's bake controller runs its bake on the runner the window
// shares with the views (views/view_jobs.h), not on a thread of its own: a
// bake waits for the job before it, and a view job queued after it waits for
// the bake, all on the one thread; its progress and outcome come back on
// the UI thread, and cancel() stops it, queued or running.
#include <atomic>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <QElapsedTimer>
#include <QThread>

#include "bake_controller.h"
#include "render_support.h"
#include "settings_panel.h"
#include "view_jobs.h"

namespace bounce::render_test {

namespace fs = std::filesystem;
using views::ViewJobs;

namespace {

const fs::path kScene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "cornell-box";

// The studio's own settings, on a coarse grid, so that the bake is short.
BakeSettings coarse_settings() {
  studio::SettingsPanel panel;
  panel.set_grid(studio::SettingsPanel::GridChoice::VoxelSize, 2);
  return panel.settings();
}

// What the controller said, in order, on the UI thread.
struct Recorder {
  std::vector<std::string> events;
  int progress = 0;
  bool done = false;
  explicit Recorder(studio::BakeController& controller) {
    QObject::connect(&controller, &studio::BakeController::stage_progress,
                     [this](const QString&, double, double) {
                       EXPECT_EQ(QThread::currentThread(), qApp->thread());
                       ++progress;
                     });
    QObject::connect(&controller, &studio::BakeController::finished,
                     [this](std::shared_ptr<const studio::BakeJobResult> job) {
                       EXPECT_NE(job, nullptr);
                       events.push_back("finished");
                       done = true;
                     });
    QObject::connect(&controller, &studio::BakeController::cancelled, [this] {
      events.push_back("cancelled");
      done = true;
    });
    QObject::connect(&controller, &studio::BakeController::failed, [this](const QString& m) {
      events.push_back("failed: " + m.toStdString());
      done = true;
    });
  }
};

// Processes events for `ms` milliseconds or until `until()`.
template <class Until>
void process_events(int ms, Until until) {
  QElapsedTimer timer;
  timer.start();
  while (!until() && timer.elapsed() < ms) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    QThread::msleep(1);
  }
}

}  // namespace

TEST(BakeController, BakesOnTheSharedRunnerInOrderWithTheViewJobs) {
  const fs::path dir = work_dir("bake-controller-shared");
  ViewJobs jobs;
  studio::BakeController controller(jobs);
  Recorder recorder(controller);
  QObject view;

  // A view job holds the runner; the bake queued behind it does not start.
  std::promise<void> open;
  std::shared_future<void> opened = open.get_future().share();
  std::vector<std::thread::id> threads;  // written on the runner only
  jobs.run<int>(
      &view, 0,
      [opened, &threads](const ViewJobs::KeepGoing&) {
        threads.push_back(std::this_thread::get_id());
        opened.wait();
        return 0;
      },
      [&recorder](int) { recorder.events.push_back("view before"); });
  controller.start(QString::fromStdString(kScene.string()), coarse_settings(),
                   QString::fromStdString((dir / "bake").string()));
  EXPECT_TRUE(controller.busy());
  EXPECT_TRUE(jobs.has_jobs(&controller));
  // A view job queued after the bake runs after it.
  std::atomic<bool> baked_before_view{false};
  jobs.run<int>(
      &view, 1,
      [&threads, &baked_before_view, &dir](const ViewJobs::KeepGoing&) {
        threads.push_back(std::this_thread::get_id());
        baked_before_view = fs::exists(dir / "bake" / "manifest.json");
        return 0;
      },
      [&recorder](int) { recorder.events.push_back("view after"); });
  process_events(300, [] { return false; });
  EXPECT_EQ(recorder.progress, 0) << "the bake ran next to the runner's job";

  open.set_value();
  jobs.wait_idle();
  EXPECT_GT(recorder.progress, 0);
  EXPECT_EQ(recorder.events, (std::vector<std::string>{"view before", "finished", "view after"}));
  EXPECT_TRUE(baked_before_view);
  ASSERT_EQ(threads.size(), 2u);
  EXPECT_EQ(threads[0], threads[1]);
  EXPECT_FALSE(controller.busy());
  EXPECT_FALSE(jobs.has_jobs(&controller));
}

TEST(BakeController, CancelStopsAQueuedBake) {
  const fs::path dir = work_dir("bake-controller-cancel-queued");
  ViewJobs jobs;
  studio::BakeController controller(jobs);
  Recorder recorder(controller);
  QObject view;
  std::promise<void> open;
  std::shared_future<void> opened = open.get_future().share();
  jobs.run<int>(
      &view, 0,
      [opened](const ViewJobs::KeepGoing&) {
        opened.wait();
        return 0;
      },
      [](int) {});
  controller.start(QString::fromStdString(kScene.string()), coarse_settings(),
                   QString::fromStdString((dir / "bake").string()));
  controller.cancel();
  open.set_value();
  jobs.wait_idle();
  EXPECT_EQ(recorder.events, (std::vector<std::string>{"cancelled"}));
  EXPECT_FALSE(controller.busy());
  EXPECT_FALSE(fs::exists(dir / "bake" / "manifest.json"));
}

TEST(BakeController, CancelStopsARunningBake) {
  const fs::path dir = work_dir("bake-controller-cancel-running");
  ViewJobs jobs;
  studio::BakeController controller(jobs);
  Recorder recorder(controller);
  // Cancelled at its first progress, which the runner already shows while
  // the bake goes on: the bake stops at one of its next polls.
  QObject::connect(&controller, &studio::BakeController::stage_progress, &controller,
                   [&controller] { controller.cancel(); });
  studio::SettingsPanel panel;
  controller.start(QString::fromStdString(kScene.string()), panel.settings(),
                   QString::fromStdString((dir / "bake").string()));
  process_events(120000, [&recorder] { return recorder.done; });
  jobs.wait_idle();
  EXPECT_EQ(recorder.events, (std::vector<std::string>{"cancelled"}));
  EXPECT_FALSE(controller.busy());
  EXPECT_FALSE(fs::exists(dir / "bake" / "manifest.json"));
}

}  // namespace bounce::render_test
