// SPSC handoff under two threads: every message arrives once, in order, never torn.
#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

#include "exec/spsc_queue.hpp"

namespace {

struct Message {
  std::uint64_t seq = 0;
  std::uint64_t payload[32] = {};  // every word derived from seq: a torn copy breaks the relation
};

constexpr std::uint64_t kMessages = 100000;

TEST(SpscQueue, TwoThreadStressKeepsSequenceAndIntegrity) {
  static reentry::fsw::exec::SpscQueue<Message, 4> queue;
  std::thread producer([] {
    Message m;
    for (std::uint64_t s = 1; s <= kMessages; ++s) {
      m.seq = s;
      for (int i = 0; i < 32; ++i) m.payload[i] = s * 2654435761ULL + static_cast<std::uint64_t>(i);
      while (!queue.try_push(m)) std::this_thread::yield();
    }
  });
  std::uint64_t expected = 1;
  std::uint64_t torn = 0;
  std::uint64_t out_of_order = 0;
  Message got;
  while (expected <= kMessages) {
    if (!queue.try_pop(got)) {
      std::this_thread::yield();
      continue;
    }
    if (got.seq != expected) ++out_of_order;
    for (int i = 0; i < 32; ++i) {
      if (got.payload[i] != got.seq * 2654435761ULL + static_cast<std::uint64_t>(i)) {
        ++torn;
        break;
      }
    }
    expected = got.seq + 1;
  }
  producer.join();
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(queue.pushed(), kMessages);
  EXPECT_FALSE(queue.try_pop(got));
}

TEST(SpscQueue, FullAndEmptyAreReported) {
  reentry::fsw::exec::SpscQueue<int, 2> q;
  int v = 0;
  EXPECT_FALSE(q.try_pop(v));
  EXPECT_TRUE(q.try_push(1));
  EXPECT_TRUE(q.try_push(2));
  EXPECT_FALSE(q.try_push(3));
  EXPECT_TRUE(q.try_pop(v));
  EXPECT_EQ(v, 1);
  EXPECT_TRUE(q.try_pop(v));
  EXPECT_EQ(v, 2);
  EXPECT_FALSE(q.ready());
}

}  // namespace
