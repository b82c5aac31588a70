// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/StageWorker.h"

#include <stdexcept>
#include <utility>

namespace dynobj::core {

StageWorker::StageWorker(bool own_thread) {
  if (own_thread) thread_ = std::thread([this] { loop(); });
}

StageWorker::~StageWorker() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void StageWorker::start(std::function<void()> task) {
  if (!thread_.joinable()) {  // inline: the task's exception is kept for wait(), as on a thread
    if (busy_) throw std::logic_error("StageWorker::start: the previous task was not waited for");
    busy_ = true;
    try {
      task();
    } catch (...) {
      error_ = std::current_exception();
    }
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (busy_) throw std::logic_error("StageWorker::start: the previous task was not waited for");
    task_ = std::move(task);
    busy_ = true;
  }
  cv_.notify_all();
}

void StageWorker::wait() {
  std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
  if (thread_.joinable()) {
    lock.lock();
    cv_.wait(lock, [this] { return !busy_; });  // busy_ holds from start() to the task's end
  }
  busy_ = false;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void StageWorker::drain() noexcept {
  try {
    wait();
  } catch (...) {  // the caller's own error is the one to report
  }
}

void StageWorker::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || task_; });
    if (stop_) return;
    std::function<void()> task = std::move(task_);
    task_ = nullptr;
    lock.unlock();
    std::exception_ptr error;
    try {
      task();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    error_ = error;
    busy_ = false;
    cv_.notify_all();
  }
}

}  // namespace dynobj::core
