// The views' one job thread (views/view_jobs.h): work runs off the UI thread
// and its result comes back on it, in order; a queued job is replaced by a
// newer one of the same receiver and key; forget() stops a running job and
// drops its result; a failure comes back as a message; a receiver that is
// gone gets nothing; tasks are never replaced, show their progress in order
// with their results, and cancel() stops them but keeps their results.
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <QApplication>
#include <QObject>
#include <QThread>

#include "view_jobs.h"

namespace bounce::render_test {

using views::ViewJobs;

// A job that holds the thread until released, so that the jobs after it
// are still queued when the test changes them.
struct Gate {
  std::promise<void> open;
  std::shared_future<void> opened = open.get_future().share();
  void hold(ViewJobs& jobs, QObject* receiver) {
    jobs.run<int>(
        receiver, 99,
        [opened = opened](const ViewJobs::KeepGoing&) {
          opened.wait();
          return 0;
        },
        [](int) {});
  }
};

TEST(ViewJobs, WorkRunsOffTheUiThreadAndResultsComeBackOnItInOrder) {
  ViewJobs jobs;
  QObject receiver;
  QThread* ui = QThread::currentThread();
  std::vector<int> shown;
  std::atomic<bool> off_ui{true};
  for (int k = 0; k < 5; ++k)
    jobs.run<int>(
        &receiver, k,
        [k, ui, &off_ui](const ViewJobs::KeepGoing&) {
          if (QThread::currentThread() == ui) off_ui = false;
          return k * k;
        },
        [&shown, ui](int r) {
          EXPECT_EQ(QThread::currentThread(), ui);
          shown.push_back(r);
        });
  jobs.wait_idle();
  EXPECT_TRUE(off_ui);
  EXPECT_EQ(shown, (std::vector<int>{0, 1, 4, 9, 16}));
  EXPECT_FALSE(jobs.busy());
}

TEST(ViewJobs, AQueuedJobIsReplacedByANewerOneOfItsKey) {
  ViewJobs jobs;
  QObject receiver;
  Gate gate;
  gate.hold(jobs, &receiver);
  std::vector<std::string> ran, shown;
  for (const std::string name : {"old", "new"})
    jobs.run<std::string>(
        &receiver, 1,
        [name, &ran](const ViewJobs::KeepGoing&) {
          ran.push_back(name);
          return name;
        },
        [&shown](std::string r) { shown.push_back(r); });
  // Another key is not replaced.
  jobs.run<std::string>(
      &receiver, 2, [](const ViewJobs::KeepGoing&) { return std::string("other"); },
      [&shown](std::string r) { shown.push_back(r); });
  gate.open.set_value();
  jobs.wait_idle();
  EXPECT_EQ(ran, std::vector<std::string>{"new"});
  EXPECT_EQ(shown, (std::vector<std::string>{"new", "other"}));
}

TEST(ViewJobs, ForgetStopsTheRunningJobAndDropsItsResult) {
  ViewJobs jobs;
  QObject receiver;
  std::promise<void> started;
  std::atomic<bool> stopped{false};
  bool shown = false;
  jobs.run<int>(
      &receiver, 0,
      [&started, &stopped](const ViewJobs::KeepGoing& keep_going) {
        started.set_value();
        while (keep_going()) QThread::msleep(1);
        stopped = true;
        return 1;
      },
      [&shown](int) { shown = true; });
  started.get_future().wait();
  jobs.forget(&receiver);
  jobs.wait_idle();
  EXPECT_TRUE(stopped);
  EXPECT_FALSE(shown);
  // The receiver's next job is shown again.
  jobs.run<int>(
      &receiver, 0, [](const ViewJobs::KeepGoing&) { return 2; }, [&shown](int) { shown = true; });
  jobs.wait_idle();
  EXPECT_TRUE(shown);
}

TEST(ViewJobs, AFailureComesBackAsItsMessage) {
  ViewJobs jobs;
  QObject receiver;
  QString failure;
  bool shown = false;
  jobs.run<int>(
      &receiver, 0,
      [](const ViewJobs::KeepGoing&) -> int { throw std::runtime_error("no matrix"); },
      [&shown](int) { shown = true; }, [&failure](const QString& m) { failure = m; });
  jobs.wait_idle();
  EXPECT_FALSE(shown);
  EXPECT_EQ(failure, "no matrix");
}

TEST(ViewJobs, AReceiverThatIsGoneGetsNothing) {
  ViewJobs jobs;
  auto receiver = std::make_unique<QObject>();
  Gate gate;
  gate.hold(jobs, receiver.get());
  bool shown = false;
  jobs.run<int>(
      receiver.get(), 0, [](const ViewJobs::KeepGoing&) { return 1; },
      [&shown](int) { shown = true; });
  receiver.reset();
  gate.open.set_value();
  jobs.wait_idle();
  EXPECT_FALSE(shown);
}

TEST(ViewJobs, TasksAreNeverReplacedAndShowProgressAndResultsInOrder) {
  ViewJobs jobs;
  QObject receiver;
  Gate gate;
  gate.hold(jobs, &receiver);
  std::vector<std::string> shown;
  for (const std::string name : {"first", "second"})
    jobs.run_task<std::string>(
        &receiver,
        [name, &shown](const ViewJobs::Task& task) {
          task.on_ui_thread([name, &shown] { shown.push_back(name + " half"); });
          return name;
        },
        [&shown](std::string r) { shown.push_back(r); });
  // A view job of the same receiver replaces neither.
  jobs.run<std::string>(
      &receiver, -1, [](const ViewJobs::KeepGoing&) { return std::string("view"); },
      [&shown](std::string r) { shown.push_back(r); });
  EXPECT_TRUE(jobs.has_jobs(&receiver));
  gate.open.set_value();
  jobs.wait_idle();
  EXPECT_EQ(shown,
            (std::vector<std::string>{"first half", "first", "second half", "second", "view"}));
  EXPECT_FALSE(jobs.has_jobs(&receiver));
}

TEST(ViewJobs, CancelStopsQueuedAndRunningTasksAndStillShowsTheirResults) {
  ViewJobs jobs;
  QObject receiver, other;
  std::promise<void> started;
  std::vector<std::string> shown;
  // Runs until cancelled.
  jobs.run_task<std::string>(
      &receiver,
      [&started](const ViewJobs::Task& task) {
        started.set_value();
        while (task.keep_going()) QThread::msleep(1);
        return std::string("running stopped");
      },
      [&shown](std::string r) { shown.push_back(r); });
  jobs.run_task<std::string>(
      &receiver,
      [](const ViewJobs::Task& task) {
        return std::string(task.keep_going() ? "queued ran" : "queued stopped");
      },
      [&shown](std::string r) { shown.push_back(r); });
  // Another receiver's job is not cancelled.
  jobs.run<std::string>(
      &other, 0,
      [](const ViewJobs::KeepGoing& keep_going) {
        return std::string(keep_going() ? "other ran" : "other stopped");
      },
      [&shown](std::string r) { shown.push_back(r); });
  started.get_future().wait();
  jobs.cancel(&receiver);
  jobs.wait_idle();
  EXPECT_EQ(shown, (std::vector<std::string>{"running stopped", "queued stopped", "other ran"}));
}

}  // namespace bounce::render_test
