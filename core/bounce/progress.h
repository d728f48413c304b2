#pragma once
// Public: progress and cancelling of long library calls.
//
//   bounce::Progress progress([](const std::string& stage, double fraction) {
//     show(stage, fraction);
//     return true;  // false asks the call to stop
//   });
//
// A long call (a bake, a sweep, a reference) begins named stages and reports
// each one's fraction done; request_stop() from any thread, or the callback
// returning false, makes it throw bounce::Cancelled at its next check.
#include "base/error.h"
#include "base/progress.h"
