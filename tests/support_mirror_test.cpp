// SPDX-License-Identifier: GPL-3.0-or-later
// The support choice's frame (support_mirror.hpp): which of a plan and its mirror image it chooses
// on, the maps and plans mirrored, and what it gives back mirrored back.
#include "support_mirror.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "helpers.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

// A sheet 6 mm wide at 4 px/mm: 24 columns, symmetric on the sheet; 10 rows, 5 above the fold.
constexpr int kCols = 24, kRows = 10;
const Sheet kSheet{.width_mm = 6, .height_mm = 2.5};

PixelGrid grid() {
  PixelGrid g;
  g.cols = kCols, g.rows = kRows, g.px_per_mm = 4, g.rows_above_fold = 5;
  return g;
}

// The back plane above the fold, the floor below, and an L of face 2 (V) with face 3 (H) on its
// foot, from column `left` on: not its own mirror image.
RasterPlan an_l(int left) {
  RasterPlan plan;
  plan.block_px = 4;
  plan.face = Grid<std::int32_t>(kCols, kRows, kBackFace);
  for (int r = 5; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) plan.face(c, r) = kFloorFace;
  plan.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 4}, {Orientation::H, 3}};
  for (int r = 2; r < 8; ++r) plan.face(left, r) = plan.face(left + 1, r) = 2;
  for (int c = left + 2; c < left + 7; ++c) plan.face(c, 6) = plan.face(c, 7) = 3;
  return plan;
}

// The same plan with faces 2 and 3 swapping ids.
RasterPlan ids_swapped(RasterPlan plan) {
  std::swap(plan.faces[2], plan.faces[3]);
  for (std::int32_t& f : plan.face.values)
    if (f == 2 || f == 3) f = 5 - f;
  return plan;
}

// The frame another plan's mirror image would choose first.
SupportFrame mirrored(SupportFrame frame) {
  return frame == SupportFrame::Plan ? SupportFrame::MirrorImage : SupportFrame::Plan;
}

TEST(SupportMirror, APlanAndItsMirrorImageChooseOppositeFramesWhateverTheirIds) {
  const RasterPlan plan = an_l(3);
  const SupportFrame frame = first_support_frame(plan, grid(), kSheet);
  ASSERT_NE(frame, SupportFrame::Only);
  EXPECT_EQ(first_support_frame(mirror_image(plan), grid(), kSheet), mirrored(frame));
  EXPECT_EQ(first_support_frame(ids_swapped(mirror_image(plan)), grid(), kSheet), mirrored(frame));
  EXPECT_EQ(first_support_frame(ids_swapped(plan), grid(), kSheet), frame);
  // Moved along the fold, the model keeps its frame.
  EXPECT_EQ(first_support_frame(an_l(9), grid(), kSheet), frame);
  EXPECT_EQ(first_support_frame(an_l(14), grid(), kSheet), frame);
}

// Two V faces side by side, at depths 4 and 6 mm, their boundary off the middle: every column
// reads the same kinds from both ends, but not the same planes, nor the same runs inwards.
TEST(SupportMirror, FacesThatDifferOnlyInDepthOrWhereTheyMeetStillChooseOppositeFrames) {
  RasterPlan plan = an_l(3);
  for (int c = 3; c < kCols; ++c)
    for (int r = 0; r < kRows; ++r) plan.face(c, r) = r < 5 ? kBackFace : kFloorFace;
  plan.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 4}, {Orientation::V, 6}};
  for (int r = 2; r < 8; ++r)
    for (int c = 8; c < 16; ++c) plan.face(c, r) = c < 11 ? 2 : 3;
  const SupportFrame frame = first_support_frame(plan, grid(), kSheet);
  ASSERT_NE(frame, SupportFrame::Only);
  EXPECT_EQ(first_support_frame(mirror_image(plan), grid(), kSheet), mirrored(frame));
  // The same depths, the boundary off the middle: only where the faces run on tells them apart.
  plan.faces[3].depth_mm = 4;
  ASSERT_NE(first_support_frame(plan, grid(), kSheet), SupportFrame::Only);
  EXPECT_EQ(first_support_frame(mirror_image(plan), grid(), kSheet),
            mirrored(first_support_frame(plan, grid(), kSheet)));
}

TEST(SupportMirror, APlanThatIsItsOwnMirrorImageOrALatticeOffTheSheetHasOneFrame) {
  RasterPlan plan = an_l(3);
  for (int c = 3; c < kCols; ++c)
    for (int r = 0; r < kRows; ++r) plan.face(c, r) = r < 5 ? kBackFace : kFloorFace;
  for (int r = 2; r < 8; ++r) plan.face(11, r) = plan.face(12, r) = 2;  // the middle two columns
  EXPECT_EQ(first_support_frame(plan, grid(), kSheet), SupportFrame::Only);
  // 24 columns at 4 px/mm are 6 mm: on a 6.1 mm sheet the lattice is not symmetric.
  const Sheet wider{.width_mm = 6.1, .height_mm = 2.5};
  EXPECT_EQ(first_support_frame(an_l(3), grid(), wider), SupportFrame::Only);
  EXPECT_EQ(first_support_frame(mirror_image(an_l(3)), grid(), wider), SupportFrame::Only);
}

TEST(SupportMirror, MirroredMapsPutEachBreakBetweenTheMirroredPixelCentres) {
  RasterMaps maps = test::blank_maps(grid(), HitKind::Back);
  maps.kind(2, 1) = HitKind::Model;
  maps.d_mm(2, 1) = 7.5;
  maps.normal(2, 1) = glm::vec3(0.6f, 0, 0.8f);
  maps.break_right(2, 1) = 0.25f;  // between columns 2 and 3, a quarter of the way from 2
  maps.break_below(2, 1) = 0.5f;
  RasterMaps m = maps;
  mirror_in_place(m);
  EXPECT_EQ(m.kind(21, 1), HitKind::Model);
  EXPECT_EQ(m.d_mm(21, 1), 7.5);
  EXPECT_EQ(m.normal(21, 1), glm::vec3(-0.6f, 0, 0.8f));
  EXPECT_EQ(m.break_right(20, 1), 0.75f);  // between columns 20 and 21, a quarter from 21
  EXPECT_EQ(m.break_below(21, 1), 0.5f);
  int breaks = 0;
  for (const float t : m.break_right.values) breaks += !std::isnan(t);
  EXPECT_EQ(breaks, 1);
  {
    const MirroredMaps back(m);  // mirrored again while it lives
    EXPECT_EQ(m.break_right(2, 1), 0.25f);
    EXPECT_EQ(m.d_mm(2, 1), 7.5);
  }
  EXPECT_EQ(m.break_right(20, 1), 0.75f) << "and as given after";
}

// Mirroring twice gives a design's maps back bit for bit: the supports mirror them in place.
TEST(SupportMirror, MapsMirroredTwiceAreTheMapsBitForBit) {
  const RayScene scene(test::box({30, 40, 20}, {100, 80, 50}));  // off the sheet's middle
  const RasterMaps maps = raster(scene, Sheet{}, RasterOptions{});
  RasterMaps twice = maps;
  mirror_in_place(twice);
  EXPECT_NE(twice.d_mm.values, maps.d_mm.values);
  mirror_in_place(twice);
  EXPECT_TRUE(test::same_bytes(twice.kind, maps.kind));
  EXPECT_TRUE(test::same_bytes(twice.d_mm, maps.d_mm));
  EXPECT_TRUE(test::same_bytes(twice.h_mm, maps.h_mm));
  EXPECT_TRUE(test::same_bytes(twice.normal, maps.normal));
  EXPECT_TRUE(test::same_bytes(twice.break_right, maps.break_right));  // NaN where none: bytes, not ==
  EXPECT_TRUE(test::same_bytes(twice.break_below, maps.break_below));
}

TEST(SupportMirror, FacesAreRenumberedInTheOrderAScanMeetsThem) {
  const RasterPlan plan = ids_swapped(an_l(3));  // face 3 is the L's upright now, met first
  const RasterPlan renumbered = with_faces_in_scan_order(plan);
  EXPECT_EQ(renumbered.face(3, 2), 2);
  EXPECT_EQ(renumbered.face(6, 6), 3);
  EXPECT_EQ(renumbered.faces[2].orientation, Orientation::V);
  EXPECT_EQ(renumbered.faces[3].depth_mm, 3);
  const RasterPlan again = with_faces_in_scan_order(an_l(3));
  EXPECT_EQ(again.face.values, an_l(3).face.values);
}

// Twice the signed area of a ring: positive counter-clockwise.
double twice_area(const std::vector<PlanPoint>& ring) {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) sum += ring[i].X * ring[i + 1].Y - ring[i + 1].X * ring[i].Y;
  return sum;
}

TEST(SupportMirror, APlanMirroredBackHasItsLinesRegionsAndPlacesMirroredAndItsRingsTurnAsBefore) {
  SupportedPlan supported;
  supported.raster_plan = an_l(3);
  supported.plan.lines = {{LineKind::Cut, {{1, 0}, {2, 0.5}}}};
  PlanRegion region;
  region.rings = {{{1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0}}};
  region.inside = {1.5, 0.5};
  supported.plan.regions = {region};
  supported.plan.faces.resize(4);
  supported.plan.faces[2].inside = {1.25, 0.75};
  supported.report.joined_faces.push_back({.at = {0.5, -1}});
  CutOutFace cut_out;
  cut_out.at = {1, -0.5};
  supported.report.cut_out_faces.push_back(cut_out);
  supported.report.narrow.push_back({.face = 2, .support = false, .width_mm = 0.5, .at = {0.25, 1}});
  const SupportedPlan m = mirror_image(supported, kSheet);
  EXPECT_EQ(m.plan.lines[0].points[1].X, 4);
  EXPECT_EQ(m.plan.lines[0].points[1].Y, 0.5);
  EXPECT_EQ(m.plan.regions[0].inside.X, 4.5);
  EXPECT_GT(twice_area(m.plan.regions[0].rings[0]), 0);
  EXPECT_EQ(m.plan.faces[2].inside.X, 4.75);
  EXPECT_EQ(m.report.joined_faces[0].at.X, 5.5);
  EXPECT_EQ(m.report.cut_out_faces[0].at.X, 5);
  EXPECT_EQ(m.report.narrow[0].at.X, 5.75);
  EXPECT_EQ(m.raster_plan.face(20, 2), 2);
  EXPECT_EQ(mirror_image(m.raster_plan).face.values, supported.raster_plan.face.values);
}

}  // namespace
}  // namespace origamic
