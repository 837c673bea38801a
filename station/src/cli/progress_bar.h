#pragma once
// Progress of one long command on stderr, and Ctrl-C as its cancel.
//
// On a terminal: one line redrawn at most ten times a second,
// "distance [#####.....] 50% 12 s left". Elsewhere (a pipe, a log): a plain
// line "distance: 0%" at the first report, then at most one per 10%. SIGINT
// (Ctrl-C) sets a flag that the core's progress callback returns; the
// command then discards its work, writes nothing, prints "distance:
// cancelled" and exits with kCancelledExit. A second Ctrl-C ends the process
// at once (the handler resets itself), and so does one after finish(), once
// the command is writing.

#include <chrono>
#include <string>

#include "sculpt/core/util/progress.h"

namespace sculpt::station::cli {

/// Exit code of a command cancelled by Ctrl-C (128 + SIGINT, as shells do).
inline constexpr int kCancelledExit = 130;

class ProgressBar {
 public:
  /// What Ctrl-C does while the bar is up.
  enum class CtrlC {
    kCancel,   ///< sets the flag that the progress callback returns
    kDefault,  ///< left as it was (work that cannot stop early: replay)
  };
  /// Installs the SIGINT handler (with kCancel) until finish(); `command`
  /// names the lines ("distance").
  explicit ProgressBar(std::string command, CtrlC ctrl_c = CtrlC::kCancel);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// For the core's long functions.
  core::Progress* progress() { return &progress_; }
  /// True once Ctrl-C was pressed (even between reports) or the work was
  /// cancelled. Check it before writing any output.
  bool cancelled() const;
  /// Clears the bar, prints "<command>: cancelled" and returns kCancelledExit.
  int cancel_exit();
  /// Clears the bar and gives SIGINT back to the previous handler (the one
  /// that removes temporaries and ends the process): call it when the work
  /// is done, before writing.
  void finish();

 private:
  bool draw(double fraction);

  std::string command_;
  bool terminal_;
  core::Progress progress_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  int last_decile_ = -1;
  bool drawn_ = false;
  bool handling_ = true;  // our SIGINT handler is installed
};

}  // namespace sculpt::station::cli
