// SPDX-License-Identifier: GPL-3.0-or-later
// The raster plan's edits (slice.hpp, raster_plan_edits.cpp), each on its own: coplanar faces
// merged, folds moved to their lines.
#include "raster_plan_edits.hpp"

#include <gtest/gtest.h>

#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

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
  s = merge_coplanar_faces(std::move(s));
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
  s = align_folds_to_lines(std::move(s), grid, 1.0);
  for (int c = 0; c < grid.cols; ++c) {
    for (int r = 0; r < 5; ++r) EXPECT_EQ(s.face(c, r), 2) << c << ", " << r;
    for (int r = 5; r < 10; ++r) EXPECT_EQ(s.face(c, r), 3) << c << ", " << r;
  }
  EXPECT_EQ(s.faces[2].pixels, 5 * grid.cols);
  EXPECT_EQ(s.faces[3].pixels, 5 * grid.cols);
  // Farther off than the tolerance, a boundary stays where it is.
  RasterPlan far = s;
  far.faces[2].depth_mm = 13;  // its line is now 3 mm above: 12 rows
  far = align_folds_to_lines(std::move(far), grid, 1.0);
  EXPECT_EQ(far.face.values, s.face.values);
}

}  // namespace
}  // namespace origamic
