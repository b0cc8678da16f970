// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/placement.hpp"

#include <gtest/gtest.h>

#include "helpers.hpp"
#include "origamic/error.hpp"

namespace origamic {
namespace {

constexpr double kTol = 1e-9;

// The auto-fit contract: inside the margins, height and depth each within half the sheet less the
// margin (room for supports), resting on the floor and the back plane, centred along
// the fold, and touching at least one margin (it is the largest such scale).
void expect_auto_fit(const TriangleMesh& model, const Sheet& sheet, const PlacementOptions& options) {
  const Placement p = place(model, sheet, options);
  const TriangleMesh oa = apply(p, model);
  double lo_h = 1e300, lo_d = 1e300, hi_h = -1e300, hi_d = -1e300, lo_X = 1e300, hi_X = -1e300, lo_Y = 1e300,
         hi_Y = -1e300;
  for (const auto& q : oa.positions) {
    lo_h = std::min(lo_h, q.y);
    lo_d = std::min(lo_d, q.z);
    hi_h = std::max(hi_h, q.y);
    hi_d = std::max(hi_d, q.z);
    lo_X = std::min(lo_X, q.x);
    hi_X = std::max(hi_X, q.x);
    lo_Y = std::min(lo_Y, q.y - q.z);
    hi_Y = std::max(hi_Y, q.y - q.z);
  }
  const double m = options.margin_mm;
  EXPECT_NEAR(lo_h, 0.0, kTol);
  EXPECT_NEAR(lo_d, 0.0, kTol);
  EXPECT_GE(lo_X, m - kTol);
  EXPECT_LE(hi_X, sheet.width_mm - m + kTol);
  EXPECT_GE(lo_Y, -sheet.half_height_mm() + m - kTol);
  EXPECT_LE(hi_Y, sheet.half_height_mm() - m + kTol);
  EXPECT_LE(hi_h, sheet.half_height_mm() - m + kTol);  // room for supports up to the back plane
  EXPECT_LE(hi_d, sheet.half_height_mm() - m + kTol);  // and down to the floor
  EXPECT_NEAR((lo_X + hi_X) / 2, sheet.width_mm / 2, kTol);
  const double slack = std::min({lo_X - m, sheet.width_mm - m - hi_X, lo_Y + sheet.half_height_mm() - m,
                                 sheet.half_height_mm() - m - hi_Y, sheet.half_height_mm() - m - hi_h,
                                 sheet.half_height_mm() - m - hi_d});
  EXPECT_NEAR(slack, 0.0, kTol);
  EXPECT_NEAR(p.min_plan.Y, lo_Y, kTol);
  EXPECT_NEAR(p.max_plan.X, hi_X, kTol);
}

TEST(Placement, AutoFitWideYUpModelTouchesTheSideMargins) {
  expect_auto_fit(test::box({-7, 3, -2}, {93, 13, 8}), Sheet{}, PlacementOptions{});
}

TEST(Placement, AutoFitTallZUpModelTouchesTheTopMargin) {
  PlacementOptions options;
  options.up = UpAxis::Z;
  expect_auto_fit(test::box({0, 0, 0}, {2, 1, 50}), Sheet{}, options);
  options.margin_mm = 0;
  expect_auto_fit(test::sphere({1, 2, 3}, 4, 32, 16), Sheet{127, 177.8}, options);
}

TEST(Placement, ZUpMapsModelZToHeightAndLargestYToTheBackPlane) {
  PlacementOptions options;
  options.up = UpAxis::Z;
  options.scale = 1.0;
  const Placement p = place(test::box({0, 0, 0}, {10, 20, 30}), Sheet{}, options);
  // Model z (0..30) becomes h; model y (0..20) becomes depth, its largest y against the back plane.
  EXPECT_NEAR(p.to_oa({0, 20, 30}).y, 30.0, kTol);
  EXPECT_NEAR(p.to_oa({0, 20, 30}).z, 0.0, kTol);
  EXPECT_NEAR(p.to_oa({0, 0, 0}).z, 20.0, kTol);
  EXPECT_NEAR(p.to_oa({0, 0, 0}).y, 0.0, kTol);
}

TEST(Placement, RotationTurnsCounterClockwiseSeenFromAbove) {
  PlacementOptions options;
  options.rotate_deg = 90;
  options.scale = 1.0;
  options.offset_mm = glm::dvec3(100, 0, 50);
  const Placement p = place(test::box({0, 0, 0}, {1, 1, 1}), Sheet{}, options);
  // +x turns to -d (away from the viewer), +d to +x.
  const glm::dvec3 x = p.to_oa({1, 0, 0}) - p.to_oa({0, 0, 0});
  const glm::dvec3 d = p.to_oa({0, 0, 1}) - p.to_oa({0, 0, 0});
  EXPECT_NEAR(x.x, 0, kTol);
  EXPECT_NEAR(x.z, -1, kTol);
  EXPECT_NEAR(d.x, 1, kTol);
}

TEST(Placement, ExplicitScaleAndOffsetAreKept) {
  PlacementOptions options;
  options.scale = 2.5;
  options.offset_mm = glm::dvec3(40, 5, 10);
  const Placement p = place(test::box({0, 0, 0}, {4, 4, 4}), Sheet{}, options);
  EXPECT_EQ(p.to_oa({0, 0, 0}), glm::dvec3(40, 5, 10));
  EXPECT_EQ(p.to_oa({4, 4, 4}), glm::dvec3(50, 15, 20));
}

TEST(Placement, ProjectionLeavingTheSheetIsAnErrorNamingTheOption) {
  PlacementOptions options;
  options.scale = 1.0;
  options.offset_mm = glm::dvec3(200, 0, 0);  // x from 200 to 220 on a 210 mm sheet
  try {
    place(test::box({0, 0, 0}, {20, 20, 20}), Sheet{}, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "PlacementOptions::scale/PlacementOptions::offset_mm") << e.what();
    EXPECT_NE(std::string(e.what()).find("leaves the"), std::string::npos) << e.what();
  }
  options.offset_mm.reset();
  options.scale = 100.0;  // auto position, but far too large
  EXPECT_THROW(place(test::box({0, 0, 0}, {20, 20, 20}), Sheet{}, options), InputError);
}

TEST(Placement, ModelBelowTheFloorOrBehindTheBackPlaneIsAnError) {
  PlacementOptions options;
  options.scale = 1.0;
  options.offset_mm = glm::dvec3(100, -5, 10);
  EXPECT_THROW(place(test::box({0, 0, 0}, {20, 20, 20}), Sheet{}, options), InputError);
  options.offset_mm = glm::dvec3(100, 5, -1);
  EXPECT_THROW(place(test::box({0, 0, 0}, {20, 20, 20}), Sheet{}, options), InputError);
  options.offset_mm = glm::dvec3(100, 0, 0);
  EXPECT_NO_THROW(place(test::box({0, 0, 0}, {20, 20, 20}), Sheet{}, options));
}

TEST(Placement, AutoFitWithoutMarginTouchesTheSheetEdge) {
  PlacementOptions options;
  options.margin_mm = 0;
  expect_auto_fit(test::sphere({0, 0, 0}, 1, 32, 16), Sheet{}, options);
}

TEST(Placement, AbsurdOptionsAreRejected) {
  const TriangleMesh box = test::box({0, 0, 0}, {1, 1, 1});
  PlacementOptions options;
  options.scale = -1;
  EXPECT_THROW(place(box, Sheet{}, options), InputError);
  options = {};
  options.margin_mm = 150;
  EXPECT_THROW(place(box, Sheet{}, options), InputError);
  options = {};
  options.rotate_deg = std::nan("");
  EXPECT_THROW(place(box, Sheet{}, options), InputError);
  EXPECT_THROW(place(box, Sheet{0, 100}, PlacementOptions{}), InputError);
}

TEST(Placement, RealModelsFitForTheirUpAxis) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  for (const auto& [file, up] : {std::pair{"res_bunny.obj", UpAxis::Y}, {"prim_cylinder.stl", UpAxis::Z},
                                 {"seedlike/capitol.stl", UpAxis::Z}, {"res_armadillo.off", UpAxis::Y}}) {
    SCOPED_TRACE(file);
    PlacementOptions options;
    options.up = up;
    expect_auto_fit(load_mesh(test::models_dir() / file).mesh, Sheet{}, options);
  }
}

}  // namespace
}  // namespace origamic
