// SPDX-License-Identifier: GPL-3.0-or-later
// Folds closer than W parted (issue 23, fold_spacing.hpp): across a strip between two folds they
// lie the difference of the planes beside it apart, and one of those planes moves to W from the
// other's.
#include "fold_spacing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/plan_analysis.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

// The face of a raster plan in a plane (the last of several), -1 if none.
std::int32_t face_in(const RasterPlan& plan, Orientation orientation, double depth_mm) {
  std::int32_t found = -1;
  for (std::size_t f = kFloorFace + 1; f < plan.faces.size(); ++f)
    if (plan.faces[f].orientation == orientation && std::abs(plan.faces[f].depth_mm - depth_mm) < 1e-6)
      found = static_cast<std::int32_t>(f);
  return found;
}

// Two boxes, one behind the other: the rear one's top H(60) over d = 0-30, a riser V(30) 6 mm high,
// the front one's top H(54) over d = 30-60 and its front V(60).
struct Staircase {
  RasterMaps maps;
  RasterPlan sliced;
  std::int32_t rear_top = -1, riser = -1, front_top = -1;
};
Staircase staircase(const Sheet& sheet) {
  const RayScene scene(test::merged(test::box({40, 0, 0}, {150, 60, 30}), test::box({40, 0, 30}, {150, 54, 60})));
  Staircase s{raster(scene, sheet, RasterOptions{}), {}};
  s.sliced = slice(s.maps, segment(s.maps, SegmentOptions{}), SliceOptions{});
  s.rear_top = face_in(s.sliced, Orientation::H, 60);
  s.riser = face_in(s.sliced, Orientation::V, 30);
  s.front_top = face_in(s.sliced, Orientation::H, 54);
  return s;
}

// The places between two folds under W apart that the exact analysis finds on a plan's lines.
int narrow_between_folds(const Plan& plan, double W) {
  return analyze_plan(plan.lines, {.min_strip_mm = W}).narrow_between_folds;
}

// The raster plan's exact plan, which must stand with one place between two folds closer than W,
// as spread_fold_pairs leaves it (no check of its own).
SupportedPlan spread_the_pair(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet) {
  SupportedPlan supported{raster_plan, build_plan(maps, raster_plan, sheet, PlanOptions{}), {}};
  EXPECT_TRUE(plan_stands(supported.plan, false));
  EXPECT_EQ(narrow_between_folds(supported.plan, raster_plan.min_strip_mm), 1);
  return spread_fold_pairs(maps, std::move(supported), sheet, PlanOptions{}, false, {});
}

// The front top raised to 57.1 mm leaves the riser 2.9 mm high between its two folds, under W =
// 3 mm; the pair is found, and the front top goes down to 57 mm (W from the rear top's fold), the
// nearer of the two planes to the model's.
TEST(FoldSpacing, ARiserUnderWBetweenTwoFoldsGrowsToW) {
  const Sheet sheet;
  const Staircase s = staircase(sheet);
  ASSERT_GE(s.rear_top, 0);
  ASSERT_GE(s.riser, 0);
  ASSERT_GE(s.front_top, 0);
  const PixelGrid& grid = s.maps.grid;
  const double W = s.sliced.min_strip_mm, tolerance = fold_snap_tolerance_mm(PlanOptions{}, s.sliced, grid);
  EXPECT_TRUE(fold_pairs_under_W(s.sliced, grid, tolerance).empty());

  const std::optional<RasterPlan> raised = move_plane(s.sliced, grid, s.front_top, 57.1, tolerance, 1);
  ASSERT_TRUE(raised.has_value());
  const std::vector<FoldPair> pairs = fold_pairs_under_W(*raised, grid, tolerance);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].above, s.rear_top);
  EXPECT_EQ(pairs[0].strip, s.riser);
  EXPECT_EQ(pairs[0].below, s.front_top);
  EXPECT_NEAR(pairs[0].apart_mm, 2.9, 1e-9);

  const SupportedPlan spread = spread_the_pair(s.maps, *raised, sheet);
  ASSERT_FALSE(HasFailure());
  ASSERT_EQ(spread.report.planes_spread.size(), 1u);
  const RefitPlane& moved = spread.report.planes_spread.front();
  EXPECT_EQ(moved.orientation, Orientation::H);
  EXPECT_EQ(moved.from_mm, 57.1);
  EXPECT_NEAR(moved.to_mm, 57, 1e-5);
  EXPECT_FALSE(moved.closed);
  EXPECT_EQ(spread.raster_plan.faces[s.front_top].depth_mm, moved.to_mm);
  EXPECT_TRUE(plan_stands(spread.plan, false));
  EXPECT_EQ(narrow_between_folds(spread.plan, W), 0);
  EXPECT_TRUE(fold_pairs_under_W(spread.raster_plan, grid, tolerance).empty());
  // The riser's two folds in the exact plan: the rear top's at Y = 60 - 30, the front top's W below.
  bool rear_fold = false, front_fold = false;
  for (const PlanPolyline& line : spread.plan.lines) {
    if (line.kind != LineKind::Mountain && line.kind != LineKind::Valley) continue;
    for (const PlanPoint& p : line.points) {
      rear_fold |= line.kind == LineKind::Mountain && p.Y == 30;
      front_fold |= line.kind == LineKind::Valley && std::abs(p.Y - (moved.to_mm - 30)) < 1e-9;
    }
  }
  EXPECT_TRUE(rear_fold);
  EXPECT_TRUE(front_fold);
  EXPECT_GE(30 - (moved.to_mm - 30), W);
}

// A check that refuses the plan leaves the plan as it was given.
TEST(FoldSpacing, APlanTheCheckRefusesIsLeftAsItIs) {
  const Sheet sheet;
  const Staircase s = staircase(sheet);
  const PixelGrid& grid = s.maps.grid;
  const double tolerance = fold_snap_tolerance_mm(PlanOptions{}, s.sliced, grid);
  const std::optional<RasterPlan> raised = move_plane(s.sliced, grid, s.front_top, 57.1, tolerance, 1);
  ASSERT_TRUE(raised.has_value());
  SupportedPlan supported{*raised, build_plan(s.maps, *raised, sheet, PlanOptions{}), {}};
  int asked = 0;
  const auto refuse = [&](const Plan&, const Plan&) { return ++asked, FoldSpacingVerdict{}; };
  const SupportedPlan spread = spread_fold_pairs(s.maps, std::move(supported), sheet, PlanOptions{}, false, refuse);
  EXPECT_EQ(asked, 1);
  EXPECT_TRUE(spread.report.planes_spread.empty());
  EXPECT_EQ(spread.raster_plan.faces[s.front_top].depth_mm, 57.1);
  EXPECT_EQ(spread.raster_plan.face.values, raised->face.values);
}

// A check that refuses a plan for places it adds beside one move: the pairs are spread again
// without that move, and the plan of the others kept. Two treads under W, as below, side by side:
// the check names two places worse on the left tread and none better there, then takes the plan.
TEST(FoldSpacing, AMoveBesidePlacesTheCheckNamesWorseIsNotMadeAgain) {
  const Sheet sheet;
  const auto step = [](double x0, double x1) {
    return test::merged(test::box({x0, 0, 0}, {x1, 60, 30}), test::box({x0, 0, 30}, {x1, 40, 40}));
  };
  const RayScene scene(test::merged(step(20, 90), step(120, 190)));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const PixelGrid& grid = maps.grid;
  RasterPlan treads = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  const double tolerance = fold_snap_tolerance_mm(PlanOptions{}, treads, grid);
  // The low fronts V(40), left and right by the column of their first pixel.
  std::vector<std::pair<int, std::int32_t>> fronts;
  for (std::size_t f = kFloorFace + 1; f < treads.faces.size(); ++f)
    if (treads.faces[f].orientation == Orientation::V && treads.faces[f].depth_mm == 40) {
      const auto at = std::ranges::find(treads.face.values, static_cast<std::int32_t>(f));
      fronts.emplace_back(static_cast<int>((at - treads.face.values.begin()) % grid.cols),
                          static_cast<std::int32_t>(f));
    }
  ASSERT_EQ(fronts.size(), 2u);
  std::ranges::sort(fronts);
  const std::int32_t left = fronts[0].second, right = fronts[1].second;
  for (const std::int32_t front : {left, right}) {
    std::optional<RasterPlan> back = move_plane(treads, grid, front, 32.9, tolerance, 1);
    ASSERT_TRUE(back.has_value());
    treads = std::move(*back);
  }
  ASSERT_EQ(fold_pairs_under_W(treads, grid, tolerance).size(), 2u);
  SupportedPlan supported{treads, build_plan(maps, treads, sheet, PlanOptions{}), {}};
  ASSERT_TRUE(plan_stands(supported.plan, false));

  int asked = 0;
  const auto check = [&](const Plan&, const Plan&) {
    // On the left tread (H(40) from Y = 7.1 to 10, X = 20 to 90).
    if (++asked == 1) return FoldSpacingVerdict{.worse_at = {{55, 8.5}, {60, 9}}};
    return FoldSpacingVerdict{.keep = true};
  };
  const SupportedPlan spread = spread_fold_pairs(maps, std::move(supported), sheet, PlanOptions{}, false, check);
  EXPECT_EQ(asked, 2);
  ASSERT_EQ(spread.report.planes_spread.size(), 1u);
  EXPECT_GT(spread.report.planes_spread.front().at.X, 105);
  EXPECT_NEAR(spread.raster_plan.faces[right].depth_mm, 33, 1e-5);
  EXPECT_EQ(spread.raster_plan.faces[left].depth_mm, 32.9);
  EXPECT_TRUE(plan_stands(spread.plan, false));
  EXPECT_EQ(narrow_between_folds(spread.plan, spread.raster_plan.min_strip_mm), 1);
}

// A tread under W between two folds: a low box before a tall one, its front moved from 40 to 32.9
// mm deep, leaves its top H(40) 2.9 mm deep between the tall box's front V(30) and its own. The
// front goes forward to 33 mm (W from V(30)), nearer the model's 40 mm than V(30) moved back.
TEST(FoldSpacing, ATreadUnderWBetweenTwoFoldsGrowsToW) {
  const Sheet sheet;
  const RayScene scene(test::merged(test::box({40, 0, 0}, {150, 60, 30}), test::box({40, 0, 30}, {150, 40, 40})));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan sliced = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  const std::int32_t tall_front = face_in(sliced, Orientation::V, 30), tread = face_in(sliced, Orientation::H, 40),
                     low_front = face_in(sliced, Orientation::V, 40);
  ASSERT_TRUE(tall_front >= 0 && tread >= 0 && low_front >= 0);
  const PixelGrid& grid = maps.grid;
  const double W = sliced.min_strip_mm, tolerance = fold_snap_tolerance_mm(PlanOptions{}, sliced, grid);
  const std::optional<RasterPlan> back = move_plane(sliced, grid, low_front, 32.9, tolerance, 1);
  ASSERT_TRUE(back.has_value());
  const std::vector<FoldPair> pairs = fold_pairs_under_W(*back, grid, tolerance);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].above, tall_front);
  EXPECT_EQ(pairs[0].strip, tread);
  EXPECT_EQ(pairs[0].below, low_front);
  EXPECT_NEAR(pairs[0].apart_mm, 2.9, 1e-9);

  const SupportedPlan spread = spread_the_pair(maps, *back, sheet);
  ASSERT_FALSE(HasFailure());
  ASSERT_EQ(spread.report.planes_spread.size(), 1u);
  const RefitPlane& moved = spread.report.planes_spread.front();
  EXPECT_EQ(moved.orientation, Orientation::V);
  EXPECT_EQ(moved.from_mm, 32.9);
  EXPECT_NEAR(moved.to_mm, 33, 1e-5);
  EXPECT_GE(moved.to_mm - 30, W);
  EXPECT_EQ(spread.raster_plan.faces[low_front].depth_mm, moved.to_mm);
  EXPECT_EQ(spread.raster_plan.faces[tall_front].depth_mm, 30);
  EXPECT_TRUE(plan_stands(spread.plan, false));
  EXPECT_EQ(narrow_between_folds(spread.plan, W), 0);
  // The tread's mountain fold with the low front, W below its valley fold with the tall front at
  // Y = 40 - 30.
  bool tread_front = false;
  for (const PlanPolyline& line : spread.plan.lines)
    if (line.kind == LineKind::Mountain)
      for (const PlanPoint& p : line.points) tread_front |= std::abs(p.Y - (40 - moved.to_mm)) < 1e-9;
  EXPECT_TRUE(tread_front);
}

// Two folds a pixel apart where the model is flat become one step (issue 23: "take two folds closer
// than W into one step"). The plan: a rear top H(60) over d = 0-5, a riser V(5) and a front top
// H(57) over d = 5-70, the front top then raised to 59.75 mm, a riser one pixel high left. The card
// is judged against a model whose front top is 59.75 mm high: parting the folds would move a top
// 2.75 mm off its model, closing them the rear top, 4 % of the model, 0.25 mm. The riser goes, and
// the two tops are one face, folded to the back plane on Y = 59.75 and to the front on 59.75 - 70.
TEST(FoldSpacing, FoldsAPixelApartWhereTheModelIsFlatBecomeOneStep) {
  const Sheet sheet;
  const RayScene stepped(test::merged(test::box({40, 0, 0}, {150, 60, 5}), test::box({40, 0, 5}, {150, 57, 70})));
  const RayScene flat(test::merged(test::box({40, 0, 0}, {150, 60, 5}), test::box({40, 0, 5}, {150, 59.75, 70})));
  const RasterMaps stepped_maps = raster(stepped, sheet, RasterOptions{});
  const RasterMaps maps = raster(flat, sheet, RasterOptions{});
  const RasterPlan sliced = slice(stepped_maps, segment(stepped_maps, SegmentOptions{}), SliceOptions{});
  const std::int32_t rear_top = face_in(sliced, Orientation::H, 60), riser = face_in(sliced, Orientation::V, 5),
                     front_top = face_in(sliced, Orientation::H, 57);
  ASSERT_TRUE(rear_top >= 0 && riser >= 0 && front_top >= 0);
  const PixelGrid& grid = maps.grid;
  const double W = sliced.min_strip_mm, tolerance = fold_snap_tolerance_mm(PlanOptions{}, sliced, grid);
  const std::optional<RasterPlan> raised = move_plane(sliced, grid, front_top, 59.75, tolerance, 1);
  ASSERT_TRUE(raised.has_value());
  const std::vector<FoldPair> pairs = fold_pairs_under_W(*raised, grid, tolerance);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].strip, riser);
  EXPECT_NEAR(pairs[0].apart_mm, 0.25, 1e-9);
  const std::int64_t tops_and_riser =
      raised->faces[rear_top].pixels + raised->faces[riser].pixels + raised->faces[front_top].pixels;

  const SupportedPlan spread = spread_the_pair(maps, *raised, sheet);
  ASSERT_FALSE(HasFailure());
  ASSERT_EQ(spread.report.planes_spread.size(), 1u);
  const RefitPlane& moved = spread.report.planes_spread.front();
  EXPECT_EQ(moved.orientation, Orientation::H);
  EXPECT_EQ(moved.from_mm, 60);
  EXPECT_EQ(moved.to_mm, 59.75);
  EXPECT_TRUE(moved.closed);
  // One H face at 59.75 mm, of all the tops' and the riser's pixels; no V(5).
  std::vector<const RasterFace*> tops;
  for (const RasterFace& face : spread.raster_plan.faces) {
    EXPECT_FALSE(face.orientation == Orientation::V && face.depth_mm == 5);
    if (face.orientation == Orientation::H && face.depth_mm > 0) tops.push_back(&face);
  }
  ASSERT_EQ(tops.size(), 1u);
  EXPECT_EQ(tops[0]->depth_mm, 59.75);
  // The back plane took the row its fold with the rear top came down by, across the top's 110 mm.
  EXPECT_EQ(tops[0]->pixels, tops_and_riser - 110 * 4);
  EXPECT_EQ(spread.raster_plan.faces[kBackFace].pixels, raised->faces[kBackFace].pixels + 110 * 4);
  EXPECT_TRUE(fold_pairs_under_W(spread.raster_plan, grid, tolerance).empty());
  EXPECT_TRUE(plan_stands(spread.plan, false));
  EXPECT_EQ(narrow_between_folds(spread.plan, W), 0);
  // Its folds: to the back plane on Y = 59.75, to the front V(70) on 59.75 - 70; none between.
  int back_fold = 0, front_fold = 0, between = 0;
  for (const PlanPolyline& line : spread.plan.lines) {
    if (line.kind != LineKind::Mountain && line.kind != LineKind::Valley) continue;
    for (const PlanPoint& p : line.points) {
      back_fold += p.Y == 59.75, front_fold += p.Y == 59.75 - 70;
      between += p.Y > 59.75 - 70 && p.Y < 59.75 && p.Y != 0;  // the main fold beside the boxes aside
    }
  }
  EXPECT_GT(back_fold, 0);
  EXPECT_GT(front_fold, 0);
  EXPECT_EQ(between, 0);
}

// The options of a design of a model of ../shared/models (up z) that ends where the supports leave
// the plan: no fold pairs spread, no tips parted.
DesignOptions as_the_supports_leave_it() {
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.spread_fold_pairs = false;
  options.tip_rounds = 0;
  return options;
}

// A design as the supports leave it (as_the_supports_leave_it) with its fold pairs spread.
SupportedPlan spread_as_supported(const DesignResult& supported, const FoldSpacingOptions& spreading) {
  const DesignOptions options = as_the_supports_leave_it();
  return spread_fold_pairs(supported.maps, {supported.raster_plan, supported.plan, {}}, options.sheet, options.plan,
                           false, {}, spreading);
}

// Where the exact plan of all the moves does not stand (it snaps folds the raster plan's do not
// show), the moves beside the faces it leaves unheld are taken back and the rest built again:
// ../shared/models' motorbike, whose 19 moves were all lost for one face, keeps most of them.
TEST(FoldSpacing, MovesBesideAFaceTheExactPlanLeavesUnheldAreTakenBackAndTheRestKept) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = design(test::models_dir() / "bad_motorbike.obj.gz", as_the_supports_leave_it());
  const double W = r.raster_plan.min_strip_mm;
  ASSERT_TRUE(plan_stands(r.plan, false));
  const int pairs_before = narrow_between_folds(r.plan, W);
  // Every face a move takes rows from keeping W of its run, as the moves below were counted.
  const auto spread_with = [&](int exact_builds) {
    return spread_as_supported(r, {.exact_builds = exact_builds, .giver_keeps_px = 0});
  };
  const SupportedPlan once = spread_with(1);
  EXPECT_TRUE(once.report.planes_spread.empty()) << "the case this test is about: all moves at once do not stand";
  EXPECT_EQ(once.raster_plan.face.values, r.raster_plan.face.values);
  const SupportedPlan again = spread_with(3);
  EXPECT_EQ(again.report.planes_spread.size(), 17u) << "19 moves, 2 of them beside the face left unheld";
  EXPECT_TRUE(plan_stands(again.plan, false));
  EXPECT_LT(narrow_between_folds(again.plan, W), pairs_before);
  EXPECT_TRUE(analyze_plan(again.plan.lines, AnalysisOptions{}).valid()) << "its lines stand too";
}

// Where no move of a face beside a strip between two folds under W apart parts it while every face
// the move takes rows from keeps W of its run there, one that leaves such a face 2 px may:
// ../shared/models' prim_torus at W = 3 mm, as its supports leave it.
TEST(FoldSpacing, GiversKeepingUnderWPartPairsThatGiversKeepingWCannot) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = design(test::models_dir() / "prim_torus.stl", as_the_supports_leave_it());
  const double W = r.raster_plan.min_strip_mm;
  ASSERT_TRUE(plan_stands(r.plan, false));
  const auto spread_with = [&](int giver_keeps_px) {
    return spread_as_supported(r, {.giver_keeps_px = giver_keeps_px});
  };
  const SupportedPlan keeping_W = spread_with(0), keeping_less = spread_with(2);
  const int before = narrow_between_folds(r.plan, W), after_W = narrow_between_folds(keeping_W.plan, W),
            after_less = narrow_between_folds(keeping_less.plan, W);
  const double tolerance = fold_snap_tolerance_mm(PlanOptions{}, r.raster_plan, r.maps.grid);
  EXPECT_EQ(before, 7);
  EXPECT_EQ(after_W, 4) << "the case this test is about: pairs that every face keeping W leaves";
  EXPECT_EQ(fold_pairs_under_W(keeping_W.raster_plan, r.maps.grid, tolerance).size(), 4u);
  EXPECT_EQ(after_less, 0);
  EXPECT_TRUE(fold_pairs_under_W(keeping_less.raster_plan, r.maps.grid, tolerance).empty());
  EXPECT_EQ(keeping_W.report.planes_spread.size(), 3u);
  EXPECT_EQ(keeping_less.report.planes_spread.size(), 7u);
  EXPECT_TRUE(plan_stands(keeping_less.plan, false));
  EXPECT_TRUE(analyze_plan(keeping_less.plan.lines, AnalysisOptions{}).valid()) << "its lines stand too";
}

// A model of ../shared/models (up z) designed at the default options, places narrower than W allowed.
DesignResult designed_allowing_narrow_places(const char* model) {
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.allow_narrow = true;
  return design(test::models_dir() / model, options);
}

// A spread plan is kept with as many more places in all as the pairs it parts: a strip between two
// folds cannot be folded, another place can be cut with care. ../shared/models' res_knot at
// W = 3 mm: its spread parts 15 of its 17 pairs at 12 more places (with half as many allowed, the
// whole plan was refused and all 17 stayed).
TEST(FoldSpacing, ASpreadAddingFewerPlacesThanThePairsItPartsIsKept) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = designed_allowing_narrow_places("res_knot.off");
  EXPECT_EQ(r.supports.planes_spread.size(), 15u);
  EXPECT_EQ(std::ranges::count_if(r.narrow_strips, [](const PlanProblem& p) { return p.folds_apart_mm > 0; }), 2);
  EXPECT_TRUE(plan_stands(r.plan, false));
}

// A spread plan refused for the places it adds is spread again without the moves beside them:
// ../shared/models' prim_cone at W = 3 mm, whose first spread plan did not stand and whose second
// parted 7 of its 13 pairs at 9 more places and was refused whole; its third parts 4 for fewer.
TEST(FoldSpacing, ARefusedSpreadIsSpreadAgainWithoutTheMovesBesideThePlacesItAdds) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const DesignResult r = designed_allowing_narrow_places("prim_cone.stl");
  EXPECT_EQ(r.supports.planes_spread.size(), 4u) << "none, and 13 pairs, when a refused plan was dropped whole";
  EXPECT_EQ(std::ranges::count_if(r.narrow_strips, [](const PlanProblem& p) { return p.folds_apart_mm > 0; }), 9);
  EXPECT_TRUE(plan_stands(r.plan, false));
}

// A plan the supports drew in the mirror image, its drawing in the user's frame not standing, has its
// fold pairs spread and its planes refit in that image too: bad_motorbike at W = 2 mm, whose every
// spread plan and refit had failed in the user's frame (a face V(32.38) dangling there, 17 mm^2).
TEST(FoldSpacing, APlanDrawnInTheMirrorImageIsSpreadThere) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.slice.min_strip_mm = 2;
  const DesignResult r = design(test::models_dir() / "bad_motorbike.obj.gz", options);
  ASSERT_TRUE(r.supports.drawn_in_mirror_image) << "the case this test is about";
  EXPECT_FALSE(plan_stands(build_plan(r.maps, r.raster_plan, options.sheet, options.plan), false))
      << "drawn in the user's frame, the plan does not stand";
  EXPECT_TRUE(plan_stands(r.plan, false));
  EXPECT_EQ(r.supports.planes_spread.size(), 43u) << "33 with every face the moves take rows from keeping W";
  EXPECT_EQ(r.supports.planes_refit.size(), 5u);
  EXPECT_TRUE(analyze_plan(r.plan.lines, AnalysisOptions{}).valid()) << "its lines stand too";
  // Mirrored back to the user's frame: the faces' points inside them lie on their own pixels.
  ASSERT_EQ(r.plan.faces.size(), r.raster_plan.faces.size());
  int faces = 0, on_their_pixels = 0;
  for (std::size_t f = kFloorFace + 1; f < r.plan.faces.size(); ++f) {
    const PlanFace& face = r.plan.faces[f];
    if (face.area_mm2 < 20 || face.status == FaceStatus::Removed) continue;
    const auto col = static_cast<int>(std::floor(face.inside.X * r.maps.grid.px_per_mm));
    const auto row = static_cast<int>(std::floor(r.maps.grid.rows_above_fold - face.inside.Y * r.maps.grid.px_per_mm));
    ++faces, on_their_pixels += r.raster_plan.face(col, row) == static_cast<std::int32_t>(f);
  }
  EXPECT_GT(faces, 100);
  EXPECT_EQ(on_their_pixels, faces);
}

}  // namespace
}  // namespace origamic
