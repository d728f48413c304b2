#include "base/progress.h"

#include <algorithm>

#include "base/error.h"

namespace bounce {

void Progress::begin_stage(const std::string& name, std::size_t total) {
  check();
  {
    std::lock_guard lock(report_mutex_);
    stage_ = name;
    total_ = std::max<std::size_t>(total, 1);
    done_.store(0);
    last_reported_ = -1.0;
    last_time_ = {};
  }
  report(0.0);
}

void Progress::advance(std::size_t units) {
  const std::size_t done = done_.fetch_add(units) + units;
  // No check() here: advance() runs inside OpenMP loops, which an exception
  // must not leave. Loops poll should_stop() and the caller check()s after.
  report(std::min(1.0, static_cast<double>(done) / static_cast<double>(total_)));
}

void Progress::end_stage() { report(1.0); }

void Progress::check() const {
  if (should_stop()) throw Cancelled();
}

void Progress::report(double fraction) {
  std::lock_guard lock(report_mutex_);
  // Monotone: concurrent advance() calls may arrive out of order.
  if (fraction <= last_reported_) return;
  const auto now = std::chrono::steady_clock::now();
  // Throttle to ~20 reports a second or 1% steps, and always report 0 and 1:
  // the callback is also where a GUI says "stop", so it must hear often.
  if (fraction > 0.0 && fraction < 1.0 && fraction - last_reported_ < 0.01 &&
      now - last_time_ < std::chrono::milliseconds(50))
    return;
  last_reported_ = fraction;
  last_time_ = now;
  if (callback_ && !callback_(stage_, fraction)) request_stop();
}

}  // namespace bounce
