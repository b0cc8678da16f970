// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact_runs.hpp"

namespace origamic {

std::unique_lock<std::recursive_mutex> exact_run_lock() {
  static std::recursive_mutex one_at_a_time;
  return std::unique_lock(one_at_a_time);
}

}  // namespace origamic
