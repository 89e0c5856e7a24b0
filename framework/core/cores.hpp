// How many threads a computation should use on a machine it may share with other processes.
#pragma once

namespace dtsl {

/// The cores not busy right now: the online cores minus the other processes running at this instant
/// (the kernel's count of runnable tasks, /proc/loadavg), at least 1. A machine whose other core is
/// taken gets 1, where OpenMP's default (every core) would make its threads wait on each other at every
/// barrier while the other process holds a core. The online core count where /proc is missing.
int free_cores();

/// Sets the thread count of every later OpenMP region of this process (no-op without OpenMP).
void set_threads(int threads);

/// The thread count later OpenMP regions use (1 without OpenMP).
int current_threads();

/// The threads this process has now (/proc/self/task; 1 where /proc is missing). More than one before
/// a fork means the child must not use OpenMP with more than one thread: GNU libgomp keeps its thread
/// pool across parallel regions, the pool's threads do not exist in a forked child, and the child's
/// next parallel region waits for them forever (an embedding program such as Python that has already
/// run a parallel region, or that has threads of its own, is such a parent).
int process_threads();

}  // namespace dtsl
