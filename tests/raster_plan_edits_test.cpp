// SPDX-License-Identifier: GPL-3.0-or-later
// The raster plan's edits (slice.hpp, raster_plan_edits.cpp), each on its own: coplanar faces
// merged, folds moved to their lines.
#include "raster_plan_edits.hpp"

#include <gtest/gtest.h>

#include <optional>

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

// A sheet three pixels wide at 4 px a mm.
PixelGrid three_columns(int rows, int rows_above_fold) {
  PixelGrid grid;
  grid.cols = 3, grid.rows = rows, grid.px_per_mm = 4, grid.rows_above_fold = rows_above_fold;
  return grid;
}

// A V face between an H face above and the floor below, 16 rows tall (4 px a mm, Y = (F - row) / 4
// at the edge above row `row`, F = grid.rows_above_fold): H(4) rows 0 to F - 9, V(2) the next 16
// rows (folds at Y = 2 and -2), the floor below. At F = 20: H rows 0-11, V rows 12-27.
RasterPlan v_between_h_and_floor(const PixelGrid& grid) {
  const int top = grid.rows_above_fold - 8;
  RasterPlan s;
  s.face = Grid<std::int32_t>(grid.cols, grid.rows, kFloorFace);
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::H, 4}, {Orientation::V, 2}};
  for (int c = 0; c < grid.cols; ++c) {
    for (int r = 0; r < top; ++r) s.face(c, r) = 2;
    for (int r = top; r < top + 16; ++r) s.face(c, r) = 3;
  }
  s.faces[1].pixels = (grid.rows - top - 16) * grid.cols, s.faces[2].pixels = top * grid.cols;
  s.faces[3].pixels = 16 * grid.cols;
  return s;
}

// Every column of a plan of v_between_h_and_floor's faces: the H face's rows above h_end, the V
// face's above v_end, the floor's below.
void expect_columns(const RasterPlan& plan, const PixelGrid& grid, int h_end, int v_end) {
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r)
      EXPECT_EQ(plan.face(c, r), r < h_end ? 2 : r < v_end ? 3 : kFloorFace) << c << ", " << r;
}

// A plane moved carries its folds: the V face half a millimetre forward meets the H face and the
// floor 2 rows lower, giving the H face its top 2 rows and taking the floor's 2; its height stays.
TEST(RasterPlanEdits, APlaneMovedTakesItsFoldsToItsNewLines) {
  const PixelGrid grid = three_columns(40, 20);
  const RasterPlan s = v_between_h_and_floor(grid);
  const std::optional<RasterPlan> moved = move_plane(s, grid, 3, 2.5, 0.3, 1);
  ASSERT_TRUE(moved.has_value());
  EXPECT_EQ(moved->faces[3].depth_mm, 2.5);
  expect_columns(*moved, grid, 14, 30);
  EXPECT_EQ(moved->faces[2].pixels, 14 * grid.cols);
  EXPECT_EQ(moved->faces[3].pixels, 16 * grid.cols);
  EXPECT_EQ(moved->faces[kFloorFace].pixels, 10 * grid.cols);
  // Back to 2 mm, the same plan again.
  const std::optional<RasterPlan> back = move_plane(*moved, grid, 3, 2, 0.3, 1);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->face.values, s.face.values);
  EXPECT_EQ(back->faces[3].depth_mm, 2);
  for (std::size_t f = 0; f < s.faces.size(); ++f) EXPECT_EQ(back->faces[f].pixels, s.faces[f].pixels) << f;
  // The H face half a millimetre higher: its fold with the V face rises 2 rows, and the V face
  // takes its rows 10-11.
  const std::optional<RasterPlan> raised = move_plane(s, grid, 2, 4.5, 0.3, 1);
  ASSERT_TRUE(raised.has_value());
  expect_columns(*raised, grid, 10, 28);
  // A fold that would leave the sheet: the V face 6 mm deep meets the floor 43 rows down.
  EXPECT_FALSE(move_plane(s, grid, 3, 6, 0.3, 1).has_value());
  // Told the face's columns, the same move; told fewer, its folds move in those only.
  const std::optional<RasterPlan> told = move_plane(s, grid, 3, 2.5, 0.3, 1, std::pair{0, grid.cols - 1});
  ASSERT_TRUE(told.has_value());
  EXPECT_EQ(told->face.values, moved->face.values);
  const std::optional<RasterPlan> first_column = move_plane(s, grid, 3, 2.5, 0.3, 1, std::pair{0, 0});
  ASSERT_TRUE(first_column.has_value());
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r) EXPECT_EQ(first_column->face(c, r), (c == 0 ? *moved : s).face(c, r));
}

// The face moved gives rows at one fold as it takes as many at the other: its run is counted as the
// move leaves it. H(4) rows 0-21, V(2) rows 22-37 (16 rows), the floor below; the V face half a
// millimetre back takes rows 20-21 and gives rows 36-37, keeping 16 (14 beyond the rows it gives on
// the plan before the move). Its run was 16 before too: asked to keep 17, it is narrower than that
// already, and the move leaves it no narrower.
TEST(RasterPlanEdits, AFaceMovedKeepsItsRunAsTheMoveLeavesIt) {
  const PixelGrid grid = three_columns(60, 30);
  const RasterPlan s = v_between_h_and_floor(grid);
  const std::optional<RasterPlan> moved = move_plane(s, grid, 3, 1.5, 0.3, 16);
  ASSERT_TRUE(moved.has_value());
  expect_columns(*moved, grid, 20, 36);
  const std::optional<RasterPlan> narrow_before = move_plane(s, grid, 3, 1.5, 0.3, 17);
  ASSERT_TRUE(narrow_before.has_value());
  EXPECT_EQ(narrow_before->face.values, moved->face.values);
}

// A face whose run in a column is shorter than `min_run_px` before the move is a place narrower than
// W already: it may give rows there, keeping one at least. H(4) rows 0-11 (12 rows): the V face half
// a millimetre back takes its rows 10-11.
TEST(RasterPlanEdits, AFaceNarrowerThanTheRunAlreadyMayGiveRows) {
  const PixelGrid grid = three_columns(40, 20);
  const RasterPlan s = v_between_h_and_floor(grid);
  EXPECT_FALSE(move_plane(s, grid, 3, 1.5, 0.3, 12).has_value());                // 12 rows before: it would keep 10
  const std::optional<RasterPlan> moved = move_plane(s, grid, 3, 1.5, 0.3, 13);  // 12 of 13 before
  ASSERT_TRUE(moved.has_value());
  expect_columns(*moved, grid, 10, 26);
  // It keeps one row at least, or gives its whole run: of an H face of 6 rows (6-11), the V face
  // 1.25 mm back takes 5 and leaves row 6; 1.5 mm back it takes all 6 and meets the back plane.
  RasterPlan thin = s;
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < 6; ++r) thin.face(c, r) = kBackFace;
  thin.faces[2].pixels = 6 * grid.cols;
  const std::optional<RasterPlan> one_left = move_plane(thin, grid, 3, 0.75, 0.3, 13);
  ASSERT_TRUE(one_left.has_value());
  for (int c = 0; c < grid.cols; ++c) {
    EXPECT_EQ(one_left->face(c, 6), 2);
    EXPECT_EQ(one_left->face(c, 7), 3);
  }
  const std::optional<RasterPlan> none_left = move_plane(thin, grid, 3, 0.5, 0.3, 13);
  ASSERT_TRUE(none_left.has_value());
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r)
      EXPECT_EQ(none_left->face(c, r), r < 6 ? kBackFace : r < 22 ? 3 : kFloorFace) << c << ", " << r;
  EXPECT_EQ(none_left->faces[2].pixels, 0);
  EXPECT_EQ(none_left->faces[3].pixels, 16 * grid.cols);
  // 1.75 mm back its line lies a row past the H face's run: the V face takes the 6 rows it has and
  // meets the back plane a row below the line, its fold with the floor 7 rows up.
  const std::optional<RasterPlan> past = move_plane(thin, grid, 3, 0.25, 0.3, 13);
  ASSERT_TRUE(past.has_value());
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r)
      EXPECT_EQ(past->face(c, r), r < 6 ? kBackFace : r < 21 ? 3 : kFloorFace) << c << ", " << r;
  EXPECT_EQ(past->faces[3].pixels, 15 * grid.cols);
}

// A V(2) strip 2 rows deep between H(4) above and H(3.5) below (at 4 px a mm, F = 20: H(4) rows
// 0-11, the strip rows 12-13, folds at Y = 2 and 1.5, H(3.5) the rows below).
RasterPlan strip_between_two_h_faces(const PixelGrid& grid) {
  RasterPlan s;
  s.face = Grid<std::int32_t>(grid.cols, grid.rows, 4);
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::H, 4}, {Orientation::V, 2}, {Orientation::H, 3.5}};
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < 14; ++r) s.face(c, r) = r < 12 ? 2 : 3;
  s.faces[2].pixels = 12 * grid.cols, s.faces[3].pixels = 2 * grid.cols, s.faces[4].pixels = 26 * grid.cols;
  return s;
}

// A face moved whose own run ends short of its new line at one fold while its other fold moves too
// does not move: a V strip 2 rows deep between H(4) and H(3.5), 0.75 mm forward, would give H(3.5)
// its 2 rows and take 3 of H(4)'s, its fold with H(3.5) a row off the line.
TEST(RasterPlanEdits, AFaceFoldedOnBothSidesDoesNotGiveItsWholeRunAtOne) {
  const PixelGrid grid = three_columns(40, 20);
  const RasterPlan s = strip_between_two_h_faces(grid);
  EXPECT_FALSE(move_plane(s, grid, 3, 1.25, 0.3, 1).has_value());
  EXPECT_FALSE(move_plane(s, grid, 3, 1.0, 0.3, 1).has_value());
  // A quarter of a millimetre back, both folds move down a row and the strip keeps its 2 rows.
  const std::optional<RasterPlan> back = move_plane(s, grid, 3, 2.25, 0.3, 1);
  ASSERT_TRUE(back.has_value());
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r) EXPECT_EQ(back->face(c, r), r < 13 ? 2 : r < 15 ? 3 : 4) << c << ", " << r;
  // Nor does a face between two parts of the face moved give them its run: with H(4) below the
  // strip too (a cut there, its fold line 2 rows up), H(4) 1 mm lower would take the strip's rows
  // from above and meet itself below them.
  RasterPlan between = s;
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 14; r < grid.rows; ++r) between.face(c, r) = 2;
  between.faces[2].pixels += 26 * grid.cols, between.faces[4].pixels = 0;
  EXPECT_FALSE(move_plane(between, grid, 2, 3, 0.3, 1).has_value());
}

// A fold moves only where the face giving rows keeps `min_run_px` of them (a tread no narrower), and
// only where no face is parted; a boundary off its fold line is no fold and stays.
TEST(RasterPlanEdits, APlaneMovesOnlyWhereTheFacesGivingRowsKeepTheirRunAndStayWhole) {
  const PixelGrid grid = three_columns(40, 20);
  const RasterPlan s = v_between_h_and_floor(grid);
  // Half a millimetre back, the V face's folds rise 2 rows: it takes rows 10-11 of the H face,
  // which keeps 10, and gives rows 26-27 to the floor.
  EXPECT_TRUE(move_plane(s, grid, 3, 1.5, 0.3, 10).has_value());   // the H face keeps 10 rows
  EXPECT_FALSE(move_plane(s, grid, 3, 1.5, 0.3, 11).has_value());  // it would keep 10 of 11
  // A boundary farther from its line than the tolerance is no fold: it stays.
  RasterPlan off = s;
  off.faces[2].depth_mm = 5;  // the H face's fold line 4 rows above its boundary
  const std::optional<RasterPlan> moved = move_plane(off, grid, 3, 2.5, 0.3, 1);
  ASSERT_TRUE(moved.has_value());
  for (int c = 0; c < grid.cols; ++c) {
    EXPECT_EQ(moved->face(c, 11), 2);
    EXPECT_EQ(moved->face(c, 12), 3);
    EXPECT_EQ(moved->face(c, 29), 3);  // the floor's fold did move
  }
  // The H face held together only by its rows 10-11 in the middle column: giving them to the V
  // face parts it (its side columns start at row 10, the middle one's keep rows 8-9 alone).
  RasterPlan bridge = s;
  for (int r = 0; r < 10; ++r) bridge.face(0, r) = bridge.face(2, r) = kBackFace;
  for (int r = 0; r < 8; ++r) bridge.face(1, r) = kBackFace;
  for (int r = 12; r < 28; ++r) bridge.face(0, r) = bridge.face(2, r) = 2;
  EXPECT_TRUE(move_plane(bridge, grid, 3, 2.5, 0.3, 1).has_value());  // forward, it gives the H face rows
  EXPECT_FALSE(move_plane(bridge, grid, 3, 1.5, 0.3, 1).has_value());
}

// Two folds half a millimetre apart become one step: H(4) rows 0-11, a V(2) strip rows 12-13 (folds
// at Y = 2 and 1.5), H(3.5) below. Moved onto H(3.5), H(4) takes the strip's rows and becomes part
// of it: one face in every row. Onto a face beyond no strip (the floor), nothing moves.
TEST(RasterPlanEdits, AFaceMovedOntoTheFaceBeyondItsStripClosesIt) {
  const PixelGrid grid = three_columns(40, 20);
  const RasterPlan s = strip_between_two_h_faces(grid);
  for (const auto& [f, onto] : {std::pair{2, 4}, std::pair{4, 2}}) {
    const double depth = s.faces[static_cast<std::size_t>(onto)].depth_mm;
    const std::optional<RasterPlan> closed = move_plane(s, grid, f, depth, 0.3, 12, std::nullopt, onto);
    ASSERT_TRUE(closed.has_value()) << f;
    for (const std::int32_t g : closed->face.values) EXPECT_EQ(g, onto);
    EXPECT_EQ(closed->faces[static_cast<std::size_t>(onto)].pixels, grid.rows * grid.cols);
    EXPECT_EQ(closed->faces[static_cast<std::size_t>(f)].pixels, 0);
    EXPECT_EQ(closed->faces[3].pixels, 0);
    EXPECT_EQ(closed->faces[static_cast<std::size_t>(f)].depth_mm, depth);
  }
  EXPECT_FALSE(move_plane(s, grid, 2, 0, 0.3, 1, std::nullopt, kFloorFace).has_value());
  // Beside the floor in one column, H(4)'s fold with the strip moves onto the floor's row there:
  // the strip gives its whole run to H(4), which meets the floor, and closes elsewhere.
  RasterPlan beside_floor = s;
  for (int r = 14; r < grid.rows; ++r) beside_floor.face(2, r) = kFloorFace;
  const std::optional<RasterPlan> over_floor = move_plane(beside_floor, grid, 2, 3.5, 0.3, 1, std::nullopt, 4);
  ASSERT_TRUE(over_floor.has_value());
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r < grid.rows; ++r)
      EXPECT_EQ(over_floor->face(c, r), c == 2 && r >= 14 ? kFloorFace : 4) << c << ", " << r;
  EXPECT_EQ(over_floor->faces[3].pixels, 0);
  // A row longer in one column, the strip meets H(3.5) a row off its fold line (0.25 mm, over the
  // 0.2 mm tolerance): closed elsewhere, it would lie there between two parts of H(3.5).
  RasterPlan longer = s;
  longer.face(2, 14) = 3;
  EXPECT_TRUE(move_plane(s, grid, 2, 3.5, 0.2, 1, std::nullopt, 4).has_value());
  EXPECT_FALSE(move_plane(longer, grid, 2, 3.5, 0.2, 1, std::nullopt, 4).has_value());
}

// A move that could be made but closes no strip between f and `onto` is not made: H(4) half a
// millimetre higher takes its fold with the V face up 2 rows, but the V face's run ends on the
// floor, not on the H(4.5) face below it.
TEST(RasterPlanEdits, AFaceMovedOntoAFaceNoStripOfItsReachesStays) {
  const PixelGrid grid = three_columns(40, 20);
  RasterPlan s = v_between_h_and_floor(grid);
  s.faces.push_back({Orientation::H, 4.5});
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 36; r < grid.rows; ++r) s.face(c, r) = 4;
  s.faces[kFloorFace].pixels -= 4 * grid.cols, s.faces[4].pixels = 4 * grid.cols;
  EXPECT_TRUE(move_plane(s, grid, 2, 4.5, 0.3, 1).has_value());
  EXPECT_FALSE(move_plane(s, grid, 2, 4.5, 0.3, 1, std::nullopt, 4).has_value());
}

}  // namespace
}  // namespace origamic
