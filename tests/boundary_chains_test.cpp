// SPDX-License-Identifier: GPL-3.0-or-later
// The raster plan's boundaries traced into chains and simplified (boundary_chains.hpp).
#include "boundary_chains.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <utility>
#include <vector>

#include "chain_points.hpp"
#include "origamic/grid.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

using chains::Chain;
using chains::LatticePoint;

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
      const int right_c = static_cast<int>(std::floor(mx - dv / 2)),
                right_r = static_cast<int>(std::floor(my + du / 2));
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
  const Grid<float> unknown;
  const chains::PictureBreaks no_breaks{unknown, unknown};
  const auto simplified = [&](double tolerance_mm) {
    std::vector<LatticePoint> points;
    for (const chains::ChainPoint& p :
         chains::simplified(stairs, lattice, no_breaks, {tolerance_mm, tolerance_mm}).points)
      points.push_back(p.lattice);
    return points;
  };
  EXPECT_EQ(simplified(0).size(), stairs.corners.size());
  const std::vector<LatticePoint> straight = simplified(0.25);
  ASSERT_EQ(straight.size(), 2u);
  EXPECT_EQ(straight.front().u, 0);
  EXPECT_EQ(straight.back().u, 16);
  const std::vector<LatticePoint> close = simplified(0.05);
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
