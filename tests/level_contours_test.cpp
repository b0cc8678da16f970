// SPDX-License-Identifier: GPL-3.0-or-later
// Where a slice's end is drawn between pixels (level_contours.hpp): on its level contour, at the
// fraction the depths at the two pixel centres give, and mirrored exactly.
#include "level_contours.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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
  RasterMaps mirrored_maps = s.maps;
  mirror_in_place(mirrored_maps);
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

// A model face's straight side seen against the back plane for 8 pixel rows, broken a quarter pixel
// into column 2, and below them the face's boundary with the back plane running on down the same
// pixel edges for 6 rows where the rays see no edge (its top folding back over the back plane): 4 x
// 14 pixels, the back plane in columns 0-1, the face in 2-3.
struct SideRunningOn {
  static constexpr int rows = 14, seen = 8;
  RasterMaps maps;
  RasterPlan plan;
  SideRunningOn() {
    maps = test::blank_maps({.cols = 4, .rows = rows, .px_per_mm = 4, .rows_above_fold = 0}, HitKind::Back);
    plan.face = Grid<std::int32_t>(4, rows, kBackFace);
    plan.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 10}};
    for (int r = 0; r < rows; ++r)
      for (int c = 2; c < 4; ++c) plan.face(c, r) = 2;
    for (int r = 0; r < seen; ++r) maps.break_right(1, r) = 0.75f;
  }
  BreaksAndLevels lines() const { return breaks_and_levels(maps, plan.face, plan.faces); }
};

TEST(LevelContours, AStraightModelEdgeRunsOnAlongTheBoundaryThatContinuesIt) {
  const SideRunningOn s;
  const BreaksAndLevels lines = s.lines();
  for (int r = 0; r < s.rows; ++r) EXPECT_EQ(lines.right(1, r), 0.75f) << "row " << r;
  EXPECT_EQ(drawn(lines.right), s.rows) << "on that line only";
  EXPECT_EQ(drawn(lines.below), 0);
  RasterMaps mirrored_maps = s.maps;
  mirror_in_place(mirrored_maps);
  const RasterPlan mirrored_plan = mirror_image(s.plan);
  const BreaksAndLevels mirrored = breaks_and_levels(mirrored_maps, mirrored_plan.face, mirrored_plan.faces);
  for (int r = 0; r < s.rows; ++r) EXPECT_EQ(mirrored.right(1, r), 0.25f) << "mirrored, row " << r;
  // Seen for 7 rows only, the edge may be a slice's end touching a crease: the rest stays.
  SideRunningOn shorter;
  shorter.maps.break_right(1, 7) = std::numeric_limits<float>::quiet_NaN();
  for (const int r : {7, 13}) EXPECT_TRUE(std::isnan(shorter.lines().right(1, r))) << "row " << r;
  // Near a third face the boundary stays on the pixel edge, as a slice's end does.
  SideRunningOn third;
  third.plan.face(2, 12) = kFloorFace;
  const BreaksAndLevels near = third.lines();
  EXPECT_EQ(near.right(1, 10), 0.75f);
  for (const int r : {11, 12, 13}) EXPECT_TRUE(std::isnan(near.right(1, r))) << "row " << r;
}

// Between two straight edges on one column of pixel edges, a gap takes their fraction if they
// agree, and is left to the junction between them if not: 30 rows, edges of 8 rows at the top and
// the bottom, 14 rows between.
TEST(LevelContours, AGapBetweenTwoStraightEdgesTakesTheirFractionOnlyIfTheyAgree) {
  SideRunningOn s;
  constexpr int rows = 30;
  s.maps = test::blank_maps({.cols = 4, .rows = rows, .px_per_mm = 4, .rows_above_fold = 0}, HitKind::Back);
  s.plan.face = Grid<std::int32_t>(4, rows, kBackFace);
  for (int r = 0; r < rows; ++r)
    for (int c = 2; c < 4; ++c) s.plan.face(c, r) = 2;
  for (int r = 0; r < 8; ++r) s.maps.break_right(1, r) = s.maps.break_right(1, rows - 1 - r) = 0.75f;
  for (int r = 8; r < rows - 8; ++r) EXPECT_EQ(s.lines().right(1, r), 0.75f) << "row " << r;
  for (int r = rows - 8; r < rows; ++r) s.maps.break_right(1, r) = 0.5f;
  const BreaksAndLevels apart = s.lines();
  for (int r = 8; r < rows - 8; ++r) EXPECT_TRUE(std::isnan(apart.right(1, r))) << "row " << r;
  EXPECT_EQ(apart.right(1, rows - 1), 0.5f);
}

}  // namespace
}  // namespace origamic
