#include "sculpt/base/priority_inheriting_mutex.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace sculpt {
namespace {

// A mutex call fails only on misuse (locking twice, unlocking another
// thread's): a bug, reported and stopped, as std::mutex would throw.
void check(int result, const char* what) {
  if (result == 0) return;
  std::fprintf(stderr, "PriorityInheritingMutex: %s: %s\n", what, std::strerror(result));
  std::abort();
}

}  // namespace

PriorityInheritingMutex::PriorityInheritingMutex() {
  pthread_mutexattr_t attr;
  check(pthread_mutexattr_init(&attr), "pthread_mutexattr_init");
  inherits_ = pthread_mutexattr_setprotocol(&attr, PTHREAD_PRIO_INHERIT) == 0;
  check(pthread_mutex_init(&mutex_, &attr), "pthread_mutex_init");
  pthread_mutexattr_destroy(&attr);
}

PriorityInheritingMutex::~PriorityInheritingMutex() {
  pthread_mutex_destroy(&mutex_);
}

void PriorityInheritingMutex::lock() {
  check(pthread_mutex_lock(&mutex_), "lock");
}

bool PriorityInheritingMutex::try_lock() {
  const int result = pthread_mutex_trylock(&mutex_);
  if (result == EBUSY) return false;
  check(result, "try_lock");
  return true;
}

void PriorityInheritingMutex::unlock() {
  check(pthread_mutex_unlock(&mutex_), "unlock");
}

}  // namespace sculpt
