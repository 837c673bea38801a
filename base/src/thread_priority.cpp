#include "sculpt/base/thread_priority.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

namespace sculpt {

std::vector<int> process_thread_ids() {
  std::vector<int> ids;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    const std::string name = task.path().filename().string();
    int id = 0;
    const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), id);
    if (error == std::errc() && end == name.data() + name.size()) ids.push_back(id);
  }
  if (ec) return {};
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<int> threads_named(std::string_view name) {
  std::vector<int> named;
  for (const int id : process_thread_ids()) {
    std::ifstream comm("/proc/self/task/" + std::to_string(id) + "/comm");
    std::string line;
    if (std::getline(comm, line) && line == name) named.push_back(id);
  }
  return named;
}

std::vector<int> threads_started(std::span<const int> before, std::span<const int> now) {
  std::vector<int> started;
  std::set_difference(now.begin(), now.end(), before.begin(), before.end(),
                      std::back_inserter(started));
  return started;
}

int this_thread_id() {
  return static_cast<int>(gettid());
}

int thread_niceness(int id) {
  // getpriority() may return -1 as a niceness: errno tells an error apart.
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(id));
  return errno != 0 ? -100 : nice;
}

int make_threads_nicer(std::span<const int> ids, int nice) {
  int changed = 0;
  for (const int id : ids) {
    const int now = thread_niceness(id);
    if (now == -100 || now >= nice) continue;  // ended, or nicer already
    if (setpriority(PRIO_PROCESS, static_cast<id_t>(id), nice) == 0) ++changed;
  }
  return changed;
}

std::string make_threads_realtime(std::span<const int> ids, int priority) {
  sched_param param{};
  param.sched_priority = priority;
  std::string why_not;
  for (const int id : ids) {
    if (sched_setscheduler(id, SCHED_FIFO | SCHED_RESET_ON_FORK, &param) == 0) continue;
    if (errno == ESRCH) continue;  // it ended meanwhile
    if (why_not.empty()) why_not = std::strerror(errno);
  }
  return why_not;
}

ThreadScheduling thread_scheduling(int id) {
  ThreadScheduling s;
  s.policy = sched_getscheduler(id) & ~SCHED_RESET_ON_FORK;
  sched_param param{};
  if (sched_getparam(id, &param) == 0) s.priority = param.sched_priority;
  return s;
}

ThreadScheduling this_thread_scheduling() {
  return thread_scheduling(0);
}

bool set_this_thread_scheduling(const ThreadScheduling& s) {
  sched_param param{};
  param.sched_priority = s.priority;
  // The flag, once set, only a privileged thread may clear: keeping it set
  // lets a helper that ran a real-time loop go back to ordinary.
  return sched_setscheduler(0, s.policy | SCHED_RESET_ON_FORK, &param) == 0;
}

}  // namespace sculpt
