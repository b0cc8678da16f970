// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a pass over a grid's rows (or columns) split into a fixed number of bands run in
// parallel. Each band gathers what it finds on its own; the caller then takes the bands in order, so
// the result is the one a single pass from the top would give, whatever the threads' timing.
#pragma once

#include <tbb/parallel_for.h>

namespace origamic {

// Fixed, so that nothing a pass gathers depends on the machine's cores.
inline constexpr int kBands = 4;

/// Calls pass(band, begin, end) for [0, count) cut into kBands bands, in parallel.
template <class Pass>
void for_bands(int count, Pass&& pass) {
  tbb::parallel_for(0, kBands, [&](int band) {
    const long long begin = static_cast<long long>(count) * band / kBands;
    const long long end = static_cast<long long>(count) * (band + 1) / kBands;
    pass(band, static_cast<int>(begin), static_cast<int>(end));
  });
}

}  // namespace origamic
