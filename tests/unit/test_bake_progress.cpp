// How a bake reports its progress (base/progress.h, core/bake): every step
// of the pipeline begins its own progress stage, named, and a front end
// shows one bar per stage. On a small bake every stage's fractions stay in
// [0, 1], never go back, and end at exactly 1; a stop asked for inside any
// stage ends the bake in that stage, with Cancelled and no result to write
// (also the last stage, whose loops have no poll left after its report).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "base/error.h"
#include "scene/scene_loader.h"

namespace bounce {
namespace {

const Scene& cornell_box() {
  static const Scene scene = [] {
    Diagnostics d;
    return SceneLoader(d).load(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box");
  }();
  return scene;
}

BakeSettings small_settings() {
  BakeSettings s;
  s.voxel_resolution = 3;
  s.codec = CodecChoice::LightWeighted;
  s.transport.bounces = 3;
  s.transport.backend = TransportSettings::Backend::OpenBLAS;
  s.pictures = false;
  return s;
}

struct Report {
  std::string stage;
  double fraction;
};

// The stages in the order they began, each with its fractions.
struct StageRun {
  std::string name;
  std::vector<double> fractions;
};

std::vector<StageRun> stage_runs(const std::vector<Report>& reports) {
  std::vector<StageRun> runs;
  for (const Report& r : reports) {
    // begin_stage reports 0 once, and nothing else does.
    if (r.fraction == 0.0 || runs.empty()) runs.push_back({r.stage, {}});
    runs.back().fractions.push_back(r.fraction);
  }
  return runs;
}

TEST(BakeProgress, EveryStageIsMonotoneAndReachesOne) {
  std::vector<Report> reports;
  Progress progress([&](const std::string& stage, double f) {
    reports.push_back({stage, f});
    return true;
  });
  Diagnostics d;
  const BakeResult result = Baker(cornell_box(), small_settings(), d).run(progress);
  ASSERT_TRUE(result.storage.compressed);
  const std::vector<StageRun> runs = stage_runs(reports);
  // Voxelize, sample, patches, form factors, transport, compression at least.
  EXPECT_GE(runs.size(), 6u);
  for (const StageRun& run : runs) {
    SCOPED_TRACE(run.name);
    ASSERT_FALSE(run.fractions.empty());
    EXPECT_EQ(run.fractions.front(), 0.0);
    EXPECT_EQ(run.fractions.back(), 1.0);
    for (std::size_t k = 1; k < run.fractions.size(); ++k) {
      EXPECT_GE(run.fractions[k], run.fractions[k - 1]);
      EXPECT_LE(run.fractions[k], 1.0);
    }
  }
}

TEST(BakeProgress, AStopInsideAnyStageEndsTheBakeThere) {
  // The stages of a whole bake, in order.
  std::vector<Report> reports;
  Progress all([&](const std::string& stage, double f) {
    reports.push_back({stage, f});
    return true;
  });
  Diagnostics d;
  Baker(cornell_box(), small_settings(), d).run(all);
  const std::vector<StageRun> runs = stage_runs(reports);
  ASSERT_FALSE(runs.empty());
  std::set<std::string> tried;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    // Each stage once, where it first begins (a bake reports some, such as
    // the compression's, many times over), and the last one: after its
    // report of 0 no loop of the bake polls any more.
    if (!tried.insert(runs[k].name).second && k + 1 != runs.size()) continue;
    SCOPED_TRACE(runs[k].name);
    // Stop at the first report of stage k (its 0): it has begun, and no
    // stage after it may.
    std::vector<std::string> begun;
    std::size_t seen = 0;
    Progress progress([&](const std::string& stage, double f) {
      if (f == 0.0) begun.push_back(stage);
      ++seen;
      return begun.size() <= k;
    });
    Diagnostics dk;
    bool cancelled = false;
    try {
      Baker(cornell_box(), small_settings(), dk).run(progress);
    } catch (const Cancelled&) {
      cancelled = true;
    }
    EXPECT_TRUE(cancelled) << "the bake ran on past a stop in stage " << k;
    ASSERT_FALSE(begun.empty());
    EXPECT_EQ(begun.size(), k + 1) << "stages begun after the stop: last " << begun.back();
    EXPECT_EQ(begun.back(), runs[k].name);
    EXPECT_GT(seen, 0u);
  }
}

}  // namespace
}  // namespace bounce
