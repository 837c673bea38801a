#pragma once
// A bounded lock-free single-producer single-consumer ring (Lamport's queue
// with acquire/release indices and cached opposite indices, as in
// folly::ProducerConsumerQueue / rigtorp::SPSCQueue). One thread may push,
// one other thread may pop; neither ever blocks.

#include <atomic>
#include <cassert>
#include <cstddef>
#include <memory>
#include <new>
#include <optional>

namespace sculpt::hal {

template <class T>
class SpscRing {
 public:
  /// capacity: items the ring holds (>= 1).
  explicit SpscRing(size_t capacity)
      : slots_(capacity + 1), buffer_(std::make_unique<T[]>(capacity + 1)) {
    assert(capacity >= 1);
  }
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  /// Producer: false (and nothing stored) when full.
  bool try_push(const T& item) {
    const size_t head = head_.load(std::memory_order_relaxed);
    const size_t next = head + 1 == slots_ ? 0 : head + 1;
    if (next == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (next == tail_cache_) return false;
    }
    buffer_[head] = item;
    head_.store(next, std::memory_order_release);
    return true;
  }

  /// Consumer: false when empty.
  bool try_pop(T& out) {
    const size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_cache_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail == head_cache_) return false;
    }
    out = buffer_[tail];
    tail_.store(tail + 1 == slots_ ? 0 : tail + 1, std::memory_order_release);
    return true;
  }

  /// Items held; exact only when called by producer or consumer with the other idle.
  size_t size_approx() const {
    const size_t h = head_.load(std::memory_order_acquire);
    const size_t t = tail_.load(std::memory_order_acquire);
    return h >= t ? h - t : h + slots_ - t;
  }
  size_t capacity() const { return slots_ - 1; }

 private:
  static constexpr size_t kLine =
      64;  // keeps producer and consumer indices on separate cache lines
  const size_t slots_;
  std::unique_ptr<T[]> buffer_;
  alignas(kLine) std::atomic<size_t> head_{0};  // written by the producer
  size_t tail_cache_ = 0;                       // producer's copy of tail_
  alignas(kLine) std::atomic<size_t> tail_{0};  // written by the consumer
  size_t head_cache_ = 0;                       // consumer's copy of head_
};

}  // namespace sculpt::hal
