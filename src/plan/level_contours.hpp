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

/// Where the chains between pixels are drawn: between (col, row) and (col + 1, row) (right) and
/// (col, row + 1) (below), the fraction of the way from the first centre to the second, to 1/1024
/// and never 0 or 1; NaN where a chain there stays on the pixel edge.
struct BreaksAndLevels {
  Grid<float> right;
  Grid<float> below;
};

/// The picture's breaks (RasterMaps::break_right, break_below) and, where no break parts two
/// neighbouring pixels of two slices in one orientation (supports and holes aside), their level
/// contour: where the model's depth (d between V slices, h between H slices) crosses, linearly
/// between the two centres, the level the slicing cut them at, taken as halfway between the highest
/// depth on the nearer slice's side of their boundary and the lowest on the farther's (none where
/// those overlap: slices of two segments). Where a boundary with no break and no level runs on down
/// a column of pixel edges from a straight model edge (8 edges or more the picture breaks across at
/// one fraction, on one side of it, or on both at the same), it takes that fraction: a box's top
/// folding back over the back plane's pixels keeps the box's side. Within a pixel of a third face
/// the chain stays on the pixel edge, where the other lines end. A mirrored plan (maps and face map)
/// gets 1 - t exactly.
/// \pre face has the maps' size and its ids index faces.
BreaksAndLevels breaks_and_levels(const RasterMaps& maps, const Grid<std::int32_t>& face,
                                  const std::vector<RasterFace>& faces);

}  // namespace origamic
