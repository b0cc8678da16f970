// SPDX-License-Identifier: GPL-3.0-or-later
// The four neighbours of a pixel, as (column, row) steps: left, right, up, down.
#pragma once

namespace origamic {

inline constexpr int kFourNeighbours[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};

}  // namespace origamic
