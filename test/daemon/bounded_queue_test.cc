#include "fusemap/daemon/bounded_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace fusemap {
namespace daemon {
namespace {

TEST(BoundedQueueTest, DropOldestKeepsNewestAndCounts) {
  std::vector<int> dropped;
  BoundedQueue<int> queue(3, OverflowPolicy::kDropOldest,
                          [&dropped](const int& v) { dropped.push_back(v); });
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(queue.Push(i));
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(queue.dropped(), 2);
  EXPECT_EQ(queue.pushed(), 5);
  EXPECT_EQ(dropped, (std::vector<int>{0, 1}));
  EXPECT_EQ(*queue.Pop(), 2);
  EXPECT_EQ(*queue.Pop(), 3);
  EXPECT_EQ(*queue.Pop(), 4);
}

TEST(BoundedQueueTest, CloseDrainsThenReturnsEmptyAndRefusesPush) {
  BoundedQueue<int> queue(4, OverflowPolicy::kDropOldest);
  queue.Push(1);
  queue.Push(2);
  queue.Close();
  EXPECT_FALSE(queue.Push(3));
  EXPECT_FALSE(queue.closed_and_drained());
  EXPECT_EQ(*queue.Pop(), 1);
  EXPECT_EQ(*queue.Pop(), 2);
  EXPECT_FALSE(queue.Pop().has_value());
  EXPECT_TRUE(queue.closed_and_drained());
  EXPECT_EQ(queue.dropped(), 0);
}

TEST(BoundedQueueTest, CloseWakesBlockedConsumer) {
  BoundedQueue<int> queue(2, OverflowPolicy::kDropOldest);
  std::atomic<bool> got_empty{false};
  std::thread consumer([&] { got_empty = !queue.Pop().has_value(); });
  queue.Close();
  consumer.join();
  EXPECT_TRUE(got_empty);
}

TEST(BoundedQueueTest, BlockPolicyNeverDropsAndKeepsOrder) {
  constexpr int kCount = 10000;
  BoundedQueue<int> queue(2, OverflowPolicy::kBlock);
  std::thread producer([&] {
    for (int i = 0; i < kCount; ++i) ASSERT_TRUE(queue.Push(i));
    queue.Close();
  });
  int expected = 0;
  while (auto v = queue.Pop()) {
    ASSERT_EQ(*v, expected);
    ASSERT_LE(queue.size(), 2u);
    ++expected;
  }
  producer.join();
  EXPECT_EQ(expected, kCount);
  EXPECT_EQ(queue.dropped(), 0);
}

TEST(BoundedQueueTest, CloseReleasesBlockedProducer) {
  BoundedQueue<int> queue(1, OverflowPolicy::kBlock);
  ASSERT_TRUE(queue.Push(0));
  std::atomic<int> result{-1};
  std::thread producer([&] { result = queue.Push(1) ? 1 : 0; });
  queue.Close();
  producer.join();
  EXPECT_EQ(result, 0);
  EXPECT_EQ(*queue.Pop(), 0);
  EXPECT_FALSE(queue.Pop().has_value());
}

TEST(BoundedQueueTest, PopUntilTimesOutEmpty) {
  BoundedQueue<int> queue(1, OverflowPolicy::kDropOldest);
  EXPECT_FALSE(queue.PopUntil(std::chrono::steady_clock::now()).has_value());
  EXPECT_FALSE(queue.closed_and_drained());
  queue.Push(7);
  EXPECT_EQ(*queue.PopUntil(std::chrono::steady_clock::now()), 7);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
