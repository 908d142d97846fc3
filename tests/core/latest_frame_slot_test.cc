#include "drvslam/core/latest_frame_slot.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace drvslam {
namespace {

TEST(LatestFrameSlotTest, NewerItemReplacesWaitingOneAndIsCounted) {
  LatestFrameSlot<int> slot;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(slot.Put(i));
  EXPECT_EQ(slot.Skipped(), 4u);
  EXPECT_EQ(slot.Accepted(), 5u);
  EXPECT_EQ(slot.TryTake().value(), 4);
  EXPECT_FALSE(slot.TryTake().has_value());
  // An empty slot takes the next item without skipping anything.
  ASSERT_TRUE(slot.Put(5));
  EXPECT_EQ(slot.Skipped(), 4u);
  EXPECT_EQ(slot.Take().value(), 5);
}

TEST(LatestFrameSlotTest, CloseDeliversTheWaitingItemThenEnds) {
  LatestFrameSlot<int> slot;
  slot.Put(1);
  slot.Close();
  EXPECT_FALSE(slot.Put(2));
  EXPECT_EQ(slot.Accepted(), 1u);
  EXPECT_EQ(slot.Take().value(), 1);
  EXPECT_FALSE(slot.Take().has_value());
}

// A fast producer and a slow consumer: the producer puts three items while the consumer is busy
// with each one it took, so of every three only the newest is taken and two are skipped.
TEST(LatestFrameSlotTest, FastProducerSlowConsumerSkipsExactly) {
  LatestFrameSlot<int> slot;
  std::mutex mutex;
  std::condition_variable changed;
  int taken_count = 0;
  bool release = false;
  std::vector<int> taken;
  constexpr int kRounds = 10;
  int next = 0;
  std::thread consumer;
  for (int round = 0; round < kRounds; ++round) {
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(slot.Put(next++));
    if (round == 0) {
      // The consumer starts once the first three wait, so every round is alike.
      consumer = std::thread([&] {
        while (std::optional<int> item = slot.Take()) {
          std::unique_lock<std::mutex> lock(mutex);
          taken.push_back(*item);
          ++taken_count;
          changed.notify_all();
          // Busy "tracking" the item until the producer has put the next three.
          changed.wait(lock, [&] { return release; });
          release = false;
        }
      });
    } else {
      std::lock_guard<std::mutex> lock(mutex);
      release = true;
      changed.notify_all();
    }
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return taken_count == round + 1; });
  }
  slot.Close();
  {
    std::lock_guard<std::mutex> lock(mutex);
    release = true;
    changed.notify_all();
  }
  consumer.join();
  ASSERT_EQ(taken.size(), static_cast<std::size_t>(kRounds));
  for (int round = 0; round < kRounds; ++round) EXPECT_EQ(taken[round], 3 * round + 2);
  EXPECT_EQ(slot.Accepted(), static_cast<std::size_t>(3 * kRounds));
  EXPECT_EQ(slot.Skipped(), static_cast<std::size_t>(2 * kRounds));
}

}  // namespace
}  // namespace drvslam
