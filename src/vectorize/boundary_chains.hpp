// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the raster plan's face boundaries traced as chains of pixel corners, the first step of
// its vectorization (exact_plan.cpp puts them in the exact arrangement). No CGAL here.
#pragma once

#include <cstdint>
#include <vector>

#include "origamic/grid.hpp"

namespace origamic::chains {

// Plan points on the pixel lattice in half-pixel units: u = 2 col, v = 2 row for pixel corners, odd
// for edge midpoints.
struct LatticePoint {
  int u, v;
};

/// The lattice's points in plan mm, as doubles.
struct LatticeScale {
  int rows_above_fold = 0;
  double px_mm = 0;

  double X(int u) const { return u * px_mm / 2; }
  double Y(int v) const { return (2 * rows_above_fold - v) * px_mm / 2; }
};

// One boundary between two faces of the raster plan, traced corner to corner with `left` on its
// left; it ends at junctions (three or more faces meet, or the sheet edge) or closes on itself.
struct Chain {
  std::int32_t left, right;
  std::vector<LatticePoint> corners;
};

/// The face map, with pixels whose centre fell outside the sheet (the partial last row or column)
/// given the face of the nearest pixel inside, so the arrangement covers the sheet to its edge.
Grid<std::int32_t> labels_inside_sheet(Grid<std::int32_t> labels);

/// Every boundary between two labels as chains, each edge of a pixel in one chain.
std::vector<Chain> trace_chains(const Grid<std::int32_t>& labels);

}  // namespace origamic::chains
