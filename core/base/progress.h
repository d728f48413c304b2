#pragma once
// Progress with cancellation, shared by the CLI (a bar on stderr) and the GUI
// (a progress bar per stage). Modelled on Open Image Denoise's callback that
// returns false to cancel and Mitsuba's should_stop() polled in long loops.
//
// Contract (tested): within a stage the reported fraction stays in [0,1],
// never goes back, and ends at exactly 1 when the stage completes.
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>

namespace bounce {

class Progress {
 public:
  // Receives (stage name, fraction in [0,1]); returns false to ask for a stop.
  using Callback = std::function<bool(const std::string& stage, double fraction)>;

  Progress() = default;
  explicit Progress(Callback callback) : callback_(std::move(callback)) {}

  // Starts a stage of `total` work units (>= 1).
  void begin_stage(const std::string& name, std::size_t total);
  // Adds finished work units; thread-safe, never throws (it is called inside
  // parallel loops): poll should_stop() in the loop and check() after it.
  void advance(std::size_t units = 1);
  // Marks the stage complete (reports 1.0).
  void end_stage();

  // Asks every long loop to stop at its next poll (e.g. from a signal handler:
  // only an atomic store, async-signal-safe).
  void request_stop() noexcept { stop_.store(true, std::memory_order_relaxed); }
  bool should_stop() const noexcept { return stop_.load(std::memory_order_relaxed); }
  // Throws Cancelled if a stop was requested.
  void check() const;

  const std::string& stage() const { return stage_; }

 private:
  void report(double fraction);
  Callback callback_;
  std::atomic<bool> stop_{false};
  std::atomic<std::size_t> done_{0};
  std::size_t total_ = 1;
  std::string stage_;
  std::mutex report_mutex_;
  double last_reported_ = -1.0;
  std::chrono::steady_clock::time_point last_time_{};
};

}  // namespace bounce
