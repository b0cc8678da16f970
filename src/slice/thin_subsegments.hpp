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

// The subsegments as merge_thin_subsegments works on them, pass after pass.
struct SubsegmentSet {
  std::vector<Subsegment> subsegments;
  std::vector<double> pixels;
  // Each one's pixels in row-major order, and whether it is thin: kept from pass to pass for the
  // subsegments no merge touched.
  std::vector<std::vector<std::pair<int, int>>> members;
  std::vector<std::uint8_t> thin;
};

// Where a surface runs steeper than 45 degrees across the slicing direction, its levels are strips
// narrower than W: each joins the neighbouring subsegment of its segment nearest in depth, pass after
// pass, until it is W wide or has no such neighbour. Levels thus merge into wider steps exactly where
// the surface is steep: the quantization adapts to it (seed Figure 4.6). `subsegment` is the map of
// their ids, renumbered to the merged ones.
void merge_thin_subsegments(const Grid<std::int32_t>& segment, double min_side_px, SubsegmentSet& set,
                            Grid<std::int32_t>& subsegment);

}  // namespace origamic
