#include "sculpt/base/temp_files.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>

namespace sculpt {
namespace {

// Fixed storage: the handler may read it at any moment, so nothing here is
// allocated or moved. A slot is claimed, its path written, and only then
// marked listed, so the handler never reads a path being written.
constexpr size_t kSlots = 64;
constexpr size_t kPathBytes = 4096;
enum SlotState : int { kFree, kClaimed, kListed };
std::array<std::atomic<int>, kSlots> g_state{};
std::array<std::array<char, kPathBytes>, kSlots> g_paths{};
std::atomic<bool> g_installed{false};

void remove_and_die(int signal) {
  for (size_t i = 0; i < kSlots; ++i)
    if (g_state[i].load(std::memory_order_acquire) == kListed) ::unlink(g_paths[i].data());
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

int remember_temp_file(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;
  for (size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_state[i].compare_exchange_strong(expected, kClaimed)) continue;
    std::memcpy(g_paths[i].data(), path.c_str(), path.size() + 1);
    g_state[i].store(kListed, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void forget_temp_file(int slot) {
  if (slot < 0) return;
  g_state[static_cast<size_t>(slot)].store(kFree, std::memory_order_release);
}

void remove_temp_files_on_signals() {
  if (g_installed.exchange(true)) return;
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction action {};
    action.sa_handler = remove_and_die;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
  }
}

}  // namespace sculpt
