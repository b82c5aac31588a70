// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/StageWorker.h>
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

using dynobj::core::StageWorker;

TEST(StageWorker, InlineRunsOnTheCallersThread) {
  StageWorker w(false);
  EXPECT_FALSE(w.ownThread());
  std::thread::id ran;
  w.start([&] { ran = std::this_thread::get_id(); });
  EXPECT_EQ(ran, std::this_thread::get_id());  // already done when start() returns
  w.wait();
}

TEST(StageWorker, OwnThreadRunsBesideTheCaller) {
  StageWorker w(true);
  EXPECT_TRUE(w.ownThread());
  for (int round = 0; round < 3; round++) {  // the same thread, task after task
    std::atomic<bool> release{false};
    std::thread::id ran;
    int value = 0;
    w.start([&] {
      while (!release) std::this_thread::yield();  // runs until the caller lets it finish
      ran = std::this_thread::get_id();
      value = 10 + round;
    });
    release = true;  // the caller went on while the task waited
    w.wait();
    EXPECT_NE(ran, std::this_thread::get_id());
    EXPECT_EQ(value, 10 + round);  // wait() makes the task's writes visible
  }
}

TEST(StageWorker, WaitRethrowsAndTheWorkerGoesOn) {
  for (const bool own : {false, true}) {
    StageWorker w(own);
    w.start([] { throw std::runtime_error("stage failed"); });
    EXPECT_THROW(w.wait(), std::runtime_error) << (own ? "own thread" : "inline");
    int value = 0;
    w.start([&] { value = 1; });
    EXPECT_NO_THROW(w.wait());
    EXPECT_EQ(value, 1);
    w.start([] { throw std::runtime_error("dropped"); });
    w.drain();  // no throw
    EXPECT_NO_THROW(w.wait());
  }
}

TEST(StageWorker, OneTaskAtATime) {
  for (const bool own : {false, true}) {
    StageWorker w(own);
    std::atomic<bool> release{!own};  // inline, the task has run to its end in start()
    w.start([&] {
      while (!release) std::this_thread::yield();
    });
    EXPECT_THROW(w.start([] {}), std::logic_error);
    release = true;
    w.wait();
  }
}
