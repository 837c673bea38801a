#include "cli/progress_bar.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>

namespace sculpt::station::cli {
namespace {

// Only an async-signal-safe store happens in the handler (a lock-free
// atomic, so the working threads that read it in the progress callback do not
// race with it either).
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);
struct sigaction g_previous {};

extern "C" void on_sigint(int) {
  g_interrupted.store(true, std::memory_order_relaxed);
}

constexpr auto kRedraw = std::chrono::milliseconds(100);
constexpr int kBarWidth = 30;

}  // namespace

ProgressBar::ProgressBar(std::string command, CtrlC ctrl_c)
    : command_(std::move(command)),
      terminal_(isatty(STDERR_FILENO) != 0),
      progress_([this](double f) { return draw(f); }),
      start_(std::chrono::steady_clock::now()) {
  g_interrupted.store(false);
  handling_ = ctrl_c == CtrlC::kCancel;
  if (!handling_) return;
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process
  sigaction(SIGINT, &sa, &g_previous);
}

ProgressBar::~ProgressBar() {
  finish();
}

bool ProgressBar::cancelled() const {
  return g_interrupted.load(std::memory_order_relaxed) || progress_.cancelled();
}

int ProgressBar::cancel_exit() {
  finish();
  std::fprintf(stderr, "%s: cancelled\n", command_.c_str());
  return kCancelledExit;
}

void ProgressBar::finish() {
  if (terminal_ && drawn_) std::fputs("\r\033[K", stderr);
  drawn_ = false;
  // Writing follows: Ctrl-C goes back to the handler that removes the
  // temporaries and ends the process (base/temp_files.h).
  if (handling_) sigaction(SIGINT, &g_previous, nullptr);
  handling_ = false;
}

bool ProgressBar::draw(double fraction) {
  if (g_interrupted.load(std::memory_order_relaxed)) return false;
  const auto now = std::chrono::steady_clock::now();
  const int percent = int(fraction * 100.0);
  if (!terminal_) {
    const int decile = int(fraction * 10.0);
    if (decile > last_decile_) {
      last_decile_ = decile;
      std::fprintf(stderr, "%s: %d%%\n", command_.c_str(), decile * 10);
      std::fflush(stderr);
    }
    return true;
  }
  if (drawn_ && now - last_draw_ < kRedraw && fraction < 1.0) return true;
  last_draw_ = now;
  drawn_ = true;
  char bar[kBarWidth + 1];
  const int filled = int(fraction * kBarWidth);
  for (int i = 0; i < kBarWidth; ++i)
    bar[i] = i < filled ? '#' : '.';
  bar[kBarWidth] = '\0';
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  char eta[32] = "";
  // Below 1% the estimate is noise.
  if (fraction >= 0.01 && fraction < 1.0)
    std::snprintf(eta, sizeof eta, " %.0f s left", elapsed * (1.0 - fraction) / fraction);
  std::fprintf(stderr, "\r%s [%s] %3d%%%s\033[K", command_.c_str(), bar, percent, eta);
  std::fflush(stderr);
  return true;
}

}  // namespace sculpt::station::cli
