// SPDX-License-Identifier: MIT
#pragma once

#include <string>

namespace tumble::experiments {

// "CPU model, N logical cores" from /proc/cpuinfo, for benchmark reports.
std::string machine_description();

// The thread count to run with: `requested`, or every core of the machine
// for 0; 1 in a build without OpenMP (with a note on stderr if more were
// asked); tumble::Error (--threads) for more than the machine's cores.
// Every command defaults to 1 thread: sweeps, test suites and peer
// benchmarks run several tumble processes side by side, and threads that
// wait at each step's barriers for a core held by another process lose
// more than they gain (docs/BENCHMARKS.md "Threads").
int resolve_threads(int requested);

// How OpenMP binds the threads to cores (OMP_PROC_BIND, with OMP_PLACES):
// "none" (OpenMP's default: threads may move between cores) or the policy,
// "close", "spread", "master" or "true". For benchmark reports: two threads
// bound to two cores ran the long drum 1 to 3.5 % faster than unbound ones on
// an Intel Xeon (studies/performance/LOG.md "Threads bound to cores").
std::string thread_binding();

}  // namespace tumble::experiments
