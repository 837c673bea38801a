#include "sculpt/hal/types/clock.h"

#include <cerrno>

#include <time.h>

namespace sculpt::hal {

int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

void sleep_until_ns(int64_t t_ns) {
  const timespec t{static_cast<time_t>(t_ns / 1'000'000'000),
                   static_cast<long>(t_ns % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
  }
}

}  // namespace sculpt::hal
