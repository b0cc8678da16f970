// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/fold_style.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "origamic/error.hpp"

namespace origamic {
namespace {

struct Span {
  double from, to;  // X along a horizontal fold
};

// The pieces of drawn lines along a horizontal fold, as X spans in order; each must be horizontal.
std::vector<Span> spans_of(const std::vector<DrawnLine>& lines) {
  std::vector<Span> spans;
  for (const DrawnLine& line : lines)
    for (const std::vector<PlanPoint>& piece : dash_pieces(line)) {
      for (const PlanPoint& p : piece) EXPECT_EQ(p.Y, 0.0);
      spans.push_back({piece.front().X, piece.back().X});
    }
  return spans;
}

// Distance from the plan point (x, 0) to the segment a-b.
double distance_to(double x, PlanPoint a, PlanPoint b) {
  const double dx = b.X - a.X, dy = b.Y - a.Y;
  const double t = std::clamp(((x - a.X) * dx + (0 - a.Y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(a.X + t * dx - x, a.Y + t * dy);
}

TEST(FoldStyle, ScoreIsTheFoldItself) {
  const PlanPolyline fold{LineKind::Mountain, {{3, 0}, {40, 0}, {70, 0}}};
  const std::vector<DrawnLine> lines = draw_fold(fold, {}, FoldStyleOptions{});
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].layer, Layer::Mountain);
  EXPECT_TRUE(lines[0].dash_mm.empty());
  ASSERT_EQ(lines[0].points.size(), 3u);
  EXPECT_EQ(lines[0].points[1].X, 40.0);
}

TEST(FoldStyle, PerforationsKeepTheInsetFromCutsAtTheEndsAndAcrossTheMiddle) {
  // A 100 mm valley fold; cuts meet it at both ends and a slanted cut touches it at X = 50.
  const PlanPolyline fold{LineKind::Valley, {{0, 0}, {30, 0}, {100, 0}}};
  const std::vector<PlanPolyline> cuts = {{LineKind::Cut, {{0, -10}, {0, 10}}},
                                          {LineKind::Cut, {{100, 0}, {100, 10}}},
                                          {LineKind::Cut, {{50, 0}, {60, 20}}}};
  FoldStyleOptions options;
  options.style = FoldStyle::Perforated;
  const std::vector<DrawnLine> lines = draw_fold(fold, cuts, options);
  for (const DrawnLine& line : lines) EXPECT_EQ(line.layer, Layer::PerfValley);
  const std::vector<Span> spans = spans_of(lines);
  ASSERT_FALSE(spans.empty());
  // The slanted cut blocks X within 0.5 of (50, 0) on the left and, on the right, where the
  // perpendicular distance (X - 50) sin(angle) is below 0.5, sin(angle) = 20 / sqrt(500).
  const double right_of_slant = 50 + 0.5 * std::sqrt(500.0) / 20;
  EXPECT_NEAR(spans.front().from, 0.5, 1e-12);
  EXPECT_NEAR(spans.back().to, 99.5, 1e-12);
  int left = 0, right = 0;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    const Span& s = spans[i];
    EXPECT_NEAR(s.to - s.from, 1.0, 1e-12) << "every cut is exactly CUT long";
    if (i > 0) {
      EXPECT_GE(s.from - spans[i - 1].to, 1.0 - 1e-12) << "no gap below GAP";
    }
    for (const PlanPolyline& cut : cuts)
      for (const double x : {s.from, (s.from + s.to) / 2, s.to})
        EXPECT_GE(distance_to(x, cut.points[0], cut.points[1]), 0.5 - 1e-12) << "X " << x;
    (s.to <= 50 ? left : right) += 1;
  }
  // The runs [0.5, 49.5] and [right_of_slant, 99.5] each start and end with a cut; the header's count.
  EXPECT_NEAR(spans[static_cast<std::size_t>(left) - 1].to, 49.5, 1e-12);
  EXPECT_NEAR(spans[static_cast<std::size_t>(left)].from, right_of_slant, 1e-12);
  EXPECT_EQ(left, static_cast<int>(std::floor((49.0 + 1) / 2)));
  EXPECT_EQ(right, static_cast<int>(std::floor((99.5 - right_of_slant + 1) / 2)));
}

TEST(FoldStyle, PerforationOfARunShorterThanACutIsTheWholeRun) {
  const PlanPolyline fold{LineKind::Mountain, {{10, 0}, {11.5, 0}}};
  const std::vector<PlanPolyline> cuts = {{LineKind::Cut, {{10, 0}, {10, 5}}},
                                          {LineKind::Cut, {{11.5, 0}, {11.5, -5}}}};
  FoldStyleOptions options;
  options.style = FoldStyle::Perforated;
  options.perf_cut_mm = 2;
  const std::vector<Span> spans = spans_of(draw_fold(fold, cuts, options));
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_NEAR(spans[0].from, 10.5, 1e-12);
  EXPECT_NEAR(spans[0].to, 11.0, 1e-12);
}

// A fold shorter than its two insets (0.5 mm between two cuts, as the capitol has) keeps its middle
// third: with no perforation at all it vanished, and validate read its two faces as one.
TEST(FoldStyle, AFoldShorterThanTwoInsetsKeepsItsMiddleThird) {
  const PlanPolyline fold{LineKind::Valley, {{100.25, 0}, {100.75, 0}}};
  const std::vector<PlanPolyline> cuts = {{LineKind::Cut, {{100.25, 0}, {100.25, 5}}},
                                          {LineKind::Cut, {{100.75, 0}, {100.75, -5}}}};
  FoldStyleOptions options;
  options.style = FoldStyle::Perforated;
  const std::vector<Span> spans = spans_of(draw_fold(fold, cuts, options));
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_NEAR(spans[0].from, 100.25 + 0.5 / 3, 1e-12);
  EXPECT_NEAR(spans[0].to, 100.25 + 1.0 / 3, 1e-12);
}

// A fold from X = 10 to 16 that a cut meets from above at X = 13 and runs along 0.05 mm above from
// there to its end: a reader parts the fold at X = 13, so its right stretch, blocked whole, keeps
// its middle third, and the left its perforation in the middle of its run.
TEST(FoldStyle, AStretchOfAFoldBlockedWholeBetweenTwoOfItsPointsKeepsItsMiddleThird) {
  const PlanPolyline fold{LineKind::Valley, {{10, 0}, {13, 0}, {16, 0}}};
  const std::vector<PlanPolyline> cuts = {{LineKind::Cut, {{10, -5}, {10, 0}}},
                                          {LineKind::Cut, {{13, 0}, {13, 0.05}, {16, 0.05}, {16, 5}}},
                                          {LineKind::Cut, {{16, 0}, {16, -5}}}};
  FoldStyleOptions options;
  options.style = FoldStyle::Perforated;
  const std::vector<Span> spans = spans_of(draw_fold(fold, cuts, options));
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_NEAR(spans[0].from, 11, 1e-12);  // the run 10.5 to 12.5, its 1 mm cut in the middle
  EXPECT_NEAR(spans[0].to, 12, 1e-12);
  EXPECT_NEAR(spans[1].from, 14, 1e-12);
  EXPECT_NEAR(spans[1].to, 15, 1e-12);

  // With the cut 0.05 mm above the whole fold, both stretches are blocked whole: each keeps its own
  // middle third, and none spans the point at X = 13.
  const std::vector<PlanPolyline> above = {{LineKind::Cut, {{10, 5}, {10, 0.05}, {16, 0.05}, {16, 5}}},
                                           {LineKind::Cut, {{13, 0}, {13, 0.05}}}};
  const std::vector<Span> both = spans_of(draw_fold(fold, above, options));
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NEAR(both[0].from, 11, 1e-12);
  EXPECT_NEAR(both[0].to, 12, 1e-12);
  EXPECT_NEAR(both[1].from, 14, 1e-12);
  EXPECT_NEAR(both[1].to, 15, 1e-12);
}

TEST(FoldStyle, DashedFoldsStartAndEndWithAWholeDashAndShowTheirKind) {
  FoldStyleOptions options;
  options.style = FoldStyle::Dashed;
  for (const LineKind kind : {LineKind::Mountain, LineKind::Valley}) {
    SCOPED_TRACE(kind == LineKind::Mountain ? "mountain" : "valley");
    const std::vector<DrawnLine> lines = draw_fold({kind, {{20, 0}, {120, 0}}}, {}, options);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].layer, kind == LineKind::Mountain ? Layer::Mountain : Layer::Valley);
    const std::vector<Span> spans = spans_of(lines);
    ASSERT_GE(spans.size(), 3u);
    EXPECT_DOUBLE_EQ(spans.front().from, 20.0);
    EXPECT_NEAR(spans.back().to, 120.0, 1e-9);
    // Mountain: dash 2, dot 0.5, dash 2, ...; valley: dash 2 throughout. Gaps all equal, >= nominal.
    const double first_gap = spans[1].from - spans[0].to;
    EXPECT_GE(first_gap, (kind == LineKind::Mountain ? 0.75 : 1.0) - 1e-12);
    for (std::size_t i = 0; i < spans.size(); ++i) {
      const double expected = kind == LineKind::Mountain && i % 2 == 1 ? 0.5 : 2.0;
      EXPECT_NEAR(spans[i].to - spans[i].from, expected, 1e-9) << "piece " << i;
      if (i > 0) {
        EXPECT_NEAR(spans[i].from - spans[i - 1].to, first_gap, 1e-9) << "gap before piece " << i;
      }
    }
    if (kind == LineKind::Mountain) {
      EXPECT_EQ(spans.size() % 2, 1u) << "ends on a dash, not a dot";
    }
  }
}

TEST(FoldStyle, ADashedFoldShorterThanAPeriodAndADashGetsThePatternScaledDown) {
  FoldStyleOptions options;
  options.style = FoldStyle::Dashed;
  // A valley period (dash 2, gap 1) and a dash need 5 mm; 4 mm get them scaled by 4/5.
  const std::vector<Span> spans = spans_of(draw_fold({LineKind::Valley, {{0, 0}, {4, 0}}}, {}, options));
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_NEAR(spans[0].to - spans[0].from, 1.6, 1e-12);
  EXPECT_NEAR(spans[1].from - spans[0].to, 0.8, 1e-12);
  EXPECT_NEAR(spans[1].to, 4.0, 1e-12);
}

TEST(FoldStyle, AbsurdPerforationsAndInsetsAreRejectedNamingTheOption) {
  auto message = [](FoldStyleOptions options) -> std::string {
    try {
      check_fold_style(options);
    } catch (const InputError& e) {
      return e.field;
    }
    return "";
  };
  const std::string perf = "FoldStyleOptions::perf_cut_mm/FoldStyleOptions::perf_gap_mm";
  EXPECT_EQ(message(FoldStyleOptions{}), "");
  EXPECT_EQ(message({.perf_cut_mm = 0}), perf);
  EXPECT_EQ(message({.perf_gap_mm = -1}), perf);
  EXPECT_EQ(message({.perf_cut_mm = NAN}), perf);
  EXPECT_EQ(message({.perf_gap_mm = 1000}), perf);
  EXPECT_EQ(message({.inset_mm = -0.1}), "FoldStyleOptions::inset_mm");
  EXPECT_EQ(message({.inset_mm = INFINITY}), "FoldStyleOptions::inset_mm");
  EXPECT_EQ(message({.inset_mm = 0}), "");
}

}  // namespace
}  // namespace origamic
