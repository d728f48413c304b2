#pragma once
// The one thread the studio's background work runs on: the views' long
// computations (a compressed matrix decoded, re-compressed, measured; the
// preview's light solved) and the studio's tasks (a bake, a report sweep).
// The core does the work there, and the view or controller is given the
// result on its own (UI) thread. The studio owns one runner and passes it
// to every view and controller, so no two computations run next to each
// other and the window stays responsive.
//
// Jobs run one at a time, in the order they were queued. A job belongs to a
// receiver (a view) and a key (what it computes for that view): a newer job
// of the same receiver and key drops the older one if it has not started
// (of a light dragged across the preview only the latest position is
// solved), and results are shown in the order they were queued. forget()
// drops all of a receiver's jobs: the queued ones, and the running one's
// result, which is asked to stop through keep_going(). The work must not
// touch its view: it gets what it needs by value or shared pointer, so a
// view may go away while its job runs (the result is then dropped).
//
// A task (run_task) is a job that is never replaced: each one queued runs.
// It may hand progress to the UI thread while it works, and cancel() asks it
// to stop while still delivering its result (a task reports that it was
// cancelled). Tasks and view jobs share the one queue, in order: a view job
// queued while a bake or sweep runs waits for it to end. That wait is
// bounded (the task ends or is cancelled, and later tasks queue behind the
// view job), and during a bake it mostly costs nothing, since the bake's
// result replaces the data the views show and with it their queued jobs.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>

#include <QObject>
#include <QPointer>
#include <QString>

namespace bounce::views {

class ViewJobs : public QObject {
  Q_OBJECT
 public:
  // Polled by long work: false once its receiver was forgotten or the runner
  // is shutting down (then its result would not be shown).
  using KeepGoing = std::function<bool()>;

  explicit ViewJobs(QObject* parent = nullptr);
  // Asks the running job to stop and waits for it; queued jobs never run.
  ~ViewJobs() override;
  ViewJobs(const ViewJobs&) = delete;
  ViewJobs& operator=(const ViewJobs&) = delete;

  // Queues `work` for `receiver` under `key`, dropping a queued job of the
  // same receiver and key. On the jobs' thread, once the jobs before it have
  // run: result = work(keep_going). Then on the UI thread, unless the
  // receiver was forgotten since or is gone: show(result), or
  // failed(message) when work threw.
  template <class Result>
  void run(QObject* receiver, int key, std::function<Result(const KeepGoing&)> work,
           std::function<void(Result)> show, std::function<void(const QString&)> failed = nullptr) {
    post(
        receiver, key,
        [work = std::move(work),
         show = std::move(show)](const Task& task) -> std::function<void()> {
          auto result = std::make_shared<Result>(work(task.keep_going));
          return [show, result] { show(std::move(*result)); };
        },
        std::move(failed));
  }

  // What a task's work is given: keep_going, as a view job's, and
  // on_ui_thread(f), which runs f on the UI thread in order with the task's
  // result, unless its receiver was forgotten since or is gone (progress
  // shown while the task works).
  struct Task {
    KeepGoing keep_going;
    std::function<void(std::function<void()>)> on_ui_thread;
  };

  // Queues `work` for `receiver` as a task: like run(), but never replaced
  // and never replacing.
  template <class Result>
  void run_task(QObject* receiver, std::function<Result(const Task&)> work,
                std::function<void(Result)> show,
                std::function<void(const QString&)> failed = nullptr) {
    post(
        receiver, kTaskKey,
        [work = std::move(work),
         show = std::move(show)](const Task& task) -> std::function<void()> {
          auto result = std::make_shared<Result>(work(task));
          return [show, result] { show(std::move(*result)); };
        },
        std::move(failed), /*replaceable=*/false);
  }

  // Drops the receiver's queued jobs and the results of its running one
  // (asked to stop): what a view does when it is given other data.
  void forget(const QObject* receiver);
  // Asks the receiver's queued and running jobs to stop (their keep_going
  // turns false) and still shows their results: how a task is cancelled.
  void cancel(const QObject* receiver);
  // Whether a job of the receiver is queued or running.
  bool has_jobs(const QObject* receiver) const;
  // Whether a job is queued or running, or a result is on its way.
  bool busy() const;
  // Processes events until no job is queued or running and every result was
  // shown (tests, headless screenshots).
  void wait_idle();

 private:
  // The key of every task: tasks are matched by their flag, not their key.
  static constexpr int kTaskKey = -1;
  using Work = std::function<std::function<void()>(const Task&)>;
  struct Job {
    QPointer<QObject> receiver;
    const QObject* owner = nullptr;  // the receiver's address, for matching
    int key = 0;
    std::uint64_t epoch = 0;  // its receiver's when queued
    Work work;
    std::function<void(const QString&)> failed;
    bool replaceable = true;
    std::atomic<bool> stop{false};
  };
  void post(QObject* receiver, int key, Work work, std::function<void(const QString&)> failed,
            bool replaceable = true);
  // Runs `show` on the UI thread if `job`'s receiver is still current and
  // there; counted as a result on its way until then.
  void send(const std::shared_ptr<Job>& job, std::function<void()> show);
  void loop();
  // Whether `job`'s receiver was not forgotten since it was queued (under
  // mutex_).
  bool current(const Job& job) const;

  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::shared_ptr<Job> running_;
  // How often each receiver was forgotten.
  std::map<const QObject*, std::uint64_t> epoch_;
  int results_on_the_way_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace bounce::views
