// SPDX-License-Identifier: GPL-3.0-or-later
// Segmentation (seed §4.2) on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>

#include "helpers.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"

namespace origamic {
namespace {

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
      if (kind == HitKind::Back) {
        EXPECT_EQ(s.segment(c, r), kBackSegment);
      }
      if (kind == HitKind::Floor) {
        EXPECT_EQ(s.segment(c, r), kFloorSegment);
      }
      if (kind != HitKind::Model) continue;
      ++model;
      (std::abs(maps.d_mm(c, r) - 50) < 1e-6 ? front : top).insert(s.segment(c, r));
    }
  EXPECT_EQ(front.size(), 1u);
  EXPECT_EQ(top.size(), 1u);
  EXPECT_NE(*front.begin(), *top.begin());
  EXPECT_EQ(s.pixels[static_cast<std::size_t>(*front.begin())] + s.pixels[static_cast<std::size_t>(*top.begin())],
            model);
}

}  // namespace
}  // namespace origamic
