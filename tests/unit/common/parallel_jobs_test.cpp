// runJobs: jobs on several threads, reported in order on the caller's.
#include "common/parallel_jobs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace storey {
namespace {

TEST(ParallelJobs, ReportsEveryJobInOrderOnTheCallersThread) {
  for (int threads : {1, 2, 5}) {
    std::vector<int> results(20, -1);
    std::vector<std::function<void()>> jobs;
    for (int i = 0; i < 20; ++i)
      jobs.push_back([&results, i] {
        if (i % 3 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        results[static_cast<std::size_t>(i)] = i * i;
      });
    std::vector<std::size_t> reported;
    const std::thread::id caller = std::this_thread::get_id();
    runJobs(jobs, threads, [&](std::size_t i) {
      EXPECT_EQ(std::this_thread::get_id(), caller);
      EXPECT_EQ(results[i], static_cast<int>(i * i)) << "reported before it was done";
      reported.push_back(i);
    });
    ASSERT_EQ(reported.size(), 20u) << threads << " threads";
    for (std::size_t i = 0; i < reported.size(); ++i) EXPECT_EQ(reported[i], i);
  }
}

TEST(ParallelJobs, TwoThreadsRunTwoJobsAtOnce) {
  // Each job waits for the other to have started: only possible side by side.
  std::mutex mutex;
  std::condition_variable changed;
  int started = 0;
  bool both = true;
  const auto job = [&] {
    std::unique_lock<std::mutex> lock(mutex);
    ++started;
    changed.notify_all();
    both = changed.wait_for(lock, std::chrono::seconds(10), [&] { return started == 2; }) && both;
  };
  runJobs({job, job}, 2);
  EXPECT_TRUE(both);
}

TEST(ParallelJobs, AJobsErrorStopsTheJobsNotStartedAndComesOut) {
  for (int threads : {1, 2}) {
    std::atomic<int> ran{0};
    std::vector<std::function<void()>> jobs;
    jobs.push_back([&] { ++ran; });
    jobs.push_back([&] {
      ++ran;
      throw std::runtime_error("job 1 failed");
    });
    for (int i = 0; i < 50; ++i)
      jobs.push_back([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        ++ran;
      });
    std::vector<std::size_t> reported;
    try {
      runJobs(jobs, threads, [&](std::size_t i) { reported.push_back(i); });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "job 1 failed");
    }
    EXPECT_EQ(reported, std::vector<std::size_t>{0}) << threads << " threads";
    EXPECT_LT(ran, 52) << threads << " threads: the jobs after the error were not stopped";
  }
}

TEST(ParallelJobs, AnErrorOfTheReportStopsTheJobs) {
  std::atomic<int> ran{0};
  std::vector<std::function<void()>> jobs(40, [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ++ran;
  });
  EXPECT_THROW(runJobs(jobs, 2,
                       [](std::size_t i) {
                         if (i == 2) throw std::runtime_error("cancelled");
                       }),
               std::runtime_error);
  EXPECT_LT(ran, 40);
}

}  // namespace
}  // namespace storey
