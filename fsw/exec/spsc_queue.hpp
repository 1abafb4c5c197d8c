// Lock-free single-producer / single-consumer queue over a preallocated array.
// One thread only pushes, one thread only pops. The producer publishes an element by a
// release store of the head index; the consumer acquires it before reading the element,
// and frees the slot by a release store of the tail index (Lamport queue). No mutex, no
// allocation: elements are copied by value into fixed storage.
#pragma once

#include <atomic>
#include <cstdint>

namespace reentry::fsw::exec {

template <class T, int Capacity>
class SpscQueue {
  static_assert(Capacity >= 1, "capacity must be positive");

 public:
  /// Producer side. Returns false (and leaves the queue unchanged) when full.
  bool try_push(const T& value) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    if (head - tail >= static_cast<std::uint64_t>(Capacity)) return false;
    slots_[head % Capacity] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  /// Consumer side. Returns false when empty.
  bool try_pop(T& out) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    out = slots_[tail % Capacity];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Consumer side: true if an element is available.
  bool ready() const {
    return head_.load(std::memory_order_acquire) != tail_.load(std::memory_order_relaxed);
  }

  /// Total number of elements ever pushed (sequence number of the next push).
  std::uint64_t pushed() const { return head_.load(std::memory_order_acquire); }

 private:
  alignas(64) std::atomic<std::uint64_t> head_{0};
  alignas(64) std::atomic<std::uint64_t> tail_{0};
  T slots_[Capacity] = {};
};

}  // namespace reentry::fsw::exec
