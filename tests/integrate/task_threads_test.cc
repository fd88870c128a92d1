// RunTasks (integrate/src/task_threads.h), which shares Magnus–Filon's generators out to the
// analysis's waiting threads: every task once, on as many threads as asked, failures rethrown.
#include "task_threads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ltp::internal {
namespace {

TEST(RunTasks, RunsEveryTaskExactlyOnce) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<std::atomic<int>> runs(97);
    RunTasks(97, threads, [&](int i) { ++runs[i]; });
    for (int i = 0; i < 97; ++i) EXPECT_EQ(runs[i].load(), 1) << "task " << i << ", " << threads;
  }
  int none = 0;
  RunTasks(0, 2, [&](int) { ++none; });
  EXPECT_EQ(none, 0);
}

TEST(RunTasks, SharesTheTasksBetweenTheThreadsAsked) {
  // Each task waits until two threads have started one: with two threads it finishes, and
  // both threads ran tasks; the caller is one of them.
  std::mutex mutex;
  std::set<std::thread::id> ids;
  std::atomic<int> started{0};
  RunTasks(2, 2, [&](int) {
    ++started;
    while (started.load() < 2) std::this_thread::yield();
    const std::lock_guard<std::mutex> lock(mutex);
    ids.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(ids.size(), 2u);
  EXPECT_EQ(ids.count(std::this_thread::get_id()), 1u);
}

TEST(RunTasks, RethrowsATaskFailureAfterTheOthersFinish) {
  std::atomic<int> finished{0};
  EXPECT_THROW(RunTasks(50, 2,
                        [&](int i) {
                          if (i == 3) throw std::runtime_error("task 3");
                          ++finished;
                        }),
               std::runtime_error);
  EXPECT_LE(finished.load(), 49);  // the rest may be skipped, none runs after the return
  const int after = finished.load();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(finished.load(), after);
}

TEST(TeamThreads, IsTheEnclosingParallelRegionsSize) {
  EXPECT_EQ(TeamThreads(), 1);
  std::atomic<int> entered{0}, said{0};
#pragma omp parallel num_threads(2)
  {
    ++entered;  // counted by the threads themselves: how many the runtime gave
#pragma omp barrier
#pragma omp single
    said = TeamThreads();
  }
  EXPECT_EQ(said.load(), entered.load());
}

}  // namespace
}  // namespace ltp::internal
