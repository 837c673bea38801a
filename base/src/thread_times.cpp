#include "sculpt/base/thread_times.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

namespace sculpt {
namespace {

std::string group_name(std::string name) {
  while (!name.empty() && (name.back() == '\n' || name.back() == ' '))
    name.pop_back();
  while (!name.empty() && std::isdigit(static_cast<unsigned char>(name.back())))
    name.pop_back();
  if (name.size() > 1 && (name.back() == '-' || name.back() == '_')) name.pop_back();
  return name.empty() ? "unnamed" : name;
}

// utime + stime of /proc/.../stat, in clock ticks; -1 if unreadable. The
// command name (field 2) may hold spaces and parentheses: the fields that
// follow start after its last ')'.
long long stat_ticks(const std::filesystem::path& stat) {
  std::ifstream in(stat);
  std::string line;
  if (!std::getline(in, line)) return -1;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(line.substr(close + 1));
  std::string field;
  long long utime = -1, stime = -1;
  // Fields 3.. follow: state is 3, utime 14, stime 15.
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14) utime = std::atoll(field.c_str());
    if (i == 15) stime = std::atoll(field.c_str());
  }
  return utime < 0 || stime < 0 ? -1 : utime + stime;
}

double seconds(const timeval& t) {
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
}

}  // namespace

void name_this_thread(const std::string& name) {
  pthread_setname_np(pthread_self(), name.substr(0, 15).c_str());
}

std::vector<ThreadGroupTime> thread_cpu_times() {
  const double tick_s = 1.0 / static_cast<double>(std::max(1L, sysconf(_SC_CLK_TCK)));
  std::map<std::string, ThreadGroupTime> groups;
  double running_s = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    std::getline(comm, name);
    const long long ticks = stat_ticks(task.path() / "stat");
    if (ticks < 0) continue;  // it ended while we looked
    ThreadGroupTime& g = groups[group_name(name)];
    g.name = group_name(name);
    ++g.threads;
    g.cpu_s += static_cast<double>(ticks) * tick_s;
    running_s += static_cast<double>(ticks) * tick_s;
  }
  if (ec || groups.empty()) return {};
  std::vector<ThreadGroupTime> out;
  for (auto& [name, g] : groups)
    out.push_back(g);
  std::sort(out.begin(), out.end(),
            [](const ThreadGroupTime& a, const ThreadGroupTime& b) { return a.cpu_s > b.cpu_s; });
  rusage self{};
  if (getrusage(RUSAGE_SELF, &self) == 0) {
    const double ended = seconds(self.ru_utime) + seconds(self.ru_stime) - running_s;
    // Ticks round down: less than two of them per thread is that rounding.
    if (ended > 2.0 * tick_s * static_cast<double>(out.size())) out.push_back({"ended", 0, ended});
  }
  return out;
}

}  // namespace sculpt
