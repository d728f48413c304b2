#include "view_jobs.h"

#include <algorithm>
#include <exception>

#include <QCoreApplication>
#include <QThread>

namespace bounce::views {

ViewJobs::ViewJobs(QObject* parent) : QObject(parent), thread_([this] { loop(); }) {}

ViewJobs::~ViewJobs() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    queue_.clear();
    if (running_) running_->stop.store(true);
  }
  ready_.notify_all();
  thread_.join();
}

void ViewJobs::post(QObject* receiver, int key, Work work,
                    std::function<void(const QString&)> failed, bool replaceable) {
  auto job = std::make_shared<Job>();
  job->receiver = receiver;
  job->owner = receiver;
  job->key = key;
  job->work = std::move(work);
  job->failed = std::move(failed);
  job->replaceable = replaceable;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job->epoch = epoch_[receiver];
    if (replaceable)
      std::erase_if(queue_, [&](const std::shared_ptr<Job>& queued) {
        return queued->replaceable && queued->owner == receiver && queued->key == key;
      });
    queue_.push_back(std::move(job));
  }
  ready_.notify_all();
}

void ViewJobs::forget(const QObject* receiver) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::erase_if(queue_,
                [&](const std::shared_ptr<Job>& queued) { return queued->owner == receiver; });
  ++epoch_[receiver];
  if (running_ && running_->owner == receiver) running_->stop.store(true);
}

void ViewJobs::cancel(const QObject* receiver) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& queued : queue_)
    if (queued->owner == receiver) queued->stop.store(true);
  if (running_ && running_->owner == receiver) running_->stop.store(true);
}

bool ViewJobs::has_jobs(const QObject* receiver) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return (running_ && running_->owner == receiver) ||
         std::any_of(queue_.begin(), queue_.end(),
                     [&](const std::shared_ptr<Job>& queued) { return queued->owner == receiver; });
}

bool ViewJobs::current(const Job& job) const {
  const auto it = epoch_.find(job.owner);
  return it != epoch_.end() && it->second == job.epoch;
}

bool ViewJobs::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return !queue_.empty() || running_ || results_on_the_way_ > 0;
}

void ViewJobs::wait_idle() {
  while (busy()) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    QThread::msleep(1);
  }
  QCoreApplication::processEvents();
}

void ViewJobs::loop() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = queue_.front();
      queue_.pop_front();
      running_ = job;
    }
    Task task;
    task.keep_going = [job] { return !job->stop.load(); };
    task.on_ui_thread = [this, job](std::function<void()> show) { send(job, std::move(show)); };
    std::function<void()> show;
    try {
      show = job->work(task);
    } catch (const std::exception& e) {
      show = [job, error = QString::fromStdString(e.what())] {
        if (job->failed) job->failed(error);
      };
    }
    // Counted as on its way before the job stops being the running one, so
    // that busy() never sees the runner idle with a result still to show.
    send(job, std::move(show));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_.reset();
    }
  }
}

void ViewJobs::send(const std::shared_ptr<Job>& job, std::function<void()> show) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++results_on_the_way_;
  }
  // Shown on the UI thread, this runner's; dropped with the runner.
  QMetaObject::invokeMethod(
      this,
      [this, job, show = std::move(show)] {
        bool shown = false;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          --results_on_the_way_;
          shown = current(*job) && job->receiver;
        }
        if (shown) show();
      },
      Qt::QueuedConnection);
}

}  // namespace bounce::views
