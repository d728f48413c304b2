#pragma once
// The command-line options of `bounce-studio --screenshot` (headless.h),
// each declared once: added to the parser, then read and checked into a
// ScreenshotRequest.
#include <QCommandLineOption>
#include <QCommandLineParser>
#include <QStringList>

#include "headless.h"

namespace bounce::studio {

class ScreenshotOptions {
 public:
  void add_to(QCommandLineParser& parser) const;
  // Whether the command line asks for a screenshot at all.
  bool requested(const QCommandLineParser& parser) const { return parser.isSet(screenshot_); }
  // Throws bounce::Error naming the option at fault.
  ScreenshotRequest read(const QCommandLineParser& parser, const QStringList& inputs) const;

 private:
  void read_size(const QCommandLineParser& parser, ScreenshotRequest& r) const;
  void read_preview(const QCommandLineParser& parser, ScreenshotRequest& r) const;

  QCommandLineOption screenshot_{"screenshot", "Render one view to this PNG and exit.", "out.png"};
  QCommandLineOption view_{"view",
                           "View for --screenshot: voxels, patches, matrix, error, preview or "
                           "report.",
                           "view", "voxels"};
  QCommandLineOption size_{"size", "Picture size for --screenshot, WxH.", "WxH", "1024x768"};
  QCommandLineOption voxel_{"voxel", "Bake with this many voxels along the longest side.", "N"};
  QCommandLineOption patches_total_{"patches-total", "Bake for about this many patches.", "N"};
  QCommandLineOption codec_{"codec", "Matrix storage: auto, dense, paper or ours.", "codec"};
  QCommandLineOption size_limit_{
      "size-limit",
      "Largest compressed matrix the error budget's search may give, as a share of dense.", "F"};
  QCommandLineOption bake_out_{"bake-out", "Keep the bake folder of --screenshot here.", "dir"};
  QCommandLineOption pick_{"pick-patch", "Patches view: pick this patch, as a click would.",
                           "index"};
  QCommandLineOption light_{"light", "Preview view: move the scene's light to x,y,z first.",
                            "x,y,z"};
  QCommandLineOption report_{
      "report", "Report view: show this report.json (default: run the quick sweep on the scene).",
      "report.json"};
  QCommandLineOption passes_{
      "passes", "Preview view: the passes to show, any of direct,indirect,ao (default: all).",
      "list"};
  QCommandLineOption probes_{"probes",
                             "Preview view: draw the bake's light probes, each lit by its SH."};
  QCommandLineOption sphere_{
      "sphere", "Preview view: draw the probe-lit sphere at x,y,z (a bake with light probes).",
      "x,y,z"};
  QCommandLineOption object_{"object",
                             "Preview view: draw this mesh as the probe-lit object (at --sphere, "
                             "else where the sphere starts).",
                             "mesh"};
  QCommandLineOption compare_codec_{
      "compare-codec", "Error view: re-compress the bake with paper or ours and show that.",
      "codec"};
};

}  // namespace bounce::studio
