#pragma once
// The sweep behind `bounce report` and the studio's report view: bakes the
// scene over patch modes, patch counts, bounce counts and codecs and measures
// each setting against the path-traced reference (docs/reference.md).
//
// It runs the same core functions as `bounce bake` and `bounce solve`, and
// reuses what the settings allow: one Baker run (voxels, samples, patches,
// form factors) per patch setting, then compute_transport per bounce count
// on those form factors and store_transport per codec on that matrix. A
// row's bake time is what a standalone bake of that row would have spent:
// the shared stages plus its own transport and storage stages.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.h"
#include "base/progress.h"
#include "report/report_data.h"
#include "scene/scene.h"

namespace bounce {

class ReferenceCache;

struct ReportCodec {
  std::string name;                     // dense, paper, ours
  std::optional<double> kept_fraction;  // paper, ours: a fixed kept share
  std::string label() const;
  // "ours", "paper", "dense", optionally ":FRACTION"; throws Error("codecs", ...).
  static ReportCodec parse(const std::string& spec);
};

struct ReportSweepSettings {
  std::vector<std::string> modes;    // virtual, voxel
  std::vector<int> patches;          // target patch counts
  std::vector<std::string> bounces;  // 1.., auto, inf
  std::vector<std::string> codecs;   // ReportCodec::parse specs; swept at auto bounces
  int reference_samples = 0;
  int width = 0, height = 0;  // camera pictures
  int eval_grid = 0;          // evaluation mesh: the scene refined on this many cells
  std::uint64_t seed = 1;     // sampling seed of every bake (BakeSettings::seed)
  std::string transfer;       // final-gather (default) or nearest
  // Bake every row with light probes and measure them (report/report_probes.h).
  bool light_probes = true;

  // The defaults of `bounce report`, or its --quick ones (seconds, for tests
  // and the studio): fills what is empty or zero.
  void fill_defaults(bool quick);
  // Throws Error naming the option.
  void validate() const;
};

// Runs the sweep. `cache` may be null (always render the reference). `log`
// gets one line per patch setting. Throws Cancelled when progress is stopped.
ReportData run_report_sweep(const Scene& scene, const ReportSweepSettings& settings,
                            const ReferenceCache* cache, Progress& progress, Diagnostics& diag,
                            const std::function<void(const std::string&)>& log = {});

}  // namespace bounce
