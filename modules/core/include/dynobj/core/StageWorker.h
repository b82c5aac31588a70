// SPDX-License-Identifier: BSD-3-Clause
// One task at a time on a thread of its own, for the detector's two independent branches
// ([pipeline] threads = 2), or on the caller's thread (threads = 1).
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace dynobj::core {

class StageWorker {
 public:
  /// `own_thread`: false runs every task inside start(), on the caller's thread.
  explicit StageWorker(bool own_thread);
  ~StageWorker();
  StageWorker(const StageWorker&) = delete;
  StageWorker& operator=(const StageWorker&) = delete;

  /// Starts `task` (at most one at a time: call wait() before the next start()).
  void start(std::function<void()> task);
  /// Returns once the task has finished; rethrows what it threw.
  void wait();
  /// wait(), dropping what the task threw: for a caller that is already failing, so that the
  /// task does not outlive the data it works on.
  void drain() noexcept;
  bool ownThread() const { return thread_.joinable(); }

 private:
  void loop();

  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::function<void()> task_;  ///< the pending task (empty: none)
  bool busy_ = false, stop_ = false;
  std::exception_ptr error_;
};

}  // namespace dynobj::core
