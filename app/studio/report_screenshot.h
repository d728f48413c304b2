#pragma once
// `bounce-studio SCENE --screenshot out.png --view report [--report report.json]`:
// the report tab's chart in a PNG. With --report it shows that file (what
// `bounce report` wrote); without, it runs the quick sweep on SCENE first
// (the tab's "Run quick sweep", `bounce report --quick`: a minute or two).
#include "headless.h"

namespace bounce::studio {

// Throws bounce::Error for bad requests, unreadable reports, failed sweeps or renders.
void take_report_screenshot(const ScreenshotRequest& request);

}  // namespace bounce::studio
