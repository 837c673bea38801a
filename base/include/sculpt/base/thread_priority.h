#pragma once
// Which of the station's threads yields when the cores are short. Under the
// kernel's fair scheduler a thread's share of a busy core follows its
// niceness (each step about 1.25 times less weight), so the work a sculptor
// waits for longest can be put ahead of work that can wait: a frame drawn
// while a big dab is still meshing shows the old surface anyway, and a
// software renderer (Mesa's llvmpipe) would otherwise take half the cores
// from the mesher at every frame.
//
// Raising a thread's niceness needs no privilege; lowering it again does, so
// a thread is made nicer only once the threads it would pass it on to (new
// threads inherit their creator's niceness) are started.
//
// Linux only (/proc/self/task, setpriority on thread ids). Thread safe.

#include <span>
#include <vector>

namespace sculpt {

/// The kernel's ids of this process's threads now running, ascending; empty
/// when /proc cannot be read.
std::vector<int> process_thread_ids();

/// The ids in `now` that are not in `before` (both ascending): the threads
/// started in between.
std::vector<int> threads_started(std::span<const int> before, std::span<const int> now);

/// Makes the threads `ids` (kernel thread ids of this process) at least as
/// nice as `nice` (0..19); a thread already nicer keeps its niceness, and one
/// that ended meanwhile is skipped. Returns how many threads were changed.
int make_threads_nicer(std::span<const int> ids, int nice);

/// The calling thread's kernel id.
int this_thread_id();

/// The niceness of thread `id` (of this process), or -100 when it cannot be
/// read (it ended).
int thread_niceness(int id);

}  // namespace sculpt
