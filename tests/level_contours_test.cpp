// SPDX-License-Identifier: GPL-3.0-or-later
// Where a slice's end is drawn between pixels (level_contours.hpp): on its level contour, at the
// fraction the depths at the two pixel centres give, and mirrored exactly.
#include "level_contours.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "helpers.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "support_mirror.hpp"

namespace origamic {
namespace {

constexpr int kCols = 8, kRows = 4;

// A leaning model face over the whole grid, d = 10 + 1.3 col + 0.1 row, sliced into two V slices
// of one segment: columns 0-3 at d = 12 and 4-7 at d = 16.
struct Sliced {
  RasterMaps maps;
  RasterPlan plan;
};
Sliced two_slices() {
  Sliced s;
  s.maps = test::blank_maps({.cols = kCols, .rows = kRows, .px_per_mm = 4, .rows_above_fold = 2}, HitKind::Model);
  RasterMaps& maps = s.maps;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) maps.d_mm(c, r) = 10 + 1.3 * c + 0.1 * r;
  s.plan.face = Grid<std::int32_t>(kCols, kRows, 2);
  for (int r = 0; r < kRows; ++r)
    for (int c = 4; c < kCols; ++c) s.plan.face(c, r) = 3;
  s.plan.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 12}, {Orientation::V, 16}};
  return s;
}

int drawn(const Grid<float>& at) {
  int n = 0;
  for (const float t : at.values) n += !std::isnan(t);
  return n;
}

// The slicing cut between the two at a level above every depth on the nearer side, 14.2 at column
// 3, row 3, and below every depth on the farther, 15.2 at column 4, row 0: halfway, 14.7.
TEST(LevelContours, ASlicesEndCrossesEachPixelEdgeWhereTheDepthCrossesItsLevel) {
  const Sliced s = two_slices();
  const BreaksAndLevels lines = breaks_and_levels(s.maps, s.plan.face, s.plan.faces);
  for (int r = 0; r < kRows; ++r) {
    const double a = 10 + 1.3 * 3 + 0.1 * r;
    EXPECT_EQ(lines.right(3, r), static_cast<float>(std::round((14.7 - a) / 1.3 * 1024) / 1024)) << "row " << r;
  }
  EXPECT_EQ(drawn(lines.right), kRows) << "only between the two slices";
  EXPECT_EQ(drawn(lines.below), 0);
  // A break the rays found stays as it is; a third face beside the pair keeps it on the pixel edge.
  Sliced other = two_slices();
  other.maps.break_right(3, 0) = 0.25f;
  other.plan.face(4, 3) = kFloorFace;
  other.plan.faces[kFloorFace].orientation = Orientation::H;
  const BreaksAndLevels kept = breaks_and_levels(other.maps, other.plan.face, other.plan.faces);
  EXPECT_EQ(kept.right(3, 0), 0.25f);
  EXPECT_TRUE(std::isnan(kept.right(3, 2))) << "the floor's pixel is beside the pair below it";
  EXPECT_TRUE(std::isnan(kept.right(3, 3))) << "nor between a slice and the floor";
  EXPECT_FALSE(std::isnan(kept.right(3, 1)));
}

TEST(LevelContours, TheMirrorImageGetsOneMinusEachFraction) {
  const Sliced s = two_slices();
  const BreaksAndLevels lines = breaks_and_levels(s.maps, s.plan.face, s.plan.faces);
  const RasterMaps mirrored_maps = mirror_image(s.maps);
  const RasterPlan mirrored_plan = mirror_image(s.plan);
  const BreaksAndLevels mirrored = breaks_and_levels(mirrored_maps, mirrored_plan.face, mirrored_plan.faces);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c + 1 < kCols; ++c) {
      const float t = lines.right(c, r), m = mirrored.right(kCols - 2 - c, r);
      EXPECT_EQ(std::isnan(t), std::isnan(m));
      if (!std::isnan(t)) {
        EXPECT_EQ(m, 1 - t) << "column " << c << ", row " << r;
      }
    }
}

}  // namespace
}  // namespace origamic
