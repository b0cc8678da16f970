// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/supports.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/likeness.hpp"
#include "origamic/plan_analysis.hpp"
#include "support_candidates.hpp"
#include "support_choice.hpp"
#include "support_picture.hpp"

namespace origamic {
namespace {

// Column extent [min, max] in pixels of every support face of a raster plan.
std::map<std::int32_t, std::pair<int, int>> support_columns(const RasterPlan& raster_plan) {
  std::map<std::int32_t, std::pair<int, int>> extent;
  for (int row = 0; row < raster_plan.face.rows; ++row)
    for (int col = 0; col < raster_plan.face.cols; ++col) {
      const std::int32_t f = raster_plan.face(col, row);
      if (f < 0 || !raster_plan.faces[static_cast<std::size_t>(f)].support) continue;
      auto [it, fresh] = extent.try_emplace(f, col, col);
      it->second = {std::min(it->second.first, col), std::max(it->second.second, col)};
    }
  return extent;
}

void expect_exact_and_standing(const Plan& plan) {
  EXPECT_TRUE(plan.arrangement_valid);
  EXPECT_TRUE(plan.faces_tile_sheet);
  EXPECT_EQ(plan.lost_faces, 0);
  EXPECT_EQ(plan.unresolved_crossings, 0);
  EXPECT_TRUE(plan_stands(plan.validity, false)) << plan.validity.floating << " floating, " << plan.validity.dangling
                                                 << " dangling, " << plan.validity.invalid << " invalid";
}

// The candidates leaving face f's top edge (up) or bottom edge at that edge itself (taking none of
// its rows), the nearest target of each block column first.
std::vector<Candidate> leaving(const std::vector<Candidate>& candidates, std::int32_t f, bool up) {
  std::vector<Candidate> out;
  for (const Candidate& c : candidates)
    if (c.face == f && c.taken == 0 && (c.target_row < c.face_row) == up) out.push_back(c);
  std::ranges::stable_sort(out, [](const Candidate& a, const Candidate& b) {
    return std::pair{a.c0, a.r1 - a.r0} < std::pair{b.c0, b.r1 - b.r0};
  });
  return out;
}

// The nearest target of every block column.
std::vector<Candidate> nearest(const std::vector<Candidate>& leaving) {
  std::vector<Candidate> out;
  for (const Candidate& c : leaving)
    if (out.empty() || out.back().c0 != c.c0) out.push_back(c);
  return out;
}

// choose_supports on the raster plan's own folds.
SupportChoice choose(const RasterMaps& maps, const RasterPlan& raster_plan, const ExactPlan& exact_plan,
                     const FaceVerdicts& standing, const std::vector<std::int32_t>& invalid, SupportReach reach = {}) {
  const std::vector<FoldEdge> folds = raster_folds(maps.grid, raster_plan, aligned_fold_tolerance_mm(maps.grid));
  return choose_supports({maps, raster_plan, exact_plan, {}, folds}, standing, invalid, SupportOptions{}, reach);
}

TEST(Supports, FloatingBoxIsSupportedAtTopAndBottom) {
  const RayScene scene(test::box({60, 40, 20}, {150, 80, 50}));
  const Sheet sheet;
  RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan raster_plan = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  ASSERT_FALSE(plan_stands(build_plan(maps, raster_plan, sheet, PlanOptions{}).validity, false));
  const SupportedPlan s = add_supports(maps, raster_plan, sheet, PlanOptions{}, SupportOptions{});
  EXPECT_TRUE(s.report.converged) << stop_reason(s.report);
  EXPECT_EQ(s.report.supports, 2);
  expect_exact_and_standing(s.plan);
  // The front V(50) now reaches down to the floor and the top H(80) back to the back plane: their
  // supports lie in their planes and merged with them. Valley folds at Y = -50 and Y = 80 exactly,
  // as wide as the box (X = 60 .. 150 mm, to a pixel).
  int found = 0;
  for (const PlanPolyline& line : s.plan.lines) {
    if (line.kind != LineKind::Valley || line.points.front().Y == 0) continue;
    const double Y = line.points.front().Y;
    EXPECT_TRUE(Y == -50.0 || Y == 80.0) << Y;
    double lo = 1e300, hi = -1e300;
    for (const PlanPoint& p : line.points) lo = std::min(lo, p.X), hi = std::max(hi, p.X);
    EXPECT_NEAR(lo, 60, 0.25);
    EXPECT_NEAR(hi, 150, 0.25);
    ++found;
  }
  EXPECT_EQ(found, 2);
}

// A round finds what each support reaches on the exact plan (ExactPlan::faces_reached); the rows
// it paints hold the fold the next exact plan draws there.
TEST(Supports, ARoundReachesTheFacesOnTheExactPlan) {
  const test::FloatingBoxPlan box;
  const RasterMaps& maps = box.maps;
  const RasterPlan& raster_plan = box.raster_plan;
  const ExactPlan& exact_plan = box.exact_plan;
  const Plan& verdict = exact_plan.verdict();
  const FaceVerdicts standing = verdicts_of(verdict);
  const std::vector<std::int32_t> invalid{2, 3};
  ASSERT_EQ(verdict.validity.floating, 2);
  // One ear: the floor, the front, its fold with the top, the top, the back plane.
  const std::vector<Candidate> exact = choose(maps, raster_plan, exact_plan, standing, invalid).supports;
  ASSERT_EQ(exact.size(), 2u);
  const double px_mm = 1 / maps.grid.px_per_mm;
  for (const Candidate& s : exact) {
    const RasterFace& face = raster_plan.faces[static_cast<std::size_t>(s.face)];
    SCOPED_TRACE(s.face);
    // The top H(77.9) reaches back to the back plane, along its own plane: the fold at Y = 77.9.
    // The front V(47.1) reaches down to the floor, along its own plane: the fold at Y = -47.1.
    const bool top = face.orientation == Orientation::H;
    EXPECT_EQ(s.target, top ? kBackFace : kFloorFace);
    EXPECT_EQ(s.orientation, face.orientation);
    EXPECT_EQ(s.depth_mm, top ? 77.9 : 47.1);
    const double fold_Y = top ? 77.9 : -47.1;
    // The target's row just beyond the support holds the fold line, a row's edge at most away.
    EXPECT_LE(std::abs(maps.grid.Y(s.target_row) - fold_Y), px_mm / 2);
    EXPECT_EQ(s.target_row, top ? s.r0 - 1 : s.r1);
    EXPECT_GE(s.c1 - s.c0, raster_plan.block_px);
  }
}

// The raster plan changes after a verdict in other ways than by supports (a narrow part joined to
// a neighbour, boundaries aligned): rays meet what it holds now where its plane differs from the
// exact plan's.
TEST(Supports, RaysMeetFacesTheRasterPlanGainedSinceTheExactPlan) {
  const test::FloatingBoxPlan box;
  const RasterMaps& maps = box.maps;
  const RasterPlan& raster_plan = box.raster_plan;
  const ExactPlan& exact_plan = box.exact_plan;
  const std::int32_t front = box.front;
  // Below the front V(47.1) (Y from 41.3 - 47.1 up), the floor gains an H(20) band from Y -30 to
  // -20 across the box: the front, reaching down along its plane, folds onto it at 20 - 47.1.
  RasterPlan changed = raster_plan;
  const auto h20 = static_cast<std::int32_t>(changed.faces.size());
  changed.faces.push_back({Orientation::H, 20, 0, 0, false, false});
  const PixelGrid& grid = maps.grid;
  for (int r = 0; r < changed.face.rows; ++r)
    for (int c = 0; c < changed.face.cols; ++c)
      if (grid.Y(r) > -30 && grid.Y(r) < -20 && grid.X(c) > 60.2 && grid.X(c) < 150.7) changed.face(c, r) = h20;
  const std::vector<std::int32_t> faces{front};
  const std::vector<Candidate> down =
      nearest(leaving(support_candidates({maps, changed, exact_plan, {}, {}}, faces, SupportReach{}), front, false));
  ASSERT_FALSE(down.empty());
  for (const Candidate& c : down) {
    if (c.c0 < 60.2 * grid.px_per_mm || c.c1 > 150.7 * grid.px_per_mm) continue;  // the band's columns
    EXPECT_EQ(c.target, h20);
    EXPECT_EQ(c.orientation, Orientation::V);
    EXPECT_EQ(c.depth_mm, 47.1);
    EXPECT_LE(std::abs(grid.Y(c.target_row) - (20 - 47.1)), 0.5 / grid.px_per_mm);
  }
  // On the plan as built, the front reaches the floor, at Y = -47.1.
  const std::vector<Candidate> before = nearest(
      leaving(support_candidates({maps, raster_plan, exact_plan, {}, {}}, faces, SupportReach{}), front, false));
  ASSERT_FALSE(before.empty());
  for (const Candidate& c : before) EXPECT_EQ(c.target, kFloorFace);
}

// A support from face 2 to face 3, 10 mm long (Y = -27.1 to -37.1), that costs the picture 1.5 and
// cuts no face: the costs support_edge adds to it are its own.
Candidate priced_candidate() {
  Candidate c;
  c.face = 2, c.target = 3, c.cost = 1.5;
  c.near = {20, 47.1}, c.far = {10, 47.1};
  return c;
}

// Two supports side by side, touching, one taking the top rows of the box's front and one its
// bottom rows: each leaves the front one piece, and together they part it (the left end and the
// bottom stay joined under the first, the right end and the top over the second). A pixel apart,
// the column between joins them; a block apart, they leave it whole too.
TEST(Supports, TwoTouchingSupportsThatEachLeaveAFaceWholePartItTogether) {
  const test::FloatingBoxPlan box;
  const RasterPlan& plan = box.raster_plan;
  int c_lo = INT_MAX, c_hi = -1, r_lo = INT_MAX, r_hi = -1;
  for (int r = 0; r < plan.face.rows; ++r)
    for (int c = 0; c < plan.face.cols; ++c)
      if (plan.face(c, r) == box.front)
        c_lo = std::min(c_lo, c), c_hi = std::max(c_hi, c), r_lo = std::min(r_lo, r), r_hi = std::max(r_hi, r);
  ASSERT_GT(c_hi - c_lo, 4 * plan.block_px);
  const int mid_c = (c_lo + c_hi) / 2, mid_r = (r_lo + r_hi) / 2, block = plan.block_px;
  const auto support = [&](int c0, int r0, int r1) {
    Candidate s;
    s.face = box.front, s.target = kBackFace;
    s.c0 = c0, s.c1 = c0 + block, s.r0 = r0, s.r1 = r1;
    return s;
  };
  const Candidate from_top = support(mid_c - block, r_lo - 5, mid_r + 2);  // over the top, into the middle
  const Candidate from_bottom = support(mid_c, mid_r - 2, r_hi + 6);       // beside it, from below
  const Candidate pixel_apart = support(mid_c + 1, mid_r - 2, r_hi + 6);
  const Candidate block_apart = support(mid_c + block, mid_r - 2, r_hi + 6);
  const SupportPicture picture(box.maps, plan);
  const CandidateFinder finder({box.maps, plan, box.exact_plan, {}, {}}, {box.front}, picture, SupportReach{});
  EXPECT_FALSE(finder.cuts(box.front, from_top));
  EXPECT_FALSE(finder.cuts(box.front, from_bottom));
  const PixelRect top = from_top.pixels(), bottom = from_bottom.pixels();
  EXPECT_TRUE(finder.cuts_with(box.front, {&top, 1}, bottom));
  EXPECT_TRUE(finder.cuts_with(box.front, {&bottom, 1}, top));
  EXPECT_FALSE(finder.cuts_with(box.front, {&top, 1}, pixel_apart.pixels()));
  EXPECT_FALSE(finder.cuts_with(box.front, {&top, 1}, block_apart.pixels()));
  EXPECT_FALSE(finder.cuts_with(box.front, {}, bottom));  // alone: its own `cuts` says
}

// A support that folds onto a face less than W before that face's next fold beyond leaves a strip
// between two parallel folds narrower than W (issue 23): the front V(47.1), reaching down, folds
// onto an H(20) band at Y = -27.1; a V face below the band makes its next fold at 20 - d. Where the
// band reaches 2.9 mm past the support's fold, the candidate says so; where it reaches 5.9 mm, or
// ends on the floor (a cut: no second fold), it does not. So on the face it holds.
TEST(Supports, ASupportLeavingItsFacesAStripUnderWBeforeTheirNextFoldSaysSo) {
  const test::FloatingBoxPlan box;
  const RasterMaps& maps = box.maps;
  const PixelGrid& grid = maps.grid;
  const std::vector<std::int32_t> faces{box.front};
  // The band from Y = `bottom_Y` to -20 across the box, and V(20 - bottom_Y) below it down to -45.
  const auto down_from_front = [&](double bottom_Y, bool v_below) {
    RasterPlan changed = box.raster_plan;
    const auto h20 = static_cast<std::int32_t>(changed.faces.size());
    changed.faces.push_back({Orientation::H, 20, 0, 0, false, false});
    changed.faces.push_back({Orientation::V, 20 - bottom_Y, 0, 0, false, false});
    for (int r = 0; r < changed.face.rows; ++r)
      for (int c = 0; c < changed.face.cols; ++c) {
        if (grid.X(c) < 60.2 || grid.X(c) > 150.7) continue;
        if (grid.Y(r) > bottom_Y && grid.Y(r) < -20) changed.face(c, r) = h20;
        if (v_below && grid.Y(r) > -45 && grid.Y(r) < bottom_Y) changed.face(c, r) = h20 + 1;
      }
    std::vector<Candidate> onto_band;
    for (const Candidate& c : nearest(leaving(
             support_candidates({maps, changed, box.exact_plan, {}, {}}, faces, SupportReach{}), box.front, false)))
      if (c.c0 >= 60.2 * grid.px_per_mm && c.c1 <= 150.7 * grid.px_per_mm) {
        EXPECT_EQ(c.target, h20);
        onto_band.push_back(c);
      }
    EXPECT_GE(onto_band.size(), 20u) << "every block column across the band's 90 mm";
    return onto_band;
  };
  for (const Candidate& c : down_from_front(-30, true)) {
    EXPECT_TRUE(c.leaves_thin_strip()) << c.c0;
    EXPECT_NEAR(c.thin_strip_mm, c.far.h - c.far.d + 30, 1e-9) << c.c0;  // from the support's fold to the band's
  }
  for (const Candidate& c : down_from_front(-33, true)) {
    EXPECT_FALSE(c.leaves_thin_strip()) << c.c0;
    EXPECT_EQ(c.thin_strip_mm, std::numeric_limits<double>::infinity()) << c.c0;
  }
  for (const Candidate& c : down_from_front(-30, false)) EXPECT_FALSE(c.leaves_thin_strip()) << c.c0;
  // On the side of the face it holds too, where it leaves that face's plane: with the top H(77.9)
  // gone to the back plane, an H support from the front's top edge (Y = 30.8) reaches back to it;
  // the front ends `strip` below, on an H face folding onto it there.
  const auto up_from_front = [&](double strip) {
    RasterPlan changed = box.raster_plan;
    const auto below = static_cast<std::int32_t>(changed.faces.size());
    changed.faces.push_back({Orientation::H, 77.9 - strip, 0, 0, false, false});
    for (std::int32_t& f : changed.face.values)
      if (f == box.top) f = kBackFace;
    for (int r = 0; r < changed.face.rows; ++r)
      for (int c = 0; c < changed.face.cols; ++c)
        if (changed.face(c, r) == box.front && grid.Y(r) < 30.8 - strip) changed.face(c, r) = below;
    std::vector<Candidate> back;
    for (const Candidate& c : nearest(leaving(
             support_candidates({maps, changed, box.exact_plan, {}, {}}, faces, SupportReach{}), box.front, true)))
      if (c.target == kBackFace && c.orientation == Orientation::H) back.push_back(c);
    EXPECT_GE(back.size(), 20u) << "every block column across the front's 90 mm";
    return back;
  };
  for (const Candidate& c : up_from_front(2)) {
    EXPECT_TRUE(c.leaves_thin_strip()) << c.c0;
    // From the support's fold on the front's top edge down to the front's fold onto H(75.9).
    EXPECT_NEAR(c.thin_strip_mm, c.near.h - c.near.d - (75.9 - 47.1), 1e-9) << c.c0;
    EXPECT_NEAR(c.thin_strip_mm, 2, 0.5 / grid.px_per_mm) << c.c0;  // that edge on the pixel lattice
  }
  for (const Candidate& c : up_from_front(4)) EXPECT_FALSE(c.leaves_thin_strip()) << c.c0;
  // Its ear costs the thin strip cost more; the picture's part stays the candidate's own.
  SupportOptions options;
  Candidate c = priced_candidate();
  const std::vector<std::uint8_t> stands = {1, 1, 0, 0};
  EXPECT_EQ(support_edge(c, stands, options, 3).cost, 1.5);
  c.thin_strip_mm = 0.6;
  EXPECT_GT(options.thin_strip_cost_mm, 0);
  EXPECT_EQ(support_edge(c, stands, options, 3).cost, 1.5 + options.thin_strip_cost_mm);
  EXPECT_EQ(support_edge(c, stands, options, 3).picture, 1.5);
  // Under W / 6, a face no one can fold, the sliver cost more again.
  c.thin_strip_mm = 0.4;
  EXPECT_GT(options.sliver_strip_cost_mm, 0);
  EXPECT_EQ(support_edge(c, stands, options, 3).cost, 1.5 + options.thin_strip_cost_mm + options.sliver_strip_cost_mm);
  EXPECT_EQ(support_edge(c, stands, options, 3).picture, 1.5);
}

// A support whose block column reaches past the end of the face it holds over the back plane or
// the floor is drawn only as far as the face's side, narrower than W: it says so and costs more.
// Over another face of the model there, it does not.
TEST(Supports, ASupportReachingPastItsFacesEndOverTheBackPlaneSaysSoAndCostsMore) {
  const test::FloatingBoxPlan box;
  int lo = INT_MAX, hi = -1;  // the front's columns
  for (int r = 0; r < box.raster_plan.face.rows; ++r)
    for (int c = 0; c < box.raster_plan.face.cols; ++c)
      if (box.raster_plan.face(c, r) == box.front) lo = std::min(lo, c), hi = std::max(hi, c);
  ASSERT_GE(hi + 1 - lo, box.raster_plan.block_px);
  ASSERT_TRUE(lo % box.raster_plan.block_px != 0) << "a block column of the lattice sticks out at the left end";
  // The lattice's block at the left end sticks out 1 px over the back plane (above the front) and
  // the floor (below it); the others, and the one flush with the left end, lie on the front.
  std::set<int> past, on_face;
  for (const Candidate& c :
       support_candidates({box.maps, box.raster_plan, box.exact_plan, {}, {}}, {box.front}, SupportReach{})) {
    if (c.face != box.front) continue;
    EXPECT_EQ(c.c1 - c.c0, box.raster_plan.block_px);
    EXPECT_EQ(c.past_end, c.c0 < lo || c.c1 > hi + 1) << c.c0 << " " << c.c1;
    (c.past_end ? past : on_face).insert(c.c0);
  }
  EXPECT_EQ(past, std::set<int>{lo / box.raster_plan.block_px * box.raster_plan.block_px});
  EXPECT_GE(on_face.size(), 30u) << "the block columns across the front's 90 mm, and the two flush with its ends";
  EXPECT_TRUE(on_face.contains(lo));
  // With a face of the model beside the front's left end, where that block sticks out, it no longer
  // reaches past the end over nothing: no candidate says so.
  RasterPlan beside = box.raster_plan;
  const auto other = static_cast<std::int32_t>(beside.faces.size());
  beside.faces.push_back({Orientation::V, 60, 0, 0, false, false});
  for (int r = 0; r < beside.face.rows; ++r)
    for (int c = lo / beside.block_px * beside.block_px; c < lo; ++c)
      if (beside.face(lo, r) == box.front) beside.face(c, r) = other, ++beside.faces.back().pixels;
  for (const Candidate& c : support_candidates({box.maps, beside, box.exact_plan, {}, {}}, {box.front}, SupportReach{}))
    EXPECT_FALSE(c.face == box.front && c.past_end) << c.c0 << " " << c.c1;
  // Its edge costs the past-end cost more; the picture's part stays the candidate's own.
  SupportOptions options;
  Candidate c = priced_candidate();
  const std::vector<std::uint8_t> stands = {1, 1, 0, 0};
  EXPECT_EQ(support_edge(c, stands, options, 3).cost, 1.5);
  c.past_end = true;
  EXPECT_GT(options.past_end_cost_mm, 0);
  EXPECT_EQ(support_edge(c, stands, options, 3).cost, 1.5 + options.past_end_cost_mm);
  EXPECT_EQ(support_edge(c, stands, options, 3).picture, 1.5);
}

// A face whose every pixel has gone to a neighbour (a whole crumb joined to it) has no edge left to
// hold: it gets no candidate, and the other faces of the round get theirs.
TEST(Supports, AFaceWithNoPixelsLeftHasNoEdgeToHold) {
  const test::FloatingBoxPlan box;
  RasterPlan joined = box.raster_plan;
  for (std::int32_t& f : joined.face.values)
    if (f == box.top) f = box.front;
  joined.faces[static_cast<std::size_t>(box.front)].pixels +=
      std::exchange(joined.faces[static_cast<std::size_t>(box.top)].pixels, 0);
  const std::vector<std::int32_t> faces{box.top, box.front};
  const std::vector<Candidate> found =
      support_candidates({box.maps, joined, box.exact_plan, {}, {}}, faces, SupportReach{true, true, true});
  ASSERT_FALSE(found.empty());
  for (const Candidate& s : found) EXPECT_EQ(s.face, box.front);
}

// A fold exactly at the far end of a face's piece of the ray does not land on that face: the support
// would cover the whole piece there. A box G on the floor (front V(30) from h 0 to 50, top H(50)) and
// a box S floating in front of it (top H(50), d 60 to 80). From S's top, as H(50), the fold onto G's
// front lies at Y = 50 - 30, its top end, on a pixel edge; the exact plan passes it over and reaches
// the back plane at Y = 50.
TEST(Supports, AFoldAtTheFarEndOfAFacesPieceLandsBeyondIt) {
  const Sheet sheet;
  const RayScene scene(test::merged(test::box({60, 0, 0}, {150, 50, 30}), test::box({80, 40, 60}, {130, 50, 80})));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan raster_plan = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  const ExactPlan exact_plan(maps, raster_plan, sheet, PlanOptions{});
  const Plan& verdict = exact_plan.verdict();
  std::int32_t s_top = -1, g_front = -1;
  for (std::size_t f = 2; f < raster_plan.faces.size(); ++f) {
    const RasterFace& face = raster_plan.faces[f];
    if (face.orientation == Orientation::H && face.depth_mm == 50 && verdict.validity.status[f] == FaceStatus::Floating)
      s_top = static_cast<std::int32_t>(f);
    if (face.orientation == Orientation::V && face.depth_mm == 30) g_front = static_cast<std::int32_t>(f);
  }
  ASSERT_GE(s_top, 0);
  ASSERT_GE(g_front, 0);
  const std::vector<Candidate> up = nearest(
      leaving(support_candidates({maps, raster_plan, exact_plan, {}, {}}, {s_top}, SupportReach{}), s_top, true));
  ASSERT_FALSE(up.empty());
  for (const Candidate& c : up) {
    EXPECT_EQ(c.target, kBackFace);
    EXPECT_EQ(c.orientation, Orientation::H);
    EXPECT_EQ(c.depth_mm, 50.0);
    EXPECT_EQ(maps.grid.Y(c.target_row), 50 + 0.5 / maps.grid.px_per_mm) << "the row just above the fold";
  }
}

// A fold on a pixel edge lands in the row beyond it, so that the support ends on the fold; where
// the target does not fill the block there, in the row before it. A box floating with its top at
// H(78) reaches the back plane at Y = 78, a pixel edge. With the row above the edge cut out of the
// raster since the exact plan, the support reaches the back plane in the row below the edge.
TEST(Supports, AFoldOnARowEdgeLandsInTheRowBeforeWhereTheRowBeyondHoldsNoTarget) {
  const Sheet sheet;
  const RayScene scene(test::box({60, 41.3, 18.6}, {150, 78, 47.1}));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan raster_plan = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  const ExactPlan exact_plan(maps, raster_plan, sheet, PlanOptions{});
  const PixelGrid& grid = maps.grid;
  std::int32_t top = -1;
  for (std::size_t f = 2; f < raster_plan.faces.size(); ++f)
    if (raster_plan.faces[f].orientation == Orientation::H && raster_plan.faces[f].depth_mm == 78)
      top = static_cast<std::int32_t>(f);
  ASSERT_GE(top, 0);
  const double px_mm = 1 / grid.px_per_mm;
  const auto row_at = [&](double Y) { return static_cast<int>(std::lround(grid.rows_above_fold - Y / px_mm - 0.5)); };
  const int beyond = row_at(78 + px_mm / 2), before = row_at(78 - px_mm / 2);
  ASSERT_EQ(grid.Y(beyond), 78 + px_mm / 2);
  ASSERT_EQ(grid.Y(before), 78 - px_mm / 2);
  const std::vector<Candidate> plain =
      nearest(leaving(support_candidates({maps, raster_plan, exact_plan, {}, {}}, {top}, SupportReach{}), top, true));
  ASSERT_FALSE(plain.empty());
  for (const Candidate& c : plain) {
    EXPECT_EQ(c.target, kBackFace);
    EXPECT_EQ(c.target_row, beyond);
  }
  RasterPlan cut = raster_plan;
  const auto hole = static_cast<std::int32_t>(cut.faces.size());
  cut.faces.push_back({Orientation::V, 0, 0, 0, false, true});
  for (int c = 0; c < cut.face.cols; ++c)
    if (cut.face(c, beyond) == kBackFace) cut.face(c, beyond) = hole;
  const std::vector<Candidate> chosen =
      nearest(leaving(support_candidates({maps, cut, exact_plan, {}, {}}, {top}, SupportReach{}), top, true));
  ASSERT_FALSE(chosen.empty());
  for (const Candidate& c : chosen) {
    EXPECT_EQ(c.target, kBackFace);
    EXPECT_EQ(c.target_row, before);
    EXPECT_EQ(c.depth_mm, 78.0);
  }
}

TEST(Supports, SlopesBecomeStaircasesAsWideAsTheSlope) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  // The wedge is one slope across the model's whole width; the Mayan pyramid's tiers are boxes,
  // and only its small top needs supports.
  for (const auto& [model, slope_width_fraction] :
       {std::pair{"seedlike/wedge.stl", 0.95}, {"seedlike/mayan_pyramid.stl", 0.0}}) {
    SCOPED_TRACE(model);
    DesignOptions options;
    options.placement.up = UpAxis::Z;
    const DesignResult r = design(test::models_dir() / model, options);
    EXPECT_TRUE(r.supports.converged) << stop_reason(r.supports);
    EXPECT_GT(r.supports.supports, 0);
    expect_exact_and_standing(r.plan);
    const auto supports = support_columns(r.raster_plan);
    int narrowest = INT_MAX, widest = 0;
    for (const auto& [id, columns] : supports) {
      narrowest = std::min(narrowest, columns.second - columns.first + 1);
      widest = std::max(widest, columns.second - columns.first + 1);
    }
    if (!supports.empty()) {
      EXPECT_GE(narrowest, r.raster_plan.block_px) << "a support narrower than W";
    }
    const double model_width_px = (r.placement.max_oa.x - r.placement.min_oa.x) * r.maps.grid.px_per_mm;
    EXPECT_GE(widest, slope_width_fraction * model_width_px) << "supports widened along the slope";
  }
}

// The wedge's ramp is sliced into H treads, held by V risers that supports add. A riser up from one
// tread and one down from the next both took rows of the tread between, leaving folds 0.32-0.57 mm
// apart; supports of a round now keep a strip width apart, so in no column across the ramp are two
// risers closer than W; nor, since the lowest tread stands W up (slice.cpp), is the riser from the
// floor. (Within W of the ramp's sides the supports' ends notch the plan: not checked here.)
TEST(Supports, RisersUpARampLeaveNoTreadNarrowerThanW) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  const DesignResult r = design(test::models_dir() / "seedlike/wedge.stl", options);
  expect_exact_and_standing(r.plan);
  const double W = options.slice.min_strip_mm, px_mm = 1 / r.maps.grid.px_per_mm;
  int columns = 0;
  for (double X = r.placement.min_oa.x + W + 0.01; X < r.placement.max_oa.x - W; X += px_mm) {  // off the pixel lines
    std::vector<double> folds_Y;
    for (const PlanPolyline& line : r.plan.lines) {
      if (line.kind != LineKind::Mountain && line.kind != LineKind::Valley) continue;
      for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
        const PlanPoint &a = line.points[i], &b = line.points[i + 1];
        if ((a.X - X) * (b.X - X) < 0) folds_Y.push_back(a.Y);  // folds run along X: a.Y == b.Y
      }
    }
    std::ranges::sort(folds_Y);
    ASSERT_GE(folds_Y.size(), 30u) << "at X = " << X << ": the ramp is a staircase of 19 treads";
    ++columns;
    for (std::size_t i = 0; i + 1 < folds_Y.size(); ++i)
      EXPECT_GE(folds_Y[i + 1] - folds_Y[i], W)
          << "at X = " << X << ", folds at Y = " << folds_Y[i] << " and " << folds_Y[i + 1];
  }
  EXPECT_GE(columns, 600) << "every pixel column of the ramp's 190 mm, but W at either side";
}

// The quarter sphere: every slice supported, no face invalid, none cut out, and the verdict
// is the one an independent reading of the plan's lines gives.
TEST(Supports, QuarterSphereStandsWithEverySliceSupportedAndSupportsAtLeastWWide) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  const DesignResult r = design(test::models_dir() / "seedlike/quarter_sphere.stl", options);
  EXPECT_TRUE(r.plan.arrangement_valid);
  EXPECT_TRUE(r.plan.faces_tile_sheet);
  EXPECT_EQ(r.plan.lost_faces, 0);
  EXPECT_EQ(r.plan.unresolved_crossings, 0);
  EXPECT_TRUE(plan_stands(r.plan.validity, false));
  const PlanAnalysis lines = analyze_plan(r.plan.lines, AnalysisOptions{});
  EXPECT_TRUE(lines.valid()) << "its lines say otherwise";
  for (const PlanProblem& p : lines.problems) EXPECT_NE(p.kind, PlanProblemKind::OutsideCard) << p.message;
  EXPECT_TRUE(r.supports.converged) << stop_reason(r.supports);
  EXPECT_EQ(r.supports.stop, SupportStop::None);
  EXPECT_EQ(r.supports.cut_out, 0);
  EXPECT_GT(r.supports.supports, 0);
  // Every slice stands: steep ones vertical, flat ones horizontal, each folded to the next.
  int raster_plan = 0, vertical = 0;
  for (std::size_t f = 2; f < r.plan.faces.size(); ++f) {
    EXPECT_EQ(r.plan.faces[f].status, FaceStatus::Valid) << "face " << f;
    if (r.raster_plan.faces[f].support) continue;
    ++raster_plan;
    vertical += r.raster_plan.faces[f].orientation == Orientation::V;
  }
  double radius_mm = 0;  // the placed model's height: the sphere's radius
  for (std::size_t i = 0; i < r.maps.kind.size(); ++i)
    if (r.maps.kind.values[i] == HitKind::Model) radius_mm = std::max(radius_mm, r.maps.h_mm.values[i]);
  EXPECT_GE(raster_plan, 2 * static_cast<int>(radius_mm / r.raster_plan.min_strip_mm) - 6)
      << "about one slice per W of the radius, each way";
  EXPECT_GT(vertical, 0);
  EXPECT_LT(vertical, raster_plan);
  // A support is at least W wide when chosen; a later one crossing it can leave a narrower piece.
  // Every such piece is reported, with its place.
  std::vector<std::int32_t> narrow_supports, reported;
  for (const auto& [id, columns] : support_columns(r.raster_plan))
    if (columns.second - columns.first + 1 < r.raster_plan.block_px &&
        !r.raster_plan.faces[static_cast<std::size_t>(id)].hole)
      narrow_supports.push_back(id);
  for (const NarrowStrip& n : r.supports.narrow) {
    if (n.support) reported.push_back(n.face);
    EXPECT_LT(n.width_mm, r.raster_plan.min_strip_mm);
    EXPECT_EQ(r.raster_plan.face(
                  static_cast<int>(n.at.X * r.maps.grid.px_per_mm),
                  r.maps.grid.rows_above_fold - 1 - static_cast<int>(std::floor(n.at.Y * r.maps.grid.px_per_mm))),
              n.face)
        << "its place is in it";
  }
  EXPECT_EQ(narrow_supports, reported);
}

TEST(Supports, SameSeedSamePlanAnotherSeedStillStands) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  const auto model = test::models_dir() / "seedlike/capitol.stl";
  const DesignResult a = design(model, options), b = design(model, options);
  EXPECT_EQ(a.raster_plan.face.values, b.raster_plan.face.values);
  expect_exact_and_standing(a.plan);
  options.supports.seed = 12345;
  const DesignResult c = design(model, options);
  expect_exact_and_standing(c.plan);
}

// The README's demo model: its roof slopes become terraces. One greedy face order leaves them
// floating, or cut out; the next orders of the seed's sequence must find a plan that stands, cutting
// nothing out.
TEST(Supports, ShippedHouseStandsAtTheDefaultOptions) {
  DesignOptions options;
  const DesignResult house = design(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj", options);
  expect_exact_and_standing(house.plan);
  EXPECT_EQ(house.supports.cut_out, 0) << stop_reason(house.supports);
  EXPECT_GE(house.supports.orders, 1);
  EXPECT_LE(house.supports.orders, options.supports.orders);
  // One order only: the report says so, and a plan that does not stand says why.
  options.supports.orders = 1;
  const DesignResult once = design(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj", options);
  EXPECT_EQ(once.supports.orders, 1);
  if (!plan_stands(once.plan.validity, false)) {
    EXPECT_NE(once.supports.stop, SupportStop::None);
    EXPECT_FALSE(stop_reason(once.supports).empty());
  }
}

// The windmill's sails are strips that part pieces of the back plane from the rest: the windmill
// stands, and every face cut out of the sheet is reported with its place and why.
TEST(Supports, AModelOfStripsStandsAndEveryFaceCutOutIsReportedWithWhy) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Y;
  const DesignResult r = design(test::models_dir() / "arch_windmill.obj", options);
  expect_exact_and_standing(r.plan);
  EXPECT_EQ(r.supports.cut_out_faces.size(), static_cast<std::size_t>(r.supports.cut_out));
  for (const CutOutFace& f : r.supports.cut_out_faces) {
    EXPECT_FALSE(f.reason.empty());
    EXPECT_GT(f.area_mm2, 0);
    EXPECT_GE(f.at.X, 0);
    EXPECT_LE(f.at.X, options.sheet.width_mm);
  }
  EXPECT_LT(r.likeness.cut_out_share, 0.03);
}

// A real model designed at the default options, up `up`, sliced: no supports.
DesignResult sliced_design(const char* model, UpAxis up) {
  DesignOptions options;
  options.placement.up = up;
  options.supports.enabled = false;
  return design(test::models_dir() / model, options);
}

// A real model (Z up) designed at the default options but `orders` and `seed`: its plan must stand.
DesignResult standing_design(const char* model, const DesignOptions& options) {
  DesignResult r = design(test::models_dir() / model, options);
  expect_exact_and_standing(r.plan);
  return r;
}
DesignResult standing_design(const char* model, int orders = DesignOptions{}.supports.orders,
                             std::uint32_t seed = DesignOptions{}.supports.seed) {
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.supports.orders = orders;
  options.supports.seed = seed;
  return standing_design(model, options);
}

// The sphere's crumbs at its rim, which no support holds, were cut out of the sheet (12 holes, 1.4%
// of the model showing the back plane or the floor). Each is now given to the neighbour whose plane
// shows the model over it better than a hole would: the sphere stands with no hole, and the report
// says where each went and what it cost against its hole.
TEST(Supports, AFaceNoSupportHoldsJoinsTheNeighbourNearestTheModelRatherThanLeaveAHole) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("seedlike/sphere.stl");
  EXPECT_EQ(r.supports.cut_out, 0);
  EXPECT_EQ(r.plan.validity.removed, 0);
  EXPECT_EQ(r.likeness.cut_out_share, 0);
  ASSERT_FALSE(r.supports.joined_faces.empty());
  for (const JoinedFace& f : r.supports.joined_faces) {
    EXPECT_GT(f.area_mm2, 0);
    // Where it was is a face of the plan now, not a hole.
    const auto col = static_cast<int>(f.at.X * r.maps.grid.px_per_mm);
    const auto row = static_cast<int>(r.maps.grid.rows_above_fold - f.at.Y * r.maps.grid.px_per_mm);
    const std::int32_t there = r.raster_plan.face(col, row);
    ASSERT_GE(there, 0);
    EXPECT_FALSE(r.raster_plan.faces[static_cast<std::size_t>(there)].hole);
  }
  EXPECT_GE(r.likeness.coverage, 0.99);
}

// A face is cut out for its cost only where holding it would cost the picture more than its hole.
// The church's two roof faces at W = 2 mm were each costly beside a join into the other: the first
// went into the second, which then had no join as cheap as its hole and was cut out, though an ear
// held it for a sixteenth of its hole (15.7% of the model cut out, p95 30 W). It is held now.
TEST(Supports, AFaceHeldForLessThanItsHoleIsNotCutOut) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Y;
  options.slice.min_strip_mm = 2;
  const DesignResult r = standing_design("arch_church.obj", options);
  for (const CutOutFace& face : r.supports.cut_out_faces)
    if (face.hold_cost >= 0) {
      EXPECT_GT(face.hold_cost, face.hole_cost) << face.reason << " at " << face.at.X;
    }
  EXPECT_LT(r.likeness.cut_out_share, 0.01);
  EXPECT_LT(r.likeness.p95_W, 3);
}

// Stairs falling away from the viewer (z up, five steps, the tallest in front): no fold can hold
// a tread behind a taller step, and one, 6.6 % of the model, is held only by supports that cost the
// picture more than its hole. Cutting out is the last resort: the faces cut out may take 3 % of the
// model, so it is held, and the report says why; with the holes unbounded it is cut out.
TEST(Supports, AFaceWhoseHoleWouldTakeMoreThanTheHolesMayIsHeldAtAnyCost) {
  const test::TempDir dir;
  TriangleMesh stairs = test::box({0, 0, 0}, {80, 100, 12});
  for (int step = 1; step < 5; ++step)
    stairs = test::merged(stairs, test::box({0, 0, 0}, {80, 100 - 20.0 * step, 12.0 * (step + 1)}));
  test::write_obj(dir / "stairs.obj", stairs);
  DesignOptions options;
  options.placement.up = UpAxis::Z;

  options.supports.holes_model_share = 1;
  const DesignResult unbounded = design(dir / "stairs.obj", options);
  expect_exact_and_standing(unbounded.plan);
  EXPECT_GT(unbounded.likeness.cut_out_share, 0.03);
  EXPECT_TRUE(unbounded.supports.spared_faces.empty());

  options.supports.holes_model_share = DesignOptions{}.supports.holes_model_share;
  EXPECT_EQ(options.supports.holes_model_share, 0.03);
  const DesignResult r = design(dir / "stairs.obj", options);
  expect_exact_and_standing(r.plan);
  EXPECT_EQ(r.supports.cut_out, 0);
  EXPECT_EQ(r.likeness.cut_out_share, 0);
  EXPECT_EQ(r.likeness.coverage, 1);
  ASSERT_FALSE(r.supports.spared_faces.empty());
  for (const CutOutFace& face : r.supports.spared_faces) {
    EXPECT_GT(face.hold_cost, face.hole_cost);
    const double px_mm2 = 1 / (r.maps.grid.px_per_mm * r.maps.grid.px_per_mm);
    EXPECT_GT(face.area_mm2, 0.03 * static_cast<double>(r.likeness.model_pixels) * px_mm2);
    EXPECT_EQ(face.reason, "its hole would take more than 3 % of the model");
  }
}

// res_knot.off with its face list scrambled as tools/fuzz.py left it: a control character joining
// two face lines (the reader takes 1,275 of the 6,400 triangles) and four face lines appended, so
// that the file still holds as many face lines as its header promises. At 2 px/mm (up z as here,
// and up y as the fuzzer ran it) the last resort met faces spared from cut-out (their holes would
// take over 3 % of the model) that no support reached and no neighbour could take: one was given
// to face -1, and the run crashed. Such a face is not given away; the plan stands.
TEST(Supports, AFaceNoNeighbourCanTakeIsNeverGivenAway) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  std::string knot = test::read_bytes(test::models_dir() / "res_knot.off");
  const std::string joined = "\n3  371 358 360\n";
  const std::size_t at = knot.find(joined);
  if (at == std::string::npos) GTEST_SKIP() << "res_knot.off is not the file this test scrambles";
  knot[at] = '\x02';
  for (int k = 0; k < 4; ++k) knot += "3  801 800 1938 2061\n";
  const test::TempDir dir;
  test::write_text(dir / "scrambled.off", knot);
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.raster.px_per_mm = 2;
  const DesignResult r = design(dir / "scrambled.off", options);
  ASSERT_FALSE(r.supports.spared_faces.empty());  // the case: faces the holes may not take
  expect_exact_and_standing(r.plan);
  for (const JoinedFace& face : r.supports.joined_faces) EXPECT_TRUE(std::isfinite(face.joined_cost));
}

// The sphere's rim crumbs that no support holds (6, each under 1 % of the model) are given away
// together, as the support loop's last resort, where giving them a quarter at a time (one or two a
// step, each step a pass of rounds) took 8 exact plans to judge the loop. Now 4 do: the first
// verdicts, the crumbs given away in one step, and one face those joins left without its support
// given away after them. The sphere still stands with no hole.
TEST(Supports, CrumbsNoSupportHoldsAreGivenAwayTogether) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("seedlike/sphere.stl");
  EXPECT_EQ(r.supports.cut_out, 0);
  EXPECT_TRUE(r.supports.converged);
  EXPECT_LE(r.supports.exact_builds, 4);
  EXPECT_GE(r.likeness.coverage, 0.99);
}

// A hipped roof with two cross gables at its back (arch_german_semidetached, up y): each gable's
// side slopes face along the main fold and slice into upright strips, which no support holds as
// cheaply as a neighbour takes them. Given away in one batch, each strip went on into the next with
// what it had taken, all into one plane (p95 3.74 W); a strip that has taken another's pixels is
// now judged anew the next round, and the card stays within 2 W of its model.
TEST(Supports, AFaceThatTookAnotherGivenAwayIsJudgedAnewNotGivenOnWithIt) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Y;
  const DesignResult r = standing_design("arch_german_semidetached.obj", options);
  EXPECT_LE(r.likeness.p95_W, 2.0);
  EXPECT_LE(r.likeness.cut_out_share, 0.01);
  EXPECT_GE(r.likeness.coverage, 0.98);
}

// The castle keep's first choice had given its keep whole to its base (mean error 0.09 -> 0.53 W,
// p95 within 1 W), which a bound of a quarter W of mean error sent to the other frame. With a face
// that took another's pixels judged anew, its first choice holds the keep: one frame, the mean
// within a quarter W of the sliced plan's (the bound, now dropped, would pass it).
TEST(Supports, TheCastleKeepsFirstChoiceHoldsItsKeep) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("arch_castle_keep.obj");
  EXPECT_EQ(r.supports.frames, 1);
  EXPECT_LE(r.likeness.mean_W, r.sliced_likeness.mean_W + 0.25);
}

// Where no third face may be cut, the candidates are those that cut none where faces may be cut,
// in the same order and at the same cost: one to be dropped is neither priced nor asked about the
// faces it crosses after the first it cuts, and that changes no candidate kept.
TEST(Supports, WhereNoThirdFaceMayBeCutTheCandidatesAreThoseThatCutNone) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignOptions options;
  const DesignResult s = sliced_design("seedlike/sphere.stl", UpAxis::Z);
  const ExactPlan exact_plan(s.maps, s.raster_plan, options.sheet, options.plan);
  std::vector<std::int32_t> faces;
  for (std::size_t f = 2; f < s.raster_plan.faces.size(); ++f) faces.push_back(static_cast<std::int32_t>(f));
  const SupportRound round{s.maps, s.raster_plan, exact_plan, {}, {}};
  std::vector<Candidate> cutting_allowed = support_candidates(round, faces, SupportReach{true, false, false});
  const std::size_t all = cutting_allowed.size();
  std::erase_if(cutting_allowed, [](const Candidate& c) { return !c.cuts.empty(); });
  ASSERT_GT(all, cutting_allowed.size()) << "some candidates cut a third face";
  const std::vector<Candidate> none_allowed = support_candidates(round, faces, SupportReach{false, false, false});
  ASSERT_EQ(none_allowed.size(), cutting_allowed.size());
  ASSERT_GT(none_allowed.size(), 100u);
  for (std::size_t k = 0; k < none_allowed.size(); ++k) {
    const Candidate &a = none_allowed[k], &b = cutting_allowed[k];
    EXPECT_EQ(std::tie(a.face, a.target, a.c0, a.c1, a.r0, a.r1), std::tie(b.face, b.target, b.c0, b.c1, b.r0, b.r1));
    EXPECT_EQ(a.cost, b.cost) << "candidate " << k;
  }
}

// A flat torus lying on the floor. Its rings of slices fold onto each other in chains; one ear
// through each chain holds it (the old greedy choice left most of the ring to slats or cut it out:
// 5.5 % of the model). Measured on the finished plan.
TEST(Supports, AFlatRingStandsWithItsSlicesKept) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult ring = standing_design("prim_torus.stl");
  EXPECT_LE(ring.likeness.cut_out_share, 0.02);
  EXPECT_LE(ring.likeness.p95_W, 2.0);
  EXPECT_GE(ring.likeness.coverage, 0.98);
  const DesignResult one = standing_design("prim_torus.stl", 1);  // asserts that it stands
  EXPECT_GT(one.supports.supports, 0);
}

// A tower whose faceted facade tapers: two of its facets lie 0.2 mm apart in depth, one plane of
// paper; held as one, every facet stands and none is cut out.
TEST(Supports, ATaperingTowerStandsOnItsFacetsWithNoneCutOut) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("arch_one_wtc.obj");
  EXPECT_LE(r.likeness.cut_out_share, 0.01);
  EXPECT_LE(r.likeness.p95_W, 1.5);
  const DesignResult seed4 = standing_design("arch_one_wtc.obj", DesignOptions{}.supports.orders, 4);
  EXPECT_LE(seed4.likeness.cut_out_share, 0.01);
}

// A pavilion: a drum under a conical roof on columns. Its roof's slices are held (some by supports
// extended a strip width past their ends, seed §4.4's corner candidates), with under a tenth of its
// area cut out; the front rings no support holds go half to the ring above, half to the one below,
// and the card is within 4 W of its model (issue 22 asks 5; 6.95 W when its errors were counted
// up to 2 W, 4.81 W when each ring went whole to one neighbour).
TEST(Supports, AConicalRoofOnColumnsStands) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("arch_pavilion_csg.stl");
  EXPECT_LE(r.supports.cut_out_share, 0.1);
  EXPECT_LE(r.likeness.p95_W, 4);
}

// The box before the back plane of the join tests, sliced at W = 3: the back plane, the floor, its
// front V(40) and its top H(50).
struct SlicedBox {
  RasterMaps maps;
  RasterPlan raster_plan;
  std::int32_t front = 0, top = 0;
};
SlicedBox sliced_box() {
  SlicedBox box;
  box.maps = raster(RayScene(test::box({60, 0, 0}, {150, 50, 40})), Sheet{}, RasterOptions{});
  box.raster_plan = slice(box.maps, segment(box.maps, SegmentOptions{}), SliceOptions{.min_strip_mm = 3});
  if (box.raster_plan.faces.size() == 4) {
    box.front = box.raster_plan.faces[2].orientation == Orientation::V ? 2 : 3;
    box.top = 5 - box.front;
  }
  return box;
}

// A box before the back plane: its front V(40) and its top H(50) are each other's only neighbours
// but the back plane and the floor, which take nothing (a hole shows them). Given to the top, the
// front would show the model 20 - 2Y mm off at plan height Y (the top's key 100 - Y against the
// front's Y + 80); a hole shows it |Y| - Y - 80 off, and 2 W more: each counted in full.
TEST(Supports, AFaceJoinsTheNeighbourWhosePlaneShowsTheModelBestAndCostsWhatItAdds) {
  const auto [maps, raster_plan, front, top] = sliced_box();
  ASSERT_EQ(raster_plan.faces.size(), 4u);
  const SupportPicture picture(maps, raster_plan);
  const std::vector<std::int32_t> both = {front, top};
  const std::vector<SupportPicture::Join> joins = picture.nearest_joins(raster_plan, both);
  ASSERT_EQ(joins.size(), 2u);
  EXPECT_EQ(joins[0].into, top);
  EXPECT_EQ(joins[1].into, front);
  // The expected sums, pixel by pixel, in mm of error times mm² of plan.
  const double W = 3, pixel_mm2 = 1 / (maps.grid.px_per_mm * maps.grid.px_per_mm);
  double joined = 0, hole = 0;
  for (int r = 0; r < maps.grid.rows; ++r)
    for (int c = 0; c < maps.grid.cols; ++c)
      if (raster_plan.face(c, r) == front) {
        const double Y = maps.grid.Y(r);
        joined += std::abs(20 - 2 * Y) * pixel_mm2;
        hole += (std::abs(std::abs(Y) - Y - 80) + 2 * W) * pixel_mm2;
      }
  EXPECT_NEAR(joins[0].error, joined, 1e-3 * joined);
  EXPECT_NEAR(picture.hole_error(front), hole, 1e-3 * hole);
  // With the top to be cut out too, the front has no neighbour to go to.
  const std::vector<std::int32_t> only_front = {front}, not_top = {top};
  const SupportPicture::Join none = picture.nearest_joins(raster_plan, only_front, not_top).front();
  EXPECT_EQ(none.into, -1);
  EXPECT_TRUE(std::isinf(none.error));
}

// Where every neighbour's plane is wrong over all of a face, the face joins the least wrong. The
// box's top is split at its middle into H(90) on the left, which the front's first pixel meets
// first, and H(65) on the right. Over the front (key Y + 80, Y from -40 to 10) they are 100 - 2Y and
// 50 - 2Y mm off, over 2 W everywhere. Each counts in full, so the nearer wins though it comes
// second (counted up to a cap of 2 W, as they once were, both would cost the same).
TEST(Supports, AFaceWhoseNeighboursAreAllWrongJoinsTheLeastWrong) {
  auto [maps, raster_plan, front, top] = sliced_box();
  ASSERT_EQ(raster_plan.faces.size(), 4u);
  const auto far_left = static_cast<std::int32_t>(raster_plan.faces.size()), near_right = far_left + 1;
  raster_plan.faces.push_back({.orientation = Orientation::H, .depth_mm = 90});
  raster_plan.faces.push_back({.orientation = Orientation::H, .depth_mm = 65});
  for (int r = 0; r < raster_plan.face.rows; ++r)
    for (int c = 0; c < raster_plan.face.cols; ++c)
      if (std::int32_t& f = raster_plan.face(c, r); f == top) {
        f = maps.grid.X(c) < 105 ? far_left : near_right;
        ++raster_plan.faces[static_cast<std::size_t>(f)].pixels;
      }
  raster_plan.faces[static_cast<std::size_t>(top)].pixels = 0;
  ASSERT_GT(raster_plan.faces[static_cast<std::size_t>(far_left)].pixels, 0);
  ASSERT_GT(raster_plan.faces[static_cast<std::size_t>(near_right)].pixels, 0);
  const SupportPicture picture(maps, raster_plan);
  const std::vector<std::int32_t> faces = {front};
  const SupportPicture::Join join = picture.nearest_joins(raster_plan, faces).front();
  EXPECT_EQ(join.into, near_right);
  // What it adds is H(65)'s error at every pixel, less what the front shows there now (its own plane).
  const double pixel_mm2 = 1 / (maps.grid.px_per_mm * maps.grid.px_per_mm);
  double added = 0;
  for (int r = 0; r < maps.grid.rows; ++r)
    for (int c = 0; c < maps.grid.cols; ++c)
      if (raster_plan.face(c, r) == front && maps.kind(c, r) == HitKind::Model) {
        const double model = maps.h_mm(c, r) + maps.d_mm(c, r), Y = maps.grid.Y(r);
        added += (std::abs(130 - Y - model) - std::abs(Y + 80 - model)) * pixel_mm2;
      }
  EXPECT_NEAR(join.error, added, 1e-3 * added);
}

// A face shared among its neighbours goes to each where its plane shows the model best. The box's
// front (key Y + 80) is cut into H(40) above Y = 0, the face to share from -30 to 0, and H(10)
// below: over the face they are |2Y| and |60 + 2Y| off, equal at Y = -15. The upper half goes to
// H(40), the lower to H(10), at half the error either would add taking it whole.
TEST(Supports, AFaceSharedAmongItsNeighboursGoesToEachWhereItsPlaneShowsTheModelBest) {
  auto [maps, raster_plan, front, top] = sliced_box();
  ASSERT_EQ(raster_plan.faces.size(), 4u);
  const auto above = static_cast<std::int32_t>(raster_plan.faces.size()), below = above + 1;
  raster_plan.faces.push_back({.orientation = Orientation::H, .depth_mm = 40});
  raster_plan.faces.push_back({.orientation = Orientation::H, .depth_mm = 10});
  std::vector<PixelAt> shared;
  for (int r = 0; r < raster_plan.face.rows; ++r)
    for (int c = 0; c < raster_plan.face.cols; ++c)
      if (std::int32_t& f = raster_plan.face(c, r); f == front) {
        const double Y = maps.grid.Y(r);
        if (Y > 0 || Y < -30) {
          f = Y > 0 ? above : below;
          ++raster_plan.faces[static_cast<std::size_t>(f)].pixels;
          --raster_plan.faces[static_cast<std::size_t>(front)].pixels;
        } else {
          shared.push_back({c, r});
        }
      }
  ASSERT_FALSE(shared.empty());
  const SupportPicture picture(maps, raster_plan);
  const std::vector<std::int32_t> not_top = {top};
  const SupportPicture::Shares shares = picture.shared_join(raster_plan, shared, not_top);
  ASSERT_EQ(shares.into.size(), shared.size());
  const double pixel_mm2 = 1 / (maps.grid.px_per_mm * maps.grid.px_per_mm);
  double added = 0;
  for (std::size_t k = 0; k < shared.size(); ++k) {
    const double Y = maps.grid.Y(shared[k].r);
    EXPECT_EQ(shares.into[k], Y > -15 ? above : below) << "at Y = " << Y;
    added += std::min(std::abs(2 * Y), std::abs(60 + 2 * Y)) * pixel_mm2;  // the front shows its own plane now
  }
  EXPECT_NEAR(shares.error, added, 1e-3 * added);
  const SupportPicture::Join whole = picture.nearest_join(raster_plan, shared, not_top);
  EXPECT_LT(shares.error, 0.6 * whole.error);
}

// A join handed to the picture (SupportPicture::give) leaves it as one built afresh on the joined
// plan: the same error at every pixel, so the same added error over any box, and the hole errors
// but for the order of one sum.
TEST(Supports, APictureGivenAJoinIsThePictureOfTheJoinedPlan) {
  const auto [maps, raster_plan, front, top] = sliced_box();
  ASSERT_EQ(raster_plan.faces.size(), 4u);
  RasterPlan joined = raster_plan;
  std::vector<PixelAt> pixels;
  for (int r = 0; r < joined.face.rows; ++r)
    for (int c = 0; c < joined.face.cols; ++c)
      if (std::int32_t& f = joined.face(c, r); f == front) pixels.push_back({c, r}), f = top;
  joined.faces[static_cast<std::size_t>(top)].pixels += joined.faces[static_cast<std::size_t>(front)].pixels;
  joined.faces[static_cast<std::size_t>(front)].pixels = 0;
  SupportPicture given(maps, raster_plan);
  given.give(front, top, joined.faces[static_cast<std::size_t>(top)], pixels);
  const SupportPicture fresh(maps, joined);
  const int c0 = pixels.front().c, r0 = pixels.front().r, c1 = pixels.back().c + 1, r1 = pixels.back().r + 1;
  for (const auto& [orientation, depth] : {std::pair{Orientation::V, 20.0}, std::pair{Orientation::H, 70.0}})
    for (const PixelRect box : {PixelRect{c0, c1, r0, r1}, {c0, c0 + 12, r0 - 40, r1}})
      EXPECT_EQ(given.added_error(orientation, depth, box), fresh.added_error(orientation, depth, box));
  EXPECT_NEAR(given.hole_error(top), fresh.hole_error(top), 1e-9 * fresh.hole_error(top));
  EXPECT_EQ(given.hole_error(front), 0.0);
  EXPECT_EQ(fresh.hole_error(front), 0.0);
}

// So is a picture given shares, one give per neighbour: the box's front, its upper part (Y > -15)
// to its top H(50) and the rest to the floor.
TEST(Supports, APictureGivenSharesIsThePictureOfTheSharedPlan) {
  const auto [maps, raster_plan, front, top] = sliced_box();
  ASSERT_EQ(raster_plan.faces.size(), 4u);
  RasterPlan shared = raster_plan;
  std::vector<PixelAt> upper, lower;
  for (int r = 0; r < shared.face.rows; ++r)
    for (int c = 0; c < shared.face.cols; ++c)
      if (std::int32_t& f = shared.face(c, r); f == front) {
        const bool up = maps.grid.Y(r) > -15;
        (up ? upper : lower).push_back({c, r});
        f = up ? top : kFloorFace;
        ++shared.faces[static_cast<std::size_t>(f)].pixels;
      }
  ASSERT_FALSE(upper.empty());
  ASSERT_FALSE(lower.empty());
  shared.faces[static_cast<std::size_t>(front)].pixels = 0;
  SupportPicture given(maps, raster_plan);
  given.give(front, top, shared.faces[static_cast<std::size_t>(top)], upper);
  given.give(front, kFloorFace, shared.faces[static_cast<std::size_t>(kFloorFace)], lower);
  const SupportPicture fresh(maps, shared);
  const int c0 = upper.front().c, r0 = upper.front().r, c1 = lower.back().c + 1, r1 = lower.back().r + 1;
  for (const auto& [orientation, depth] : {std::pair{Orientation::V, 20.0}, std::pair{Orientation::H, 70.0}})
    for (const PixelRect box : {PixelRect{c0, c1, r0, r1}, {c0, c0 + 12, r0 - 40, r1}})
      EXPECT_EQ(given.added_error(orientation, depth, box), fresh.added_error(orientation, depth, box));
  for (const std::int32_t f : {top, std::int32_t{kFloorFace}})
    EXPECT_NEAR(given.hole_error(f), fresh.hole_error(f), 1e-9 * std::abs(fresh.hole_error(f)));
  EXPECT_EQ(given.hole_error(front), 0.0);
}

// A model's sliced plan, and the likeness of the supports each frame chooses on it.
struct FramesChosen {
  DesignResult sliced;
  Likeness first;
  std::optional<Likeness> other;  // none where the plan has one frame
};
FramesChosen frames_chosen(const char* model, UpAxis up) {
  const DesignOptions options;
  FramesChosen chosen{sliced_design(model, up), {}, {}};
  DesignResult& s = chosen.sliced;
  const auto likeness_of = [&](const Plan& plan) {
    return likeness(s.maps, card_view(s.maps.grid, plan), options.slice.min_strip_mm);
  };
  chosen.first = likeness_of(add_supports(s.maps, s.raster_plan, options.sheet, options.plan, options.supports).plan);
  if (const std::optional<SupportedPlan> other =
          add_supports_in_other_frame(s.maps, s.raster_plan, options.sheet, options.plan, options.supports))
    chosen.other = likeness_of(other->plan);
  return chosen;
}

// Where the supports chosen first cost the likeness more than 1 W of p95 over the sliced plan, the
// other frame's choice is tried too, and the design keeps the one that shows the model better. The
// water tower's first choice costs it 4.1 W (6.32 W against 2.24 W sliced); the other's, 5.83 W.
TEST(Supports, WhereSupportsCostOverAStripWidthTheOtherFramesChoiceIsTriedAndTheBetterKept) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const FramesChosen frames = frames_chosen("arch_water_tower.obj", UpAxis::Y);
  ASSERT_TRUE(frames.other.has_value());
  ASSERT_GT(frames.first.p95_W, frames.sliced.sliced_likeness.p95_W + 1);
  EXPECT_NE(frames.first.p95_W, frames.other->p95_W);
  DesignOptions options;
  options.placement.up = UpAxis::Y;
  options.tip_rounds = 0;        // the plan as supported: tips parted off later move its picture a hair,
  options.refit_planes = false;  // planes refit more
  options.spread_fold_pairs = false;
  const DesignResult designed = design(test::models_dir() / "arch_water_tower.obj", options);
  EXPECT_EQ(designed.supports.frames, 2);
  EXPECT_EQ(designed.likeness.p95_W, std::min(frames.first.p95_W, frames.other->p95_W));
  expect_exact_and_standing(designed.plan);
  // The capitol's supports cost it nothing (0.88 W, sliced 0.89 W): one frame.
  EXPECT_EQ(standing_design("seedlike/capitol.stl").supports.frames, 1);
}

// The faces a plan gave to neighbours whose planes added more than `cap_W` of error per pixel of the
// face, on average (to a hair: the loop divides the sum by the pixels, the report by the area).
int joined_farther_than(const SupportReport& report, double W, double cap_W) {
  return static_cast<int>(std::ranges::count_if(report.joined_faces, [&](const JoinedFace& joined) {
    return joined.joined_cost * W / joined.area_mm2 > cap_W + 1e-9;
  }));
}

// arch_city_block's towers went, join after join, into shelves far off the model: faces no support
// held, each given to the neighbour that showed it best then (a cascade). With joins capped
// (SupportOptions::join_error_cap_W) no face goes to a neighbour whose plane adds more than the
// cap: it is held where that costs no more than its hole, or cut out.
TEST(Supports, WithJoinsCappedNoFaceGoesToANeighbourFartherOffThanTheCap) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignResult s = sliced_design("arch_city_block.obj", UpAxis::Z);
  const DesignOptions options;
  const double W = options.slice.min_strip_mm;
  SupportOptions capped = options.supports;
  const std::optional<SupportedPlan> uncapped =
      add_supports_in_other_frame(s.maps, s.raster_plan, options.sheet, options.plan, capped);
  capped.join_error_cap_W = 3;
  const std::optional<SupportedPlan> held =
      add_supports_in_other_frame(s.maps, s.raster_plan, options.sheet, options.plan, capped);
  ASSERT_TRUE(uncapped && held);
  EXPECT_GT(joined_farther_than(uncapped->report, W, 3), 0) << "uncapped, some face goes farther";
  EXPECT_EQ(joined_farther_than(held->report, W, 3), 0);
  EXPECT_FALSE(held->report.joined_faces.empty()) << "joins within the cap still happen";
  expect_exact_and_standing(held->plan);
}

// Where both frames' supports cost the likeness over 1 W of p95 and gave faces to neighbours more
// than 3 W off, the other frame is tried a third time with such joins capped, and the best of the
// three plans kept: arch_city_block 5.53 W -> 4.39 W (sliced 1.17 W), better than either frame.
TEST(Supports, WhereBothFramesGaveFacesFarAwayATryWithJoinsCappedIsKeptWhereBetter) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.tip_rounds = 0;  // the plan as supported
  const DesignResult designed = standing_design("arch_city_block.obj", options);
  EXPECT_EQ(designed.supports.frames, 3);
  const FramesChosen frames = frames_chosen("arch_city_block.obj", UpAxis::Z);
  ASSERT_TRUE(frames.other.has_value());
  const double bound = frames.sliced.sliced_likeness.p95_W + 1;
  ASSERT_GT(std::min(frames.first.p95_W, frames.other->p95_W), bound);
  EXPECT_LT(designed.likeness.p95_W, std::min(frames.first.p95_W, frames.other->p95_W));
  EXPECT_LT(designed.likeness.p95_W, 5.0);
}

// Passes of rounds that held nothing are undone: the slices go back to those of the last exact
// verdict. The plan kept must be the exact plan of the slices kept, built afresh: no pass, undone
// or not, may leave them apart. (Tips parted off after the supports change the lines, not the
// slices: the plan here is the plan as supported.)
TEST(Supports, ThePlanKeptIsTheExactPlanOfTheSlicesKept) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Y;
  options.tip_rounds = 0;
  const DesignResult r = standing_design("res_bunny_low.obj", options);
  ASSERT_GT(r.supports.passes_undone, 0) << "a design with undone passes";
  const Plan fresh = build_plan(r.maps, r.raster_plan, DesignOptions{}.sheet, PlanOptions{});
  EXPECT_EQ(fresh.validity.status, r.plan.validity.status);
  EXPECT_EQ(fresh.lines.size(), r.plan.lines.size());
  EXPECT_EQ(fresh.cut_mm, r.plan.cut_mm);
  EXPECT_EQ(fresh.mountain_mm, r.plan.mountain_mm);
  EXPECT_EQ(fresh.valley_mm, r.plan.valley_mm);
}

}  // namespace
}  // namespace origamic

namespace origamic {
namespace {

// A support shorter than W leaves a strip narrower than W between its two parallel folds (issue
// 23): the ear search's edge for it costs the short support cost more, beside the split cost of the
// faces it cuts in two; the picture's part stays the candidate's own.
TEST(Supports, AnEarThroughASupportShorterThanWCostsTheShortSupportCostMore) {
  SupportOptions options;
  const double W = 3;
  // An H support at h = 50 from a V face at d = 40 back to one at d = 37.5: its folds 2.5 mm apart.
  Candidate c;
  c.face = 2, c.target = 3, c.cost = 1.5;
  c.near = {50, 40}, c.far = {50, 37.5};
  const std::vector<std::uint8_t> stands = {1, 1, 0, 0, 1};
  const SupportEdge short_one = support_edge(c, stands, options, W);
  EXPECT_EQ(short_one.face_Y, 10);
  EXPECT_EQ(short_one.target_Y, 12.5);
  EXPECT_EQ(short_one.cost, 1.5 + options.short_support_cost_mm);
  EXPECT_GT(options.short_support_cost_mm, 0);
  EXPECT_EQ(short_one.picture, 1.5) << "the picture's part is the candidate's own";
  // W apart, or a rounding short of it: no more.
  c.far = {50, 37};
  EXPECT_EQ(support_edge(c, stands, options, W).cost, 1.5);
  c.far = {50, 37 + kFoldLineTolerance_mm / 2};
  EXPECT_EQ(support_edge(c, stands, options, W).cost, 1.5);
  // Down the plan, a V support from an H face at h = 20 to one at h = 18: 2 mm apart.
  c.near = {20, 40}, c.far = {18, 40};
  EXPECT_EQ(support_edge(c, stands, options, W).cost, 1.5 + options.short_support_cost_mm);
  // A face it cuts in two costs the split cost, ten times that where it stands.
  c.cuts = {3, 4};
  EXPECT_EQ(support_edge(c, stands, options, W).cost, 1.5 + 11 * options.split_cost_mm + options.short_support_cost_mm);
  options.short_support_cost_mm = 0;
  EXPECT_EQ(support_edge(c, stands, options, W).cost, 1.5 + 11 * options.split_cost_mm);
}

// A box floats in front of the back plane; behind the left part of its top stands a lower box C
// against the back plane, whose top H(66) the 45-degree view sees just above the box's top. From
// the top's back edge a support reaches the back plane, 18.6 mm away, either across C's top or
// over bare back plane right of C: equally long, so the old cost (length) took the first it found,
// from the left; the picture's cost takes the second.
TEST(Supports, ASupportThroughTheBackPlaneIsChosenOverAnEquallyLongOneAcrossAVisibleFace) {
  const Sheet sheet;
  const RayScene scene(
      test::merged(test::box({60, 41.3, 18.6}, {150, 77.9, 47.1}), test::box({65, 0, 0}, {105, 66, 8})));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan raster_plan = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  const ExactPlan exact_plan(maps, raster_plan, sheet, PlanOptions{});
  std::int32_t top = -1, front = -1, c_top = -1;
  for (std::size_t f = 2; f < raster_plan.faces.size(); ++f) {
    const RasterFace& face = raster_plan.faces[f];
    if (face.orientation == Orientation::H && face.depth_mm == 77.9) top = static_cast<std::int32_t>(f);
    if (face.orientation == Orientation::V && face.depth_mm == 47.1) front = static_cast<std::int32_t>(f);
    if (face.orientation == Orientation::H && face.depth_mm == 66) c_top = static_cast<std::int32_t>(f);
  }
  ASSERT_GE(top, 0);
  ASSERT_GE(front, 0);
  ASSERT_GE(c_top, 0);
  // Both kinds of candidate are there, as long, to the back plane.
  const std::vector<Candidate> up =
      nearest(leaving(support_candidates({maps, raster_plan, exact_plan, {}, {}}, {top}, SupportReach{}), top, true));
  const int c_from = static_cast<int>(65 * maps.grid.px_per_mm), c_to = static_cast<int>(105 * maps.grid.px_per_mm);
  const auto across_c = std::ranges::find_if(up, [&](const Candidate& c) { return c.c0 > c_from && c.c1 < c_to; });
  const auto bare = std::ranges::find_if(up, [&](const Candidate& c) { return c.c0 > c_to; });
  ASSERT_NE(across_c, up.end());
  ASSERT_NE(bare, up.end());
  EXPECT_EQ(across_c->target, kBackFace);
  EXPECT_EQ(bare->target, kBackFace);
  EXPECT_EQ(across_c->r1 - across_c->r0, bare->r1 - bare->r0) << "equally long";
  EXPECT_GT(across_c->picture_mm, 1.0);
  EXPECT_EQ(bare->picture_mm, 0);
  EXPECT_GT(across_c->cost, bare->cost);
  // The round holds the top by the back plane, beside C.
  const SupportChoice choice = choose(maps, raster_plan, exact_plan, verdicts_of(exact_plan.verdict()), {top, front});
  int from_top = 0;
  for (const Candidate& s : choice.supports) {
    if (s.face != top) continue;
    ++from_top;
    EXPECT_EQ(s.target, kBackFace);
    EXPECT_TRUE(s.c1 <= c_from || s.c0 >= c_to) << "over bare back plane, not C's top: columns " << s.c0 << "-" << s.c1;
  }
  EXPECT_EQ(from_top, 1);
}

// A dome's top is held by one support over the dome's back to the back plane, the rings below it
// by the chain they fold into: the old greedy choice cut the top out (a hole where the dome is
// highest) and painted a support per ring across the back.
TEST(Supports, ADomesTopStandsAndTheCardStaysCloseToTheModel) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = standing_design("seedlike/sphere.stl");
  std::size_t top = r.maps.kind.size();  // the model pixel highest above the floor
  for (std::size_t i = 0; i < r.maps.kind.size(); ++i)
    if (r.maps.kind.values[i] == HitKind::Model &&
        (top == r.maps.kind.size() || r.maps.h_mm.values[i] > r.maps.h_mm.values[top]))
      top = i;
  ASSERT_LT(top, r.maps.kind.size());
  EXPECT_EQ(r.card.surface.values[top], CardSurface::Model);
  EXPECT_LE(likeness_error_map(r.maps, r.card).values[top], r.raster_plan.min_strip_mm);
  EXPECT_LE(r.likeness.p95_W, 2.0);
  EXPECT_LE(r.likeness.cut_out_share, 0.03);
  EXPECT_LE(r.likeness.support_share, 0.1);
}

// The plan is the same on one thread as on all: the passes in parallel gather by fixed bands and
// indices, and nothing reads what another thread may not have written yet.
TEST(Supports, ThePlanDoesNotDependOnTheThreads) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  const auto model = test::models_dir() / "seedlike/torus.stl";
  const DesignResult all = design(model, options);
  const DesignResult one = [&] {
    const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    return design(model, options);
  }();
  EXPECT_EQ(one.raster_plan.face.values, all.raster_plan.face.values);
  EXPECT_EQ(one.supports.supports, all.supports.supports);
  ASSERT_EQ(one.plan.lines.size(), all.plan.lines.size());
  for (std::size_t i = 0; i < one.plan.lines.size(); ++i) {
    EXPECT_EQ(one.plan.lines[i].kind, all.plan.lines[i].kind) << "line " << i;
    const std::vector<PlanPoint>&a = one.plan.lines[i].points, &b = all.plan.lines[i].points;
    ASSERT_EQ(a.size(), b.size()) << "line " << i;
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_TRUE(a[k].X == b[k].X && a[k].Y == b[k].Y) << "line " << i << " point " << k;
  }
}

// Why supports stopped is an enum with its counts; the report says it in words.
TEST(Supports, TheStopReasonSaysWhyInWords) {
  SupportReport report;
  EXPECT_EQ(stop_reason(report), "");
  report.stop = SupportStop::NoProgress;
  report.stop_faces = 12;
  EXPECT_EQ(stop_reason(report), "12 faces still invalid: no progress in 3 rounds");
  report.stop = SupportStop::RoundBound;
  report.round_bound = 71;
  EXPECT_EQ(stop_reason(report), "12 faces still invalid after 71 rounds (the loop's bound)");
  report.stop = SupportStop::Unreachable;
  report.stop_loose_pieces = 2;
  report.stop_at_quota = true;
  EXPECT_EQ(stop_reason(report),
            "12 faces invalid and no support reaches them; 2 loose pieces of the back plane or the floor; cutting "
            "them out would remove over a quarter of the model");
  report.stop = SupportStop::ExactInvalid;
  report.stop_loose_pieces = 0, report.stop_at_quota = false;
  EXPECT_EQ(stop_reason(report), "12 faces invalid in the exact plan");
}

}  // namespace
}  // namespace origamic
