// OrderedWorker: the work done in push order on its own thread, errors back
// to the producer, a producer that gives up early.
#include "common/ordered_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace storey {
namespace {

TEST(OrderedWorker, DoesTheWorkInPushOrderOnAnotherThread) {
  std::vector<int> done;
  std::thread::id worker_id;
  {
    OrderedWorker<int> worker(3, [&](int& item) {
      done.push_back(item);
      worker_id = std::this_thread::get_id();
      if (item % 7 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    for (int i = 0; i < 200; ++i) worker.push(i);
    worker.finish();
    ASSERT_EQ(done.size(), 200u);
  }
  for (int i = 0; i < 200; ++i) EXPECT_EQ(done[static_cast<std::size_t>(i)], i);
  EXPECT_NE(worker_id, std::this_thread::get_id());
}

TEST(OrderedWorker, CapacityZeroWorksInline) {
  std::vector<int> done;
  std::thread::id worker_id;
  OrderedWorker<int> worker(0, [&](int& item) {
    done.push_back(item);
    worker_id = std::this_thread::get_id();
  });
  worker.push(5);
  EXPECT_EQ(done, std::vector<int>{5});  // done before push() returned
  EXPECT_EQ(worker_id, std::this_thread::get_id());
  worker.finish();
}

TEST(OrderedWorker, NeverHoldsMoreThanItsCapacity) {
  std::atomic<int> pushed{0}, worked{0};
  int most_ahead = 0;
  OrderedWorker<int> worker(2, [&](int&) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    ++worked;
  });
  for (int i = 0; i < 50; ++i) {
    worker.push(i);
    ++pushed;
    most_ahead = std::max(most_ahead, pushed - worked);
  }
  worker.finish();
  EXPECT_EQ(worked, 50);
  // Queued (2) plus the one in progress.
  EXPECT_LE(most_ahead, 3);
}

TEST(OrderedWorker, TheWorksErrorComesOutOfTheNextPushOrFinish) {
  std::vector<int> done;
  OrderedWorker<int> worker(2, [&](int& item) {
    if (item == 3) throw std::runtime_error("bad item 3");
    done.push_back(item);
  });
  bool thrown = false;
  try {
    for (int i = 0; i < 100; ++i) worker.push(i);
    worker.finish();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "bad item 3");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(done, (std::vector<int>{0, 1, 2}));  // nothing after the failed item
}

TEST(OrderedWorker, AProducerThatGivesUpStopsTheThread) {
  std::atomic<int> worked{0};
  {
    OrderedWorker<int> worker(4, [&](int&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ++worked;
    });
    for (int i = 0; i < 5; ++i) worker.push(i);
  }  // destroyed without finish(): ends after the item in progress
  EXPECT_LT(worked, 5);
}

}  // namespace
}  // namespace storey
