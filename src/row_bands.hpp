// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a pass over a grid's rows (or columns) split into a fixed number of bands run on all cores. Each band
// gathers what it finds on its own; the caller then takes the bands in order, so the result is the
// one a single pass from the top would give, whatever the cores' timing.
#pragma once

#include <vector>

#include <tbb/parallel_for.h>

namespace origamic {

inline constexpr int kBands = 4;

/// Calls pass(band, row_begin, row_end) for rows [0, rows) in kBands bands, concurrently.
template <class Pass>
void for_row_bands(int rows, Pass&& pass) {
  tbb::parallel_for(0, kBands, [&](int band) {
    const long long begin = static_cast<long long>(rows) * band / kBands;
    const long long end = static_cast<long long>(rows) * (band + 1) / kBands;
    pass(band, static_cast<int>(begin), static_cast<int>(end));
  });
}

}  // namespace origamic
