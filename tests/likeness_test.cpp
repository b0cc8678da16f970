// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/likeness.hpp"

#include <gtest/gtest.h>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

// Maps of a model that fills a small sheet of 1 px/mm above the main fold, its depth given per row
// (h = Y + d, as along the 45-degree ray).
RasterMaps column_model(int cols, int rows, double (*depth_of_row)(int)) {
  RasterMaps maps;
  maps.grid = {.cols = cols, .rows = rows, .px_per_mm = 1, .rows_above_fold = rows};
  maps.kind = Grid<HitKind>(cols, rows, HitKind::Model);
  maps.d_mm = Grid<double>(cols, rows);
  maps.h_mm = Grid<double>(cols, rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      maps.d_mm(c, r) = depth_of_row(r);
      maps.h_mm(c, r) = maps.grid.Y(r) + depth_of_row(r);
    }
  maps.model_pixels = static_cast<std::size_t>(cols) * rows;
  return maps;
}

TEST(Likeness, StaircaseOfASlopeHasTheErrorWorkedOutByHand) {
  // A slope whose depth falls 0.5 mm a row, sliced into V steps of 4 rows at their mean depth: the
  // rows of a step are 0.75, 0.25, 0.25 and 0.75 mm off it, so h + d is 1.5, 0.5, 0.5, 1.5 mm off.
  const RasterMaps maps = column_model(10, 40, [](int row) { return 30.0 - 0.5 * (39 - row); });
  Grid<std::int32_t> face(10, 40);
  std::vector<RasterFace> faces = {{Orientation::V, 0}, {Orientation::H, 0}};
  for (int step = 0; step < 10; ++step) {
    const double mean = (maps.d_mm(0, 4 * step) + maps.d_mm(0, 4 * step + 3)) / 2;
    faces.push_back({.orientation = Orientation::V, .depth_mm = mean});
    for (int r = 4 * step; r < 4 * step + 4; ++r)
      for (int c = 0; c < 10; ++c) face(c, r) = static_cast<std::int32_t>(faces.size() - 1);
  }
  const double W = 2;
  const Likeness l = likeness(maps, card_view(maps.grid, face, faces), W);
  EXPECT_DOUBLE_EQ(l.mean_mm, 1.0);
  EXPECT_DOUBLE_EQ(l.p95_mm, 1.5);
  EXPECT_DOUBLE_EQ(l.mean_W, 0.5);
  EXPECT_DOUBLE_EQ(l.p95_W, 0.75);
  EXPECT_DOUBLE_EQ(l.coverage, 1.0);
  EXPECT_EQ(l.model_pixels, 400);
}

TEST(Likeness, AnHFaceIsSeenAtTwiceItsHeightLessY) {
  const RasterMaps maps = column_model(4, 8, [](int) { return 5.0; });
  Grid<std::int32_t> face(4, 8, 2);
  const std::vector<RasterFace> faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::H, 9.0}};
  const CardView card = card_view(maps.grid, face, faces);
  for (int r = 0; r < 8; ++r) EXPECT_FLOAT_EQ(card.key_mm(1, r), static_cast<float>(2 * 9.0 - maps.grid.Y(r)));
  // The model is V(5) at h = Y + 5: h + d = Y + 10 against 18 - Y.
  const Grid<float> error = likeness_error_map(maps, card);
  EXPECT_FLOAT_EQ(error(0, 7), static_cast<float>(std::abs(18 - 2 * maps.grid.Y(7) - 10)));
}

TEST(Likeness, AModelThatLosesEveryFaceIsAllCutOut) {
  const RasterMaps maps = column_model(6, 6, [](int) { return 4.0; });
  Grid<std::int32_t> face(6, 6, 2);
  for (int c = 0; c < 6; ++c) face(c, 5) = 3;
  std::vector<RasterFace> faces = {
      {Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 4.0}, {Orientation::H, 8.0}};
  faces[2].hole = faces[3].hole = true;
  const Likeness l = likeness(maps, card_view(maps.grid, face, faces), 3);
  EXPECT_DOUBLE_EQ(l.cut_out_share, 1.0);
  EXPECT_DOUBLE_EQ(l.coverage, 0.0);
  // Through a hole the back plane shows: h + d = Y against the model's Y + 8.
  EXPECT_DOUBLE_EQ(l.mean_mm, 8.0);
}

TEST(Likeness, SupportsAreCountedApartFromTheModelsFaces) {
  const RasterMaps maps = column_model(10, 10, [](int) { return 4.0; });
  Grid<std::int32_t> face(10, 10, 2);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 3; ++c) face(c, r) = 3;
  std::vector<RasterFace> faces = {
      {Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 4.0}, {Orientation::V, 4.0}};
  faces[3].support = true;
  const Likeness l = likeness(maps, card_view(maps.grid, face, faces), 3);
  EXPECT_DOUBLE_EQ(l.support_share, 0.3);
  EXPECT_DOUBLE_EQ(l.coverage, 1.0);
  EXPECT_DOUBLE_EQ(l.p95_mm, 0.0);
}

// A box pop-up against the back plane on the floor, rastered from its mesh.
struct BoxModel {
  Sheet sheet;
  double x0 = 40.25, x1 = 151.75, h = 61.5, d = 37.25;
  RasterMaps maps;
  BoxModel() {
    const RayScene scene(test::box({x0, 0, 0}, {x1, h, d}));
    maps = raster(scene, sheet, RasterOptions{});
  }
};

TEST(Likeness, RegionsDrawnByHandOfABoxMeetItsModelExactly) {
  const BoxModel box;
  const std::vector<PlanRegion> regions = test::box_popup_regions(box.sheet, box.x0, box.x1, box.h, box.d);
  const CardView card = card_view(box.maps.grid, regions, {});
  // The regions tile the sheet: every pixel centre is in one of them.
  for (const CardSurface s : card.surface.values) ASSERT_NE(s, CardSurface::Outside);
  const Likeness l = likeness(box.maps, card, 3);
  EXPECT_GT(l.model_pixels, 100000);
  EXPECT_NEAR(l.p95_mm, 0.0, 1e-9);
  EXPECT_NEAR(l.mean_mm, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(l.coverage, 1.0);
  EXPECT_DOUBLE_EQ(l.cut_out_share, 0.0);
}

TEST(Likeness, TheFinishedPlanOfABoxMeetsItsModelExactly) {
  const test::TempDir dir;
  test::write_obj(dir / "box.obj", test::box({0, 0, 0}, {3, 2, 1.5}));
  const DesignResult r = design(dir / "box.obj", DesignOptions{});
  ASSERT_TRUE(plan_stands(r.plan.validity, false));
  EXPECT_EQ(r.plan.faces.size(), 4u);
  for (const Likeness& l : {r.likeness, r.sliced_likeness}) {
    EXPECT_GT(l.model_pixels, 100000);
    EXPECT_NEAR(l.p95_mm, 0.0, 1e-9);
    EXPECT_NEAR(l.mean_mm, 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(l.coverage, 1.0);
    EXPECT_DOUBLE_EQ(l.support_share, 0.0);
    EXPECT_DOUBLE_EQ(l.cut_out_share, 0.0);
  }
}

TEST(Likeness, RemovedAndUnplacedRegionsAreHoles) {
  const BoxModel box;
  std::vector<PlanRegion> regions = test::box_popup_regions(box.sheet, box.x0, box.x1, box.h, box.d);
  regions[2].status = FaceStatus::Removed;  // the front cut out
  regions[3].placed = false;                // the top placed by no fold
  const Likeness l = likeness(box.maps, card_view(box.maps.grid, regions, {}), 3);
  EXPECT_DOUBLE_EQ(l.cut_out_share, 1.0);
  EXPECT_DOUBLE_EQ(l.coverage, 0.0);
}

TEST(Likeness, AFaceNarrowerThanWEverywhereHoldsNoDiscWAcross) {
  // At 4 px/mm, W = 3 mm is 12 pixels: a face 3 mm wide holds a disc 12 pixels across, one 2.5 mm
  // wide does not, however long, and one with a 2 mm tip beside a 5 mm body does.
  const PixelGrid grid{.cols = 200, .rows = 200, .px_per_mm = 4, .rows_above_fold = 100};
  const auto box = [](double X0, double X1, double Y0, double Y1) {
    PlanRegion region;
    region.rings = {{{X0, Y0}, {X1, Y0}, {X1, Y1}, {X0, Y1}}};
    region.placed = true;
    return region;
  };
  PlanRegion tipped;
  tipped.rings = {{{10, -20}, {15, -20}, {15, -10}, {12, -10}, {12, 10}, {10, 10}}};
  const std::vector<PlanRegion> regions = {box(10, 13, 1, 21), box(20, 22.5, 1, 24), tipped};
  const std::vector<double> discs = widest_discs_px(grid, regions);
  ASSERT_EQ(discs.size(), 3u);
  EXPECT_DOUBLE_EQ(discs[0], 12);
  EXPECT_DOUBLE_EQ(discs[1], 10);
  EXPECT_DOUBLE_EQ(discs[2], 20);
}

}  // namespace
}  // namespace origamic
