#pragma once
// A mutex whose holder runs at the priority of the most urgent thread
// waiting for it (POSIX priority inheritance; on Linux a PI futex).
//
// The window's sculpting thread is real-time (thread_priority.h) and takes
// turns with the frame's thread, which is nicer than ordinary, for the
// controller (input_hub.h). With a plain mutex a report waited for a frame
// that held the turn while the real-time mesher took both cores: the
// sculpting thread, ahead of the mesher, waited for a thread behind it
// (priority inversion; 3.2 ms on the demo). Here the frame's thread runs at
// the sculpting thread's priority while that waits, and drops back as it
// lets go.
//
// Lockable (std::lock_guard, std::unique_lock). Not recursive. Linux and
// any POSIX system with _POSIX_THREAD_PRIO_INHERIT; where the protocol is
// refused it is an ordinary mutex (inherits_priority() says which).

#include <pthread.h>

namespace sculpt {

class PriorityInheritingMutex {
 public:
  PriorityInheritingMutex();
  ~PriorityInheritingMutex();
  PriorityInheritingMutex(const PriorityInheritingMutex&) = delete;
  PriorityInheritingMutex& operator=(const PriorityInheritingMutex&) = delete;

  void lock();
  bool try_lock();
  void unlock();

  /// Whether the system took the priority-inheritance protocol.
  bool inherits_priority() const { return inherits_; }

 private:
  pthread_mutex_t mutex_;
  bool inherits_ = false;
};

}  // namespace sculpt
