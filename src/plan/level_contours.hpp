// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: where a slice ends (seed §4.3), a level contour of the model's surface, to a fraction of
// a pixel. No CGAL here.
#pragma once

#include <cstdint>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

/// The picture's breaks (RasterMaps::break_right, break_below) and, between neighbouring pixels of
/// two slices in one orientation that no break parts, where the model's depth (d for V slices, h for
/// H) crosses the level halfway between the two slices' planes: the fraction of the
/// way from the first centre to the second, to 1/1024 as the breaks are, found by linear
/// interpolation of the depths at the two centres; NaN elsewhere. A cut drawn there follows the
/// contour, not the pixels' staircase.
struct BreaksAndLevels {
  Grid<float> right;  // between (col, row) and (col + 1, row)
  Grid<float> below;  // between (col, row) and (col, row + 1)
};
BreaksAndLevels breaks_and_levels(const RasterMaps& maps, const Grid<std::int32_t>& face,
                                  const std::vector<RasterFace>& faces);

}  // namespace origamic
