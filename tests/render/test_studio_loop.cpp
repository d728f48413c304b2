// The artist's loop through the studio's bake controller with the bake cache
// (BakeJobOptions::cache): the voxel grid reaches the views before the bake
// ends (the first picture, saved as studio-loop-first-picture.png), the
// patches once their stage ends; a second bake of the same scene and
// settings opens the cached folder without baking; a corrupt cached folder
// is baked again and the job says why.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include <QElapsedTimer>
#include <QThread>

#include "bake_controller.h"
#include "render_support.h"
#include "settings_panel.h"
#include "view_jobs.h"
#include "voxel_view.h"

namespace bounce::render_test {

namespace fs = std::filesystem;

namespace {

const fs::path kScene = fs::path(BOUNCE_RESOURCE_DIR) / "scenes" / "cornell-box";

BakeSettings small_settings() {
  studio::SettingsPanel panel;
  panel.set_grid(studio::SettingsPanel::GridChoice::VoxelSize, 4);
  return panel.settings();
}

// One bake through the controller, with what it showed on the way.
struct LoopRun {
  std::shared_ptr<const studio::BakeJobResult> job;
  std::string failure;
  qint64 first_partial_ms = -1;  // since start()
  qint64 finished_ms = -1;
  bool voxels_before_finish = false;  // the first partial came before the bake ended
  std::size_t voxels_shown = 0, voxel_pixels = 0, most_patches = 0;
};

LoopRun bake_through_controller(const fs::path& cache, const fs::path& screenshot = {}) {
  views::ViewJobs jobs;
  studio::BakeController controller(jobs);
  views::VoxelView view;
  view.resize(480, 360);
  view.show();
  settle();
  LoopRun run;
  QElapsedTimer timer;
  QObject::connect(&controller, &studio::BakeController::partial,
                   [&](std::shared_ptr<const views::BakeViewData> data) {
                     run.most_patches = std::max(run.most_patches, data->patch_count());
                     if (run.first_partial_ms >= 0) return;
                     run.first_partial_ms = timer.elapsed();
                     run.voxels_before_finish = !run.job;
                     view.set_data(data);
                     const QImage image = view.render_image();
                     run.voxels_shown = view.shown_voxels();
                     run.voxel_pixels = count_colour(image, {views::VoxelView::kVoxelColour[0],
                                                             views::VoxelView::kVoxelColour[1],
                                                             views::VoxelView::kVoxelColour[2]});
                     if (!screenshot.empty())
                       image.save(QString::fromStdString(screenshot.string()));
                   });
  QObject::connect(&controller, &studio::BakeController::finished,
                   [&](std::shared_ptr<const studio::BakeJobResult> job) {
                     run.finished_ms = timer.elapsed();
                     run.job = std::move(job);
                   });
  QObject::connect(&controller, &studio::BakeController::failed,
                   [&](const QString& m) { run.failure = m.toStdString(); });
  timer.start();
  controller.start(QString::fromStdString(kScene.string()), small_settings(),
                   QString::fromStdString(cache.string()), {}, {}, true);
  while (!run.job && run.failure.empty() && timer.elapsed() < 180000) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    QThread::msleep(1);
  }
  return run;
}

}  // namespace

TEST(StudioLoop, VoxelsFirstThenPatchesThenTheCachedBakeOpensAtOnce) {
  const fs::path dir = work_dir("studio-loop");
  const fs::path cache = dir / "cache";
  const LoopRun first = bake_through_controller(cache, dir / "studio-loop-first-picture.png");
  ASSERT_TRUE(first.job) << first.failure;
  EXPECT_FALSE(first.job->reused);
  EXPECT_TRUE(first.voxels_before_finish) << "the voxel grid came with the finished bake";
  EXPECT_GT(first.voxels_shown, 0u);
  EXPECT_GT(first.voxel_pixels, 0u) << "no voxel-colour pixel in the first picture";
  EXPECT_GT(first.most_patches, 0u) << "the patches were not shown before the bake ended";
  EXPECT_LT(first.first_partial_ms, 5000) << "the first picture took " << first.first_partial_ms;
  std::printf("[ measured ] first picture (voxel grid) %lld ms, bake finished %lld ms\n",
              static_cast<long long>(first.first_partial_ms),
              static_cast<long long>(first.finished_ms));
  // The bake is in the cache under its content key.
  const std::string key = first.job->folder.filename().string();
  EXPECT_EQ(first.job->folder.parent_path(), cache);
  EXPECT_EQ(stored_bake_key(first.job->folder), key);

  const LoopRun second = bake_through_controller(cache);
  ASSERT_TRUE(second.job) << second.failure;
  EXPECT_TRUE(second.job->reused);
  EXPECT_EQ(second.first_partial_ms, -1) << "a cached bake has nothing partial to show";
  EXPECT_EQ(second.job->data->patch_count(), first.job->data->patch_count());
  std::printf("[ measured ] cached bake opened in %lld ms\n",
              static_cast<long long>(second.finished_ms));
  EXPECT_LT(second.finished_ms, 5000);

  // A half-copied cache entry: baked again, and the job says which file.
  fs::resize_file(first.job->folder / bake_file::kPatches, 64);
  const LoopRun third = bake_through_controller(cache);
  ASSERT_TRUE(third.job) << third.failure;
  EXPECT_FALSE(third.job->reused);
  EXPECT_NE(third.job->cache_note.find("patches.npy"), std::string::npos) << third.job->cache_note;
  EXPECT_EQ(stored_bake_key(third.job->folder), key);
}

}  // namespace bounce::render_test
