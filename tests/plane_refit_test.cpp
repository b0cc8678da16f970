// SPDX-License-Identifier: GPL-3.0-or-later
// Planes refit once supports hold every face (issue 22, plane_refit.hpp): a face showing the model
// from a plane off it moves onto the plane that shows it best, its folds with it, where the exact
// plan still stands.
#include "plane_refit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <set>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/likeness.hpp"
#include "raster_card.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

// A box's front, moved 4 mm behind the model (its folds with it), shows the model 8 mm off: the
// refit moves it back onto the model, and its folds onto Y = h - d and -d again.
TEST(PlaneRefit, ABoxFrontMovedBehindTheModelMovesBackOntoIt) {
  const RayScene scene(test::box({40, 0, 0}, {150, 60, 40}));
  const Sheet sheet;
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan sliced = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  ASSERT_EQ(sliced.faces.size(), 4u);
  const std::int32_t front = sliced.faces[2].orientation == Orientation::V ? 2 : 3;
  const std::int32_t top = 5 - front;
  ASSERT_NEAR(sliced.faces[front].depth_mm, 40, 1e-6);
  const double tolerance = fold_snap_tolerance_mm(PlanOptions{}, sliced, maps.grid);
  std::optional<RasterPlan> behind = move_plane(sliced, maps.grid, front, 36, tolerance, 1);
  ASSERT_TRUE(behind.has_value());
  SupportedPlan supported{*behind, build_plan(maps, *behind, sheet, PlanOptions{}), {}};
  ASSERT_TRUE(plan_stands(supported.plan, false));
  const double W = sliced.min_strip_mm;
  EXPECT_NEAR(likeness(maps, card_view(maps.grid, supported.plan), W).p95_mm, 8, 0.01);

  const SupportedPlan refit = refit_planes(maps, std::move(supported), sheet, PlanOptions{}, false);
  ASSERT_EQ(refit.report.planes_refit.size(), 1u);
  const RefitPlane& moved = refit.report.planes_refit.front();
  EXPECT_EQ(moved.orientation, Orientation::V);
  EXPECT_FALSE(moved.support);
  EXPECT_EQ(moved.from_mm, 36);
  EXPECT_NEAR(moved.to_mm, 40, 1e-4);
  EXPECT_EQ(refit.raster_plan.faces[front].depth_mm, moved.to_mm);
  EXPECT_TRUE(plan_stands(refit.plan, false));
  EXPECT_LT(likeness(maps, card_view(maps.grid, refit.plan), W).p95_mm, 0.05);
  // The point reported lies in the front.
  const PixelGrid& grid = maps.grid;
  const int col = static_cast<int>(moved.at.X * grid.px_per_mm);
  const int row = static_cast<int>(std::lround(grid.rows_above_fold - 0.5 - moved.at.Y * grid.px_per_mm));
  EXPECT_EQ(refit.raster_plan.face(col, row), front);
  // Its folds on their lines, across the box's width (x 40-150): with the top at Y = h - d, with
  // the floor at Y = -d.
  const double h = refit.raster_plan.faces[top].depth_mm;
  const auto fold_span = [&](LineKind kind, double Y) {
    double lo = 1e300, hi = -1e300;
    for (const PlanPolyline& line : refit.plan.lines)
      if (line.kind == kind)
        for (const PlanPoint& p : line.points)
          if (std::abs(p.Y - Y) < 1e-9) lo = std::min(lo, p.X), hi = std::max(hi, p.X);
    return std::pair{lo, hi};
  };
  const auto [mountain_lo, mountain_hi] = fold_span(LineKind::Mountain, h - moved.to_mm);
  const auto [valley_lo, valley_hi] = fold_span(LineKind::Valley, -moved.to_mm);
  EXPECT_LE(mountain_lo, 40.5);
  EXPECT_GE(mountain_hi, 149.5);
  EXPECT_LE(valley_lo, 40.5);
  EXPECT_GE(valley_hi, 149.5);
}

// A plan whose faces show the model as well as their planes can keeps them: the sliced box.
TEST(PlaneRefit, APlanThatFitsTheModelIsLeftAsItIs) {
  const RayScene scene(test::box({40, 0, 0}, {150, 60, 40}));
  const Sheet sheet;
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan sliced = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  SupportedPlan supported{sliced, build_plan(maps, sliced, sheet, PlanOptions{}), {}};
  const SupportedPlan refit = refit_planes(maps, supported, sheet, PlanOptions{}, false);
  EXPECT_TRUE(refit.report.planes_refit.empty());
  EXPECT_EQ(refit.raster_plan.face.values, sliced.face.values);
}

// A round shaft under a box that overhangs it in front: the shaft's slices, which no support holds
// but through the box, go to one plane; refit, it shows the shaft better, and the card stands.
TEST(PlaneRefit, AShaftUnderAnOverhangShowsTheModelBetterRefit) {
  constexpr int sides = 24;
  test::Floor shaft;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    shaft.push_back({105 + 12 * std::cos(a), 50 + 12 * std::sin(a)});
  }
  const TriangleMesh model =
      test::merged(test::prism(shaft, 0, 60), test::prism({{70, 20}, {140, 20}, {140, 90}, {70, 90}}, 60, 90));
  const auto designed = [&](bool refit) {
    DesignOptions options;
    options.placement.scale = 1;
    options.placement.offset_mm = glm::dvec3(0.0);
    options.refit_planes = refit;
    return design(LoadedMesh{.mesh = model, .format = "obj"}, options);
  };
  const DesignResult supported = designed(false), refit = designed(true);
  ASSERT_FALSE(refit.supports.planes_refit.empty());
  EXPECT_TRUE(refit.plan.validity.ok());
  EXPECT_LT(refit.likeness.p95_W, supported.likeness.p95_W - 0.1);
  EXPECT_LE(refit.narrow_strips.size(), supported.narrow_strips.size());
  // Each face refit is in its new plane in the exact plan.
  for (const RefitPlane& moved : refit.supports.planes_refit) {
    bool found = false;
    for (const PlanRegion& region : refit.plan.regions)
      found |= region.orientation == moved.orientation && std::abs(region.depth_mm - moved.to_mm) < 1e-9;
    EXPECT_TRUE(found) << moved.from_mm << " -> " << moved.to_mm;
  }
}

// Pass after pass: the chapel's plan as supported at W = 4 mm (no plane refit, no fold pair spread,
// no tip parted), refit once, shows the model better; refit again on the plan that pass left, more
// faces move and it shows the model better still; the passes end where one moves none, and
// refitting their plan again moves nothing either.
TEST(PlaneRefit, ASecondPassFindsPlanesTheFirstLeft) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.slice.min_strip_mm = 4;
  options.refit_planes = options.spread_fold_pairs = false;
  options.tip_rounds = 0;
  const DesignResult designed = design(test::models_dir() / "seedlike/chapel.stl", options);
  const SupportedPlan supported{designed.raster_plan, designed.plan, designed.supports};
  const bool dangling = options.supports.allow_dangling;
  const double W = options.slice.min_strip_mm;
  const auto p95_W = [&](const SupportedPlan& s) {
    return likeness(designed.maps, card_view(designed.maps.grid, s.plan), W).p95_W;
  };
  const auto refit = [&](const SupportedPlan& plan, int passes) {
    return refit_planes(designed.maps, plan, options.sheet, options.plan, dangling, {.passes = passes});
  };
  const SupportedPlan once = refit(supported, 1), twice = refit(supported, 2), all = refit(supported, 8);
  EXPECT_LT(p95_W(once), p95_W(supported));
  // More faces move, each listed once however many passes moved it.
  EXPECT_GT(twice.report.planes_refit.size(), once.report.planes_refit.size());
  std::set<std::int32_t> listed;
  const PixelGrid& grid = designed.maps.grid;
  for (const RefitPlane& moved : twice.report.planes_refit) {
    const int col = static_cast<int>(moved.at.X * grid.px_per_mm);
    const int row = static_cast<int>(std::lround(grid.rows_above_fold - 0.5 - moved.at.Y * grid.px_per_mm));
    EXPECT_TRUE(listed.insert(twice.raster_plan.face(col, row)).second) << moved.at.X << ", " << moved.at.Y;
  }
  EXPECT_LT(p95_W(twice), p95_W(once));
  EXPECT_LE(p95_W(all), p95_W(twice));
  EXPECT_TRUE(plan_stands(all.plan, dangling));
  EXPECT_EQ(refit(all, 8).report.planes_refit.size(), all.report.planes_refit.size());
}

// The card's error counts built at once (a design's first card) are those added pixel by pixel: the
// same count up to every bin, the same 95th percentile and the same sum, to the last bit.
TEST(PlaneRefit, ErrorCountsBuiltAtOnceAreTheCountsAddedOneByOne) {
  constexpr double W = 3;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> error(-2 * W, 70 * W);  // some off the model, some past the last bin
  std::vector<double> errors(20000);
  for (double& e : errors) e = error(random);
  raster_card::ErrorCounts one_by_one(W);
  for (const double e : errors)
    if (e >= 0) one_by_one.add(e, 1);
  const raster_card::ErrorCounts at_once(W, errors);
  for (int b = 0; b < 1 << 14; ++b) ASSERT_EQ(at_once.up_to(b), one_by_one.up_to(b)) << "bin " << b;
  EXPECT_EQ(at_once.fares(), one_by_one.fares());
  EXPECT_GT(at_once.fares().first, 0);
}

}  // namespace
}  // namespace origamic
