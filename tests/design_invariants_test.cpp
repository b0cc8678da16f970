// SPDX-License-Identifier: GPL-3.0-or-later
// Invariants of the whole design: the plan of a model mirrored along the main fold is the mirrored
// plan, sliced and with supports, and the plan of a model moved along the fold by whole pixels is
// the moved plan (with supports too when it moves by whole strips).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/mesh_io.hpp"
#include "origamic/plan.hpp"
#include "origamic/plan_analysis.hpp"
#include "origamic/supports.hpp"

namespace origamic {
namespace {

const std::filesystem::path kHouse = std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj";
constexpr double kScale = 15, kX = 100;  // mm per unit of the house, and where its origin goes

// A plan's segments of each kind, each with its ends in nanometres, the smaller end first, after
// mapping X (an exact map, or one rounding: nanometres absorb it). With `edges_stay`, points on the
// sheet's left and right edges keep their X: the sheet does not move with the model.
std::multiset<std::array<long long, 5>> segments(const Plan& plan, double X_sign, double X_shift,
                                                 bool edges_stay = false) {
  std::multiset<std::array<long long, 5>> out;
  const auto X_of = [&](double X) {
    return edges_stay && (X == 0 || X == plan.sheet.width_mm) ? X : X_sign * X + X_shift;
  };
  for (const PlanPolyline& line : plan.lines)
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      std::array<long long, 2> a = {std::llround(X_of(line.points[i - 1].X) * 1e6),
                                    std::llround(line.points[i - 1].Y * 1e6)};
      std::array<long long, 2> b = {std::llround(X_of(line.points[i].X) * 1e6), std::llround(line.points[i].Y * 1e6)};
      if (b < a) std::swap(a, b);
      out.insert({static_cast<long long>(line.kind), a[0], a[1], b[0], b[1]});
    }
  return out;
}

// What one set of segments has that the other has not, a few of each, for the failure message.
std::string difference(const std::multiset<std::array<long long, 5>>& a,
                       const std::multiset<std::array<long long, 5>>& b) {
  std::vector<std::array<long long, 5>> only_a, only_b;
  std::ranges::set_difference(a, b, std::back_inserter(only_a));
  std::ranges::set_difference(b, a, std::back_inserter(only_b));
  std::string text = std::to_string(only_a.size()) + " segments only in the first, " + std::to_string(only_b.size()) +
                     " only in the second";
  for (const auto* list : {&only_a, &only_b})
    for (std::size_t i = 0; i < list->size() && i < 6; ++i) {
      const auto& s = (*list)[i];
      text += (i == 0 ? (list == &only_a ? "\n first: " : "\n second: ") : " ") + std::string("[") +
              std::to_string(s[0]) + " (" + std::to_string(s[1] / 1e6) + ", " + std::to_string(s[2] / 1e6) + ")-(" +
              std::to_string(s[3] / 1e6) + ", " + std::to_string(s[4] / 1e6) + ")]";
    }
  return text;
}

// The house mirrored along the main fold (x to -x), its triangles still facing out.
TriangleMesh mirrored_along_the_fold(TriangleMesh mesh) {
  for (glm::dvec3& p : mesh.positions) p.x = -p.x;
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  mesh.corner_normals.clear();
  return mesh;
}

DesignResult design_at(const TriangleMesh& model, double x, bool supports) {
  DesignOptions options;
  options.placement.scale = kScale;
  options.placement.offset_mm = glm::dvec3(x, 0, 0);
  options.supports.enabled = supports;
  return design(LoadedMesh{.mesh = model, .format = "obj"}, options);
}

TEST(DesignInvariants, AModelMirroredAlongTheFoldGivesTheMirroredPlan) {
  const TriangleMesh house = load_mesh(kHouse).mesh;
  const TriangleMesh mirrored = mirrored_along_the_fold(house);
  const double width_mm = Sheet{}.width_mm;
  const DesignResult a = design_at(house, kX, false), b = design_at(mirrored, width_mm - kX, false);
  EXPECT_EQ(a.plan.faces.size(), b.plan.faces.size());
  const auto expected = segments(a.plan, -1, width_mm), got = segments(b.plan, 1, 0);
  EXPECT_TRUE(expected == got) << difference(expected, got);
  // With supports: one of the two chooses them on the other's mirror image.
  const DesignResult c = design_at(house, kX, true), d = design_at(mirrored, width_mm - kX, true);
  EXPECT_EQ(c.plan.faces.size(), d.plan.faces.size());
  EXPECT_TRUE(c.plan.validity.ok() && d.plan.validity.ok());
  const auto expected_supported = segments(c.plan, -1, width_mm), got_supported = segments(d.plan, 1, 0);
  EXPECT_TRUE(expected_supported == got_supported) << difference(expected_supported, got_supported);
  // One of the two chose on its mirror image; each plan is still drawn afresh from its raster plan.
  EXPECT_NE(c.supports.mirror_image, d.supports.mirror_image);
  for (const DesignResult* r : {&c, &d}) {
    const Plan drawn = build_plan(r->maps, r->raster_plan, Sheet{}, PlanOptions{});
    EXPECT_EQ(drawn.cut_mm, r->plan.cut_mm);
    EXPECT_EQ(drawn.mountain_mm, r->plan.mountain_mm);
    EXPECT_EQ(drawn.valley_mm, r->plan.valley_mm);
  }
}

// The supports mirror the maps in place to choose on the mirror image and give them back bit for bit;
// the normals, which nothing after slicing reads, are dropped unless kept, and the plan is the same.
TEST(DesignInvariants, TheMapsComeBackFromTheSupportsAsTheyWereAndTheirNormalsOnlyWhenKept) {
  const TriangleMesh house = load_mesh(kHouse).mesh;
  const double width_mm = Sheet{}.width_mm;
  std::vector<bool> chosen_on_the_mirror_image;
  for (const auto& [model, x] : {std::pair{house, kX}, {mirrored_along_the_fold(house), width_mm - kX}}) {
    const DesignResult sliced = design_at(model, x, false);  // maps no support stage has touched
    DesignOptions options;
    options.placement.scale = kScale;
    options.placement.offset_mm = glm::dvec3(x, 0, 0);
    const DesignResult dropped = design(LoadedMesh{.mesh = model, .format = "obj"}, options);
    options.keep_normals = true;
    const DesignResult kept = design(LoadedMesh{.mesh = model, .format = "obj"}, options);
    EXPECT_EQ(dropped.maps.normal.size(), 0u);
    EXPECT_EQ(sliced.maps.normal.size(), 0u);
    EXPECT_EQ(kept.maps.normal.size(), kept.maps.d_mm.size());
    EXPECT_TRUE(test::same_bytes(kept.maps.d_mm, sliced.maps.d_mm) &&
                test::same_bytes(kept.maps.h_mm, sliced.maps.h_mm) &&
                test::same_bytes(kept.maps.kind, sliced.maps.kind) &&
                test::same_bytes(kept.maps.break_right, sliced.maps.break_right) &&
                test::same_bytes(kept.maps.break_below, sliced.maps.break_below));
    const auto a = segments(dropped.plan, 1, 0), b = segments(kept.plan, 1, 0);
    EXPECT_TRUE(a == b) << difference(a, b);
    chosen_on_the_mirror_image.push_back(kept.supports.mirror_image);
  }
  EXPECT_NE(chosen_on_the_mirror_image[0], chosen_on_the_mirror_image[1]) << "one of the two mirrored its maps";
}

// The other frame's supports (add_supports_in_other_frame) are another choice, and a mirrored
// model's are the mirror image of the model's.
TEST(DesignInvariants, TheOtherFramesSupportsOfAMirroredModelAreTheMirroredOnes) {
  const TriangleMesh house = load_mesh(kHouse).mesh;
  const TriangleMesh mirrored = mirrored_along_the_fold(house);
  const double width_mm = Sheet{}.width_mm;
  DesignResult a = design_at(house, kX, false), b = design_at(mirrored, width_mm - kX, false);
  const DesignOptions options;
  const SupportedPlan first = add_supports(a.maps, a.raster_plan, options.sheet, options.plan, options.supports);
  const std::optional<SupportedPlan> other =
      add_supports_in_other_frame(a.maps, a.raster_plan, options.sheet, options.plan, options.supports);
  const std::optional<SupportedPlan> other_mirrored =
      add_supports_in_other_frame(b.maps, b.raster_plan, options.sheet, options.plan, options.supports);
  ASSERT_TRUE(other && other_mirrored);
  EXPECT_NE(first.report.mirror_image, other->report.mirror_image);
  EXPECT_TRUE(other->plan.validity.ok() && other_mirrored->plan.validity.ok());
  EXPECT_FALSE(segments(first.plan, 1, 0) == segments(other->plan, 1, 0)) << "the same supports either way";
  const auto expected = segments(other->plan, -1, width_mm), got = segments(other_mirrored->plan, 1, 0);
  EXPECT_TRUE(expected == got) << difference(expected, got);
}

TEST(DesignInvariants, AModelMovedAlongTheFoldByWholePixelsGivesTheMovedPlan) {
  const TriangleMesh house = load_mesh(kHouse).mesh;
  // One pixel (0.25 mm) sliced; a whole strip width W (12 pixels) with supports too, whose
  // candidates lie on the W-wide block columns of the sheet.
  for (const auto& [shift, supports] : {std::pair{0.25, false}, std::pair{3.0, true}}) {
    SCOPED_TRACE(std::to_string(shift) + (supports ? " mm with supports" : " mm sliced"));
    const DesignResult a = design_at(house, kX, supports), b = design_at(house, kX + shift, supports);
    EXPECT_EQ(a.plan.faces.size(), b.plan.faces.size());
    const auto expected = segments(a.plan, 1, shift, true), got = segments(b.plan, 1, 0, true);
    EXPECT_TRUE(expected == got) << difference(expected, got);
  }
}

// The design's verdict (issue 23): the plan stands, and no place is narrower than W unless the user
// allows it; allowing narrow places makes no plan that does not stand valid.
// A sphere's slices end in tips where they meet the silhouette and each other: the design parts
// off those it can, keeping the plan standing and its picture, and reports the rest as its DXF
// will read back.
TEST(DesignTips, TipsNarrowerThanWArePartedOffAndThePlanStillStands) {
  // This sphere's first round gains as it is; on the 48 x 24 sphere at W = 4 mm only once tried
  // again without the tips that made places (ARoundWhoseTipsMakeNarrowPlacesIsTriedAgainWithoutThem).
  const TriangleMesh ball = test::sphere({0, 0, 0}, 1, 96, 48);
  DesignOptions options;
  options.tip_rounds = 0;
  const DesignResult as_supported = design(LoadedMesh{.mesh = ball, .format = "obj"}, options);
  options.tip_rounds = DesignOptions{}.tip_rounds;
  const DesignResult blunted = design(LoadedMesh{.mesh = ball, .format = "obj"}, options);
  EXPECT_GT(blunted.tips_parted, 0);
  EXPECT_LT(blunted.narrow_strips.size(), as_supported.narrow_strips.size());
  EXPECT_TRUE(plan_stands(blunted.plan, false));
  EXPECT_LE(blunted.likeness.p95_W, as_supported.likeness.p95_W + 0.05);
  EXPECT_LE(blunted.likeness.mean_W, as_supported.likeness.mean_W + 0.02);
  // Read back as the files have it (Y from the sheet's lower edge): the same places, no error else.
  std::vector<PlanPolyline> lines = blunted.plan.lines;
  const double half = options.sheet.half_height_mm();
  for (PlanPolyline& line : lines)
    for (PlanPoint& p : line.points) p.Y = (p.Y + half) - half;
  const PlanAnalysis read = analyze_plan(lines, {.min_strip_mm = options.slice.min_strip_mm});
  std::size_t narrow = 0;
  for (const PlanProblem& problem : read.problems) {
    EXPECT_TRUE(problem.kind == PlanProblemKind::NarrowStrip || !is_error(problem.kind)) << problem.message;
    narrow += problem.kind == PlanProblemKind::NarrowStrip;
  }
  EXPECT_EQ(narrow, blunted.narrow_strips.size());
  // Every face of the plan is still one of the design's faces, and their areas tile the sheet.
  // Each with its face's plane, to the bit: a region placed from the lines can be an ulp off it.
  for (const PlanRegion& region : blunted.plan.regions) {
    ASSERT_GE(region.face, 0);
    const PlanFace& face = blunted.plan.faces[static_cast<std::size_t>(region.face)];
    EXPECT_EQ(region.orientation, face.orientation);
    EXPECT_EQ(region.depth_mm, face.depth_mm);
  }
  double area = 0;
  for (const PlanFace& face : blunted.plan.faces) area += face.area_mm2;
  EXPECT_NEAR(area, options.sheet.width_mm * options.sheet.height_mm, 1e-6);
}

// A round of tips where some tips leave their faces, or the faces given them, more places narrower
// than W than before is tried again without those: on the 48 x 24 sphere at W = 4 mm the first
// round's cuts leave more places than they part, and are all refused (at W = 3 mm, since junctions
// move onto level contours past the pixel edges beside a third face, the whole round is taken).
TEST(DesignTips, ARoundWhoseTipsMakeNarrowPlacesIsTriedAgainWithoutThem) {
  DesignOptions options;
  options.tip_rounds = 0;
  options.slice.min_strip_mm = 4;
  const DesignResult supported =
      design(LoadedMesh{.mesh = test::sphere({0, 0, 0}, 1, 48, 24), .format = "obj"}, options);
  const double W = options.slice.min_strip_mm;
  const auto narrow = [](const PlanAnalysis& a) {
    return std::ranges::count_if(a.problems,
                                 [](const PlanProblem& p) { return p.kind == PlanProblemKind::NarrowStrip; });
  };
  const TipRepairOptions once{
      .min_strip_mm = W, .max_tip_mm = 4.0 / 3.0 * W, .rounds = 1, .retries = 0};  // design()'s reach
  const TipRepair whole = blunt_narrow_tips(supported.plan.lines, once);
  TipRepairOptions again = once;
  again.retries = 1;
  const TipRepair retried = blunt_narrow_tips(supported.plan.lines, again);
  const auto before = narrow(analyze_plan(supported.plan.lines, {.min_strip_mm = W}));
  EXPECT_EQ(whole.rounds, 0);
  EXPECT_EQ(whole.tips, 0);
  EXPECT_EQ(narrow(whole.analysis), before);
  EXPECT_EQ(retried.rounds, 1);
  EXPECT_GT(retried.tips, 0);
  EXPECT_LT(narrow(retried.analysis), before);
  EXPECT_EQ(narrow(retried.analysis), narrow(analyze_plan(retried.lines, {.min_strip_mm = W})));
}

TEST(DesignVerdict, APlanIsValidWhereItStandsAndHasNoPlaceNarrowerThanWUnlessAllowed) {
  DesignResult result;
  result.plan.validity.valid = 3;
  EXPECT_TRUE(design_valid(result));
  PlanProblem narrow;
  narrow.kind = PlanProblemKind::NarrowStrip;
  narrow.value_mm = 0.5;
  result.narrow_strips.push_back(narrow);
  EXPECT_FALSE(design_valid(result));
  result.allow_narrow = true;
  EXPECT_TRUE(design_valid(result));
  result.plan.validity.floating = 1;
  EXPECT_FALSE(design_valid(result));
  result.plan.validity.floating = 0;
  result.plan.loose_card_pieces = 1;
  EXPECT_FALSE(design_valid(result)) << "a loose piece of card: the plan does not stand";
  result.plan.loose_card_pieces = 0;
  result.plan.validity.dangling = 1;
  EXPECT_FALSE(design_valid(result));
  result.allow_dangling = true;
  EXPECT_TRUE(design_valid(result));
}

}  // namespace
}  // namespace origamic
