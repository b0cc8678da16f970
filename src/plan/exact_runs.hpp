// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: one exact run at a time per process. The exact numbers are built without thread safety
// (exact_kernel.hpp: with it, every lazy number paid for a std::call_once, which tripled the plan's
// time; without it their reference counts and caches are unguarded), so every public call that
// makes or frees them (design, add_supports, build_plan, ExactPlan, analyze_plan) holds this lock on
// its caller's thread: two threads calling design() wait for each other instead of racing. It is
// recursive (design calls the others); the worker threads of a run never take it (they read what
// the run made, under ExactPlan's own lock). So a run must not be started from a TBB task of
// another run's (its thread could wait for the lock its own task holds).
#pragma once

#include <mutex>

namespace origamic {

std::unique_lock<std::recursive_mutex> exact_run_lock();

}  // namespace origamic
