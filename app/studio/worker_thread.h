#pragma once
// One background job at a time for a studio controller (bake, report): runs a
// function on its own QThread so the window never freezes, and holds the
// cancel flag that the job's Progress callback polls (core/base/progress.h:
// returning false stops the core at its next poll).
//
// The controller's destructor must call cancel_and_wait() itself: the job
// emits the controller's signals, so it has to end before the controller is
// torn down, which is before this member's own destructor would run.
#include <atomic>
#include <functional>

class QObject;
class QThread;

namespace bounce::studio {

class WorkerThread {
 public:
  // `owner` receives the thread's clean-up on its own thread.
  explicit WorkerThread(QObject* owner) : owner_(owner) {}
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;

  bool busy() const { return thread_ != nullptr; }
  // Runs `job` on a new thread with the cancel flag cleared; does nothing and
  // returns false while a job is running.
  bool start(std::function<void()> job);
  void cancel() { cancel_.store(true); }
  // For the job's Progress callback: true until cancel().
  bool keep_going() const { return !cancel_.load(); }
  // Cancels a running job and blocks until it has ended.
  void cancel_and_wait();

 private:
  QObject* owner_;
  QThread* thread_ = nullptr;
  std::atomic<bool> cancel_{false};
};

}  // namespace bounce::studio
