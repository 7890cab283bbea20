#include "core/base/parallel_tasks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(ParallelTasks, RunsEveryTaskExactlyOnceOnWorkersBelowTheThreadCount) {
  for (int threads : {-3, 0, 1, 2, 3, 8})
    for (int64_t tasks : {0, 1, 2, 7, 1000}) {
      std::vector<std::atomic<int>> runs(tasks);
      std::atomic<int> bad_worker{0};
      RunTasks(threads, tasks, [&](int worker, int64_t t) {
        if (worker < 0 || worker >= std::max(threads, 1)) ++bad_worker;
        ++runs[t];
      });
      for (int64_t t = 0; t < tasks; ++t)
        ASSERT_EQ(runs[t].load(), 1) << "threads " << threads << " tasks " << tasks << " t " << t;
      EXPECT_EQ(bad_worker.load(), 0) << "threads " << threads;
    }
}

TEST(ParallelTasks, OneThreadRunsTasksInOrderOnTheCallingThread) {
  std::vector<int64_t> order;
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  RunTasks(1, 5, [&](int worker, int64_t t) {
    elsewhere |= worker != 0 || std::this_thread::get_id() != caller;
    order.push_back(t);
  });
  EXPECT_FALSE(elsewhere);
  EXPECT_EQ(order, (std::vector<int64_t>{0, 1, 2, 3, 4}));
}

TEST(ParallelTasks, WorkerZeroIsTheCallingThread) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> mismatches{0}, zero_tasks{0};
  // Tasks of a millisecond each: the started threads cannot take them all before the caller
  // starts on its share.
  RunTasks(4, 64, [&](int worker, int64_t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (worker != 0) return;
    ++zero_tasks;
    if (std::this_thread::get_id() != caller) ++mismatches;
  });
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_GT(zero_tasks.load(), 0);
}

TEST(TaskRanges, CoverTheListInConsecutiveRangesOfNearlyEqualSize) {
  for (int threads : {-1, 0, 1, 2, 3, 8})
    for (int per_thread : {1, 4, 16})
      for (int64_t count : {0, 1, 5, 16, 17, 1000, 1001}) {
        const TaskRanges r = TaskRanges::Split(count, threads, per_thread, /*min_split=*/16);
        SCOPED_TRACE(testing::Message() << "threads " << threads << " per thread " << per_thread
                                        << " count " << count);
        const int64_t expected =
            threads <= 1 || count < 16 ? 1 : std::min<int64_t>(count, per_thread * threads);
        ASSERT_EQ(r.tasks, expected);
        EXPECT_EQ(r.begin(0), 0);
        EXPECT_EQ(r.end(r.tasks - 1), count);
        int64_t smallest = count, largest = 0;
        for (int64_t t = 0; t < r.tasks; ++t) {
          if (t > 0) {
            EXPECT_EQ(r.begin(t), r.end(t - 1));
          }
          smallest = std::min(smallest, r.end(t) - r.begin(t));
          largest = std::max(largest, r.end(t) - r.begin(t));
        }
        EXPECT_LE(largest - smallest, 1);
      }
}

TEST(TaskCancel, AWorkerOtherThanTheCallingThreadSeesTheCancel) {
  // On a loaded machine the calling thread (worker 0) may run none of the tasks: the worker
  // that runs them must see the cancel itself.
  CancelToken cancel;
  TaskCancel stop(cancel, 2, 2);
  EXPECT_FALSE(stop.Poll(1));
  cancel.Cancel();
  EXPECT_TRUE(stop.Poll(1));  // its second unit: it asks the token
  EXPECT_TRUE(stop.fired());
  EXPECT_TRUE(stop.Poll(0));  // the other worker sees the shared flag at once
}

}  // namespace
}  // namespace membrane
