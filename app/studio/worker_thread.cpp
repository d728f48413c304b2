#include "worker_thread.h"

#include <QThread>

namespace bounce::studio {

bool WorkerThread::start(std::function<void()> job) {
  if (thread_) return false;
  cancel_.store(false);
  thread_ = QThread::create(std::move(job));
  QObject::connect(thread_, &QThread::finished, owner_, [this] {
    thread_->deleteLater();
    thread_ = nullptr;
  });
  thread_->start();
  return true;
}

void WorkerThread::cancel_and_wait() {
  if (!thread_) return;
  cancel();
  thread_->wait();
}

}  // namespace bounce::studio
