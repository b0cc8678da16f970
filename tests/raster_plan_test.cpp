// SPDX-License-Identifier: GPL-3.0-or-later
// The stages between the depth maps and the exact plan, each on its own: segmentation, the raster
// plan's edits (merging coplanar faces, aligning folds to their lines) and the tracing and
// simplifying of its boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <utility>
#include <vector>

#include "boundary_chains.hpp"
#include "helpers.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

using chains::Chain;
using chains::LatticePoint;

// A box on the floor against nothing: its front and its top are two smooth regions, apart from the
// back plane and the floor; every model pixel is in one of them, by the way it faces.
TEST(Segment, ABoxIsItsFrontAndItsTopBesideTheBackPlaneAndTheFloor) {
  const RayScene scene(test::box({60, 0, 20}, {150, 40, 50}));
  const RasterMaps maps = raster(scene, Sheet{}, RasterOptions{});
  const Segmentation s = segment(maps, SegmentOptions{});
  ASSERT_EQ(s.count, 4);
  std::set<std::int32_t> front, top;
  std::int64_t model = 0;
  for (int r = 0; r < maps.grid.rows; ++r)
    for (int c = 0; c < maps.grid.cols; ++c) {
      const HitKind kind = maps.kind(c, r);
      if (kind == HitKind::Back) EXPECT_EQ(s.segment(c, r), kBackSegment);
      if (kind == HitKind::Floor) EXPECT_EQ(s.segment(c, r), kFloorSegment);
      if (kind != HitKind::Model) continue;
      ++model;
      (std::abs(maps.d_mm(c, r) - 50) < 1e-6 ? front : top).insert(s.segment(c, r));
    }
  EXPECT_EQ(front.size(), 1u);
  EXPECT_EQ(top.size(), 1u);
  EXPECT_NE(*front.begin(), *top.begin());
  EXPECT_EQ(s.pixels[static_cast<std::size_t>(*front.begin())] + s.pixels[static_cast<std::size_t>(*top.begin())], model);
}

// Touching faces in one plane are one face; a face of that plane elsewhere stays itself, and the ids
// close up behind the merged one.
TEST(RasterPlanEdits, TouchingCoplanarFacesMergeAndIdsCloseUp) {
  RasterPlan s;
  s.face = Grid<std::int32_t>(10, 4, kBackFace);
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 10}, {Orientation::V, 10},
             {Orientation::H, 5}, {Orientation::V, 10}};
  for (int r = 0; r < 2; ++r) {
    s.face(0, r) = s.face(1, r) = 2;  // 4 px
    s.face(2, r) = 3;                 // 2 px, beside face 2: the same plane
    s.face(4, r) = 4;                 // 2 px, another plane
    s.face(7, r) = s.face(8, r) = 5;  // 4 px, the same plane, apart from 2 and 3
  }
  for (int c = 0; c < 10; ++c) s.face(c, 3) = kFloorFace;
  merge_coplanar_faces(s);
  ASSERT_EQ(s.faces.size(), 5u);
  EXPECT_EQ(s.face(2, 0), 2);
  EXPECT_EQ(s.faces[2].pixels, 6);
  EXPECT_EQ(s.face(4, 1), 3);
  EXPECT_EQ(s.faces[3].orientation, Orientation::H);
  EXPECT_EQ(s.face(8, 0), 4);
  EXPECT_EQ(s.faces[4].pixels, 4);
  EXPECT_EQ(s.faces[kBackFace].pixels, 40 - 12 - 10);  // less the faces and the floor
  EXPECT_EQ(s.faces[kFloorFace].pixels, 10);
}

// Seed §4.5 on the raster: an H face above a V face meets it on Y = h - d. A boundary two rows off
// that line moves, column by column, to the pixel edge nearest it, and the pixel counts follow.
TEST(RasterPlanEdits, AFoldMovesToThePixelEdgeNearestItsLine) {
  PixelGrid grid;
  grid.cols = 6, grid.rows = 12, grid.px_per_mm = 4, grid.rows_above_fold = 6;
  RasterPlan s;
  s.face = Grid<std::int32_t>(grid.cols, grid.rows, kFloorFace);
  // H(h) above V(d): their fold line Y = h - d = 0.3 mm lies 0.05 mm above the edge at Y = 0.25
  // between rows 4 and 5 (edges lie every 0.25 mm, Y = (6 - row) / 4).
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::H, 10.3}, {Orientation::V, 10}};
  for (int c = 0; c < grid.cols; ++c) {
    for (int r = 0; r < 3; ++r) s.face(c, r) = 2;   // the boundary drawn at Y = 0.75, between rows 2 and 3
    for (int r = 3; r < 10; ++r) s.face(c, r) = 3;
  }
  s.faces[2].pixels = 3 * grid.cols, s.faces[3].pixels = 7 * grid.cols, s.faces[1].pixels = 2 * grid.cols;
  align_folds_to_lines(s, grid, 1.0);
  for (int c = 0; c < grid.cols; ++c) {
    for (int r = 0; r < 5; ++r) EXPECT_EQ(s.face(c, r), 2) << c << ", " << r;
    for (int r = 5; r < 10; ++r) EXPECT_EQ(s.face(c, r), 3) << c << ", " << r;
  }
  EXPECT_EQ(s.faces[2].pixels, 5 * grid.cols);
  EXPECT_EQ(s.faces[3].pixels, 5 * grid.cols);
  // Farther off than the tolerance, a boundary stays where it is.
  RasterPlan far = s;
  far.faces[2].depth_mm = 13;  // its line is now 3 mm above: 12 rows
  align_folds_to_lines(far, grid, 1.0);
  EXPECT_EQ(far.face.values, s.face.values);
}

// Every pixel edge between two labels is in one chain, once; chains step one pixel edge at a time,
// have their two labels on their two sides, and end where three labels meet or at the sheet's edge.
TEST(BoundaryChains, EveryEdgeBetweenTwoFacesIsTracedOnce) {
  Grid<std::int32_t> labels(6, 5, kBackFace);
  for (int r = 1; r < 3; ++r) {
    labels(1, r) = labels(2, r) = 2;
    labels(3, r) = 3;
  }
  for (int c = 0; c < 6; ++c) labels(c, 4) = kFloorFace;
  labels(4, 3) = 2;  // an island of face 2, apart from the rest of it
  int edges = 0;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 6; ++c) {
      edges += c + 1 < 6 && labels(c, r) != labels(c + 1, r);
      edges += r + 1 < 5 && labels(c, r) != labels(c, r + 1);
    }
  const std::vector<Chain> chains = chains::trace_chains(labels);
  int traced = 0;
  std::set<std::pair<std::int32_t, std::int32_t>> pairs;
  for (const Chain& chain : chains) {
    ASSERT_GE(chain.corners.size(), 2u);
    EXPECT_NE(chain.left, chain.right);
    pairs.insert({std::min(chain.left, chain.right), std::max(chain.left, chain.right)});
    for (std::size_t i = 1; i < chain.corners.size(); ++i) {
      const LatticePoint a = chain.corners[i - 1], b = chain.corners[i];
      EXPECT_EQ(std::abs(a.u - b.u) + std::abs(a.v - b.v), 2) << "one pixel edge a step";
      // The pixels either side of the step, in the plan (Y up, rows down): `left` on its left.
      const double du = (b.u - a.u) / 2.0, dv = (b.v - a.v) / 2.0, mx = (a.u + b.u) / 4.0, my = (a.v + b.v) / 4.0;
      const int left_c = static_cast<int>(std::floor(mx + dv / 2)), left_r = static_cast<int>(std::floor(my - du / 2));
      const int right_c = static_cast<int>(std::floor(mx - dv / 2)), right_r = static_cast<int>(std::floor(my + du / 2));
      EXPECT_EQ(labels(left_c, left_r), chain.left);
      EXPECT_EQ(labels(right_c, right_r), chain.right);
      ++traced;
    }
  }
  EXPECT_EQ(traced, edges);
  EXPECT_EQ(pairs, (std::set<std::pair<std::int32_t, std::int32_t>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {2, 3}}));
}

// Douglas-Peucker over a chain's edge midpoints: a staircase within the tolerance of the straight
// line between its ends is that line; within a smaller one it keeps corners, none farther than the
// tolerance from what is drawn; with none it is the chain itself.
TEST(BoundaryChains, AStaircaseSimplifiesWithinItsTolerance) {
  Chain stairs{2, 3, {}};
  for (int k = 0; k <= 8; ++k) {  // eight steps of one pixel right and one down
    stairs.corners.push_back({2 * k, 2 * k});
    if (k < 8) stairs.corners.push_back({2 * k + 2, 2 * k});
  }
  const chains::LatticeScale lattice{10, 0.25};
  EXPECT_EQ(chains::simplified(stairs, lattice, 0).size(), stairs.corners.size());
  const std::vector<LatticePoint> straight = chains::simplified(stairs, lattice, 0.25);
  ASSERT_EQ(straight.size(), 2u);
  EXPECT_EQ(straight.front().u, 0);
  EXPECT_EQ(straight.back().u, 16);
  const std::vector<LatticePoint> close = chains::simplified(stairs, lattice, 0.05);
  EXPECT_GT(close.size(), 2u);
  EXPECT_EQ(close.front().u, stairs.corners.front().u);
  EXPECT_EQ(close.back().v, stairs.corners.back().v);
  // Every edge midpoint of the staircase lies within the tolerance of the polyline kept.
  auto distance = [&](double x, double y) {
    double nearest = 1e300;
    for (std::size_t k = 1; k < close.size(); ++k) {
      const double ax = lattice.X(close[k - 1].u), ay = lattice.Y(close[k - 1].v), bx = lattice.X(close[k].u),
                   by = lattice.Y(close[k].v), dx = bx - ax, dy = by - ay;
      const double t = std::clamp(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      nearest = std::min(nearest, std::hypot(ax + t * dx - x, ay + t * dy - y));
    }
    return nearest;
  };
  for (std::size_t i = 1; i < stairs.corners.size(); ++i) {
    const LatticePoint a = stairs.corners[i - 1], b = stairs.corners[i];
    EXPECT_LE(distance(lattice.X((a.u + b.u) / 2), lattice.Y((a.v + b.v) / 2)), 0.05 + 1e-12) << i;
  }
}

}  // namespace
}  // namespace origamic
