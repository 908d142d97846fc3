#include "drvslam/core/bounded_queue.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace drvslam {
namespace {

TEST(BoundedQueueTest, KeepsOrder) {
  BoundedQueue<int> queue(4);
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(queue.Push(i));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(queue.Pop().value(), i);
  EXPECT_FALSE(queue.TryPop().has_value());
}

TEST(BoundedQueueTest, DropOldestKeepsNewest) {
  BoundedQueue<int> queue(2);
  for (int i = 0; i < 5; ++i) queue.PushDropOldest(i);
  EXPECT_EQ(queue.Size(), 2u);
  EXPECT_EQ(queue.Pop().value(), 3);
  EXPECT_EQ(queue.Pop().value(), 4);
}

TEST(BoundedQueueTest, TryPushRefusesWhenFullOrClosedAndKeepsWhatIsQueued) {
  BoundedQueue<int> queue(2);
  EXPECT_TRUE(queue.TryPush(1));
  EXPECT_TRUE(queue.TryPush(2));
  EXPECT_FALSE(queue.TryPush(3));
  EXPECT_EQ(queue.Size(), 2u);
  EXPECT_EQ(queue.Pop().value(), 1);
  EXPECT_TRUE(queue.TryPush(4));
  queue.Close();
  EXPECT_FALSE(queue.TryPush(5));
  EXPECT_EQ(queue.Pop().value(), 2);
  EXPECT_EQ(queue.Pop().value(), 4);
  EXPECT_FALSE(queue.Pop().has_value());
}

TEST(BoundedQueueTest, CloseWakesConsumerAndDrains) {
  BoundedQueue<int> queue(2);
  queue.Push(7);
  queue.Close();
  EXPECT_FALSE(queue.Push(8));
  EXPECT_EQ(queue.Pop().value(), 7);
  EXPECT_FALSE(queue.Pop().has_value());
}

TEST(BoundedQueueTest, ProducerBlocksUntilConsumerCatchesUp) {
  BoundedQueue<int> queue(1);
  std::vector<int> received;
  std::thread consumer([&] {
    while (auto item = queue.Pop()) received.push_back(*item);
  });
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(queue.Push(i));
  queue.Close();
  consumer.join();
  ASSERT_EQ(received.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(received[i], i);
}

}  // namespace
}  // namespace drvslam
