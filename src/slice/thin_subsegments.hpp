// SPDX-License-Identifier: GPL-3.0-or-later
// Slicing's levels merged where they are thinner than W (seed Figure 4.6), for slice.cpp.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/oa.hpp"

namespace origamic {

struct Subsegment {
  std::int32_t segment = 0;
  double depth_mm = 0;
  Orientation orientation = Orientation::V;
};

// Subsegments and their sizes in pixels, one entry each.
struct SizedSubsegments {
  std::vector<Subsegment> subsegments;
  std::vector<double> pixels;
};

// Where a surface runs steeper than 45 degrees across the slicing direction, its levels are strips
// narrower than W: each joins the neighbouring subsegment of its segment nearest in depth, pass after
// pass, until it is W wide or has no such neighbour. Levels thus merge into wider steps exactly where
// the surface is steep: the quantization adapts to it (seed Figure 4.6). A level is thin where its
// oriented box has a side under min_side_px, and, with `by_widest_disc`, also where the widest disc
// it holds is under it (disc_width.hpp); such a level joins only a neighbour of its orientation.
// Returns the merged subsegments; `subsegment`, the map of their ids, is renumbered to them.
std::vector<Subsegment> merge_thin_subsegments(const Grid<std::int32_t>& segment, double min_side_px,
                                               bool by_widest_disc, SizedSubsegments sized,
                                               Grid<std::int32_t>& subsegment);

}  // namespace origamic
