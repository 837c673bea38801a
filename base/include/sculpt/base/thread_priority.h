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
// Niceness only shares a core out: a dab's sculpting and meshing still
// had a third of the cores beside llvmpipe's threads at niceness 5, and the
// demo's first 66-voxel ball took 16-22 ms from report to mesh where the
// same work alone takes 8. The threads a dab's latency runs through are
// made real-time instead (SCHED_FIFO, below the force loop's priority):
// they run whenever they have work and sleep otherwise, so drawing gets
// the cores back between dabs. The kernel keeps a twentieth of each second
// for ordinary threads (sched_rt_runtime_us), so a flood of dabs slows the
// frames but cannot stop them. Threads a real-time thread starts are not
// real-time (SCHED_RESET_ON_FORK): a panel's long job started from the
// sculpting thread stays behind drawing.
//
// Linux only (/proc/self/task, setpriority and sched_setscheduler on thread
// ids). Thread safe.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sculpt {

/// The kernel's ids of this process's threads now running, ascending; empty
/// when /proc cannot be read.
std::vector<int> process_thread_ids();

/// The ids of this process's threads named `name` (pthread_setname_np,
/// at most 15 characters), ascending.
std::vector<int> threads_named(std::string_view name);

/// The ids in `now` that are not in `before` (both ascending): the threads
/// started in between.
std::vector<int> threads_started(std::span<const int> before, std::span<const int> now);

/// Makes the threads `ids` (kernel thread ids of this process) at least as
/// nice as `nice` (0..19); a thread already nicer keeps its niceness, and one
/// that ended meanwhile is skipped. Returns how many threads were changed.
int make_threads_nicer(std::span<const int> ids, int nice);

/// Puts the threads `ids` (kernel thread ids of this process) under
/// SCHED_FIFO at `priority` (1..99), the threads they start afterwards not.
/// Returns "" when every thread still running was changed, else why one was
/// not (the system's reason, e.g. no CAP_SYS_NICE or rtprio limit).
std::string make_threads_realtime(std::span<const int> ids, int priority);

/// A thread's scheduling policy (SCHED_OTHER, SCHED_FIFO, ...) and
/// real-time priority (0 for ordinary threads).
struct ThreadScheduling {
  int policy = 0;
  int priority = 0;
  bool operator==(const ThreadScheduling&) const = default;
};

/// The scheduling of thread `id` of this process (0: the calling thread).
ThreadScheduling thread_scheduling(int id);
/// The calling thread's scheduling.
ThreadScheduling this_thread_scheduling();
/// Gives the calling thread `s`, the threads it starts afterwards ordinary
/// scheduling; false when the system refused (a real-time policy needs a
/// privilege that leaving one does not).
bool set_this_thread_scheduling(const ThreadScheduling& s);

/// The calling thread's kernel id.
int this_thread_id();

/// The niceness of thread `id` (of this process), or -100 when it cannot be
/// read (it ended).
int thread_niceness(int id);

}  // namespace sculpt
