// SPDX-License-Identifier: GPL-3.0-or-later
// A traced chain drawn on the model's edge (chain_points.hpp): its points moved onto the picture's
// breaks, its junctions to where the model's edge meets the line beside it.
#include "chain_points.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "chain_legs.hpp"

namespace origamic {
namespace {

using chains::Chain;
using chains::LatticePoint;

// A staircase of 12 steps right and down on a lattice of 1 mm pixels whose pixel edges the picture
// breaks across a quarter pixel off them, all on one straight model edge X + Y = c; and, from its
// last corner, a straight run of 7 pixel edges along its lattice row.
struct StaircaseOnAnEdge {
  static constexpr int steps = 12;
  chains::LatticeScale lattice{20, 1.0};
  Grid<float> right{40, 40, std::numeric_limits<float>::quiet_NaN()}, below = right;
  Chain stairs{2, 3, {}}, row{2, 4, {}};
  double c = 0;

  StaircaseOnAnEdge() {
    for (int k = 1; k <= steps; ++k) {
      stairs.corners.push_back({2 * k, 2 * k});
      stairs.corners.push_back({2 * k + 2, 2 * k});
      below(k, k - 1) = 0.25f;  // the edge at v = 2k: a quarter down from row k - 1's centre
      right(k, k) = 0.75f;      // the edge at u = 2k + 2: three quarters right from column k's centre
    }
    const LatticePoint last{2 * steps + 2, 2 * steps + 2};
    stairs.corners.push_back(last);
    for (int k = 0; k <= 7; ++k) row.corners.push_back({last.u + 2 * k, last.v});
    c = lattice.X(3) + lattice.Y(2) + lattice.px_mm / 4;  // through u = 2k + 1.5 at v = 2k
  }
  chains::PictureBreaks breaks() const { return {right, below}; }
  double off_edge(double X, double Y) const { return std::abs(X + Y - c) / std::sqrt(2.0); }
  // The junction where the row leaves the staircase moved, alone, along the row onto the edge.
  void expect_row_start_moved_onto_edge(const chains::JunctionMoves& moves) const {
    ASSERT_EQ(moves.moved.size(), 1u);
    const chains::MovedJunction& m = moves.moved[0];
    EXPECT_EQ(m.corner.u, row.corners.front().u);
    EXPECT_EQ(m.corner.v, row.corners.front().v);
    EXPECT_EQ(m.v_on_lattice, m.corner.v);
    EXPECT_NEAR(m.X, c - lattice.Y(m.corner.v), 1e-9);
  }
  // The junction at corner j moved alone onto the edge, square to it: along its normal (1, 1) by
  // 0.75 / sqrt 2 = 0.53 mm, on no lattice line.
  void expect_moved_square_onto_edge(const chains::JunctionMoves& moves, LatticePoint j) const {
    ASSERT_EQ(moves.moved.size(), 1u);
    const chains::MovedJunction& m = moves.moved[0];
    EXPECT_EQ(m.corner.u, j.u);
    EXPECT_EQ(m.corner.v, j.v);
    EXPECT_EQ(m.u_on_lattice, -1);
    EXPECT_EQ(m.v_on_lattice, -1);
    EXPECT_EQ(m.on_fold_of, -1);
    EXPECT_LE(off_edge(m.X, m.Y), 1e-9);
    const double X = lattice.X(j.u), Y = lattice.Y(j.v);
    EXPECT_NEAR(m.X - X, m.Y - Y, 1e-9);
    EXPECT_NEAR(std::hypot(m.X - X, m.Y - Y), 0.75 / std::sqrt(2.0), 1e-9);
  }
  // A corner moved across to the edge, along X.
  std::array<double, 2> on_edge(LatticePoint corner) const {
    const double Y = lattice.Y(corner.v);
    return {c - Y, Y};
  }
};

// The staircase as two chains meeting at its corner j = (12, 12): up to j, and on from j.
struct StaircaseSplitAtJ : StaircaseOnAnEdge {
  const LatticePoint j{12, 12};
  Chain before{2, 3, {}}, after{4, 3, {}};

  StaircaseSplitAtJ() {
    const auto at_j = std::ranges::find_if(stairs.corners, [&](LatticePoint p) { return p.u == j.u && p.v == j.v; });
    if (at_j == stairs.corners.end()) {
      ADD_FAILURE() << "j is no corner of the staircase";
      return;
    }
    before.corners.assign(stairs.corners.begin(), at_j + 1);
    after.corners.assign(at_j, stairs.corners.end());
  }
};

// Its points move onto the edge, and with its ends moved onto it too the chain is that one segment,
// drawn exactly.
TEST(ChainPoints, AStaircaseOnTheModelsEdgeIsItsStraightEdge) {
  const StaircaseOnAnEdge s;
  const chains::DrawnChain drawn = chains::simplified(s.stairs, s.lattice, s.breaks(), {0.1, 0.02});
  ASSERT_GE(drawn.points.size(), 3u);
  EXPECT_LE(drawn.off_edge_mm, 0.02);
  for (std::size_t k = 1; k + 1 < drawn.points.size(); ++k) {
    ASSERT_TRUE(drawn.points[k].on_break) << k;
    EXPECT_LE(s.off_edge(drawn.points[k].X, drawn.points[k].Y), 1e-9) << k;
  }
  const chains::DrawnChain straight =
      chains::simplified(s.stairs, s.lattice, s.breaks(), {0.1, 0.02},
                         {s.on_edge(s.stairs.corners.front()), s.on_edge(s.stairs.corners.back())});
  EXPECT_EQ(straight.points.size(), 2u);
  EXPECT_LE(straight.off_edge_mm, 1e-9);
}

// A run of breaks shorter than 8 pixel edges (a slice's end touching a crease) stays on the lattice.
TEST(ChainPoints, AShortRunOfBreaksStaysOnTheLattice) {
  StaircaseOnAnEdge s;
  s.stairs.corners.resize(7);  // 6 pixel edges, all across breaks
  for (const chains::ChainPoint& p : chains::simplified(s.stairs, s.lattice, s.breaks(), {0.1, 0.02}).points)
    EXPECT_FALSE(p.on_break);
  s = StaircaseOnAnEdge{};
  s.stairs.corners.resize(10);  // 9 pixel edges: a run long enough is drawn on the edge
  const std::vector<chains::ChainPoint> points =
      chains::simplified(s.stairs, s.lattice, s.breaks(), {0.1, 0.02}).points;
  EXPECT_TRUE(std::ranges::any_of(points, &chains::ChainPoint::on_break));
}

// An L of two straight lattice runs: down 5 pixel edges from corner (10, 10), then right 4.
Chain ell_of_two_runs() {
  Chain ell{2, 3, {}};
  for (int k = 0; k <= 5; ++k) ell.corners.push_back({10, 10 + 2 * k});
  for (int k = 1; k <= 4; ++k) ell.corners.push_back({10 + 2 * k, 20});
  return ell;
}

// On its pixel contour (no simplifying), a chain is its turning corners: an L of two straight runs
// is three points, the corner kept; a staircase keeps every step.
TEST(ChainPoints, OnItsPixelContourAChainIsItsTurningCorners) {
  const StaircaseOnAnEdge s;
  const Chain ell = ell_of_two_runs();
  const chains::DrawnChain drawn = chains::simplified(ell, s.lattice, s.breaks(), {0, 0});
  ASSERT_EQ(drawn.points.size(), 3u);
  const std::array<std::array<int, 2>, 3> expected = {{{10, 10}, {10, 20}, {18, 20}}};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_FALSE(drawn.points[k].on_break);
    EXPECT_EQ(drawn.points[k].lattice.u, expected[k][0]) << k;
    EXPECT_EQ(drawn.points[k].lattice.v, expected[k][1]) << k;
  }
  EXPECT_EQ(chains::simplified(s.stairs, s.lattice, s.breaks(), {0, 0}).points.size(), s.stairs.corners.size());
}

// Simplified, an L of two straight lattice runs is drawn on its corner, which the pixel edges'
// midpoints either side would cut off by half a pixel; a jog of one edge between two runs is a
// step, drawn through its midpoints, neither of its corners a point (drawn on them, the farther
// would be kept: 0.5 mm off the chord, where the midpoint beside it is 0.45 mm off).
TEST(ChainPoints, ACornerOfTwoStraightRunsIsDrawnOnIt) {
  const StaircaseOnAnEdge s;
  const Chain ell = ell_of_two_runs();
  const chains::DrawnChain drawn = chains::simplified(ell, s.lattice, s.breaks(), {0.1, 0.02});
  ASSERT_EQ(drawn.points.size(), 3u);
  EXPECT_EQ(drawn.points[1].lattice.u, 10);
  EXPECT_EQ(drawn.points[1].lattice.v, 20);
  Chain jog{2, 3, {}};
  for (int k = 0; k <= 5; ++k) jog.corners.push_back({10, 10 + 2 * k});  // down 5 pixel edges
  for (int k = 0; k <= 5; ++k) jog.corners.push_back({12, 20 + 2 * k});  // right 1, down 5
  const chains::DrawnChain stepped = chains::simplified(jog, s.lattice, s.breaks(), {0.1, 0.02});
  ASSERT_GT(stepped.points.size(), 2u);
  for (std::size_t k = 1; k + 1 < stepped.points.size(); ++k)
    EXPECT_TRUE(stepped.points[k].lattice.u % 2 != 0 || stepped.points[k].lattice.v % 2 != 0) << k;
}

// The staircase's last corner, where the lattice row leaves it, moves along the row to where the
// model's edge crosses it: on the row exactly, at X = c - Y. Pinned, it stays.
TEST(ChainPoints, AJunctionMovesToWhereTheModelsEdgeMeetsTheLineBesideIt) {
  const StaircaseOnAnEdge s;
  const std::vector<Chain> chains = {s.stairs, s.row};
  const chains::JunctionMoves moves = chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}});
  s.expect_row_start_moved_onto_edge(moves);
  EXPECT_EQ(moves.collapsed, (std::vector<bool>{false, false}));
  const chains::JunctionMoves pinned = chains::moved_junctions(chains, s.lattice, s.breaks(), {{.pinned = true}, {}});
  EXPECT_TRUE(pinned.moved.empty());
  // A fold snapping onto Y = 7.1 at the row's end: the junction moves along the fold's line.
  const chains::JunctionMoves on_fold =
      chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {.fold_Y = {7.1, std::nullopt}}});
  ASSERT_EQ(on_fold.moved.size(), 1u);
  EXPECT_EQ(on_fold.moved[0].on_fold_of, 1);
  EXPECT_NEAR(on_fold.moved[0].X, s.c - 7.1, 1e-9);
  EXPECT_DOUBLE_EQ(on_fold.moved[0].Y, 7.1);
}

// Down the staircase's last column from its end, a straight run of 5 pixel edges (a support's side
// below a wall's edge): the junction above it moves across it, along the row, onto the edge. Where
// a fold ends the run below, the run's lower end follows along the fold, as far: the run stays
// straight. Where no fold does, or the run keeps its contour, that end stays.
TEST(ChainPoints, ARunWhoseJunctionMovedAcrossItTakesItsFoldsEndAlong) {
  const StaircaseOnAnEdge s;
  const LatticePoint top = s.row.corners.front();
  Chain column{4, 5, {}};
  for (int k = 0; k <= 5; ++k) column.corners.push_back({top.u, top.v + 2 * k});
  const LatticePoint bottom = column.corners.back();
  const std::vector<Chain> chains = {s.stairs, s.row, column};
  const double fold_Y = s.lattice.Y(bottom.v) - 0.1;
  const chains::JunctionMoves moves =
      chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {.fold_Y = {std::nullopt, fold_Y}}});
  ASSERT_EQ(moves.moved.size(), 2u);
  const auto at = [&](LatticePoint corner) {
    return std::ranges::find_if(
        moves.moved, [&](const chains::MovedJunction& m) { return m.corner.u == corner.u && m.corner.v == corner.v; });
  };
  ASSERT_NE(at(top), moves.moved.end());
  ASSERT_NE(at(bottom), moves.moved.end());
  const double X = s.c - s.lattice.Y(top.v);  // the row meets the edge
  EXPECT_NEAR(at(top)->X, X, 1e-9);
  EXPECT_EQ(at(bottom)->X, at(top)->X);
  EXPECT_EQ(at(bottom)->Y, fold_Y);
  EXPECT_EQ(at(bottom)->on_fold_of, 2);
  EXPECT_EQ(at(bottom)->u_on_lattice, -1);
  for (const std::vector<chains::ChainEnds>& ends :
       {std::vector<chains::ChainEnds>{{}, {}, {}}, {{}, {}, {.pinned = true, .fold_Y = {std::nullopt, fold_Y}}}}) {
    const chains::JunctionMoves kept = chains::moved_junctions(chains, s.lattice, s.breaks(), ends);
    EXPECT_TRUE(std::ranges::none_of(
        kept.moved, [&](const chains::MovedJunction& m) { return m.corner.u == bottom.u && m.corner.v == bottom.v; }));
  }
}

// Where no model edge passes, a junction where a fold snaps onto its line moves square onto that
// line, by at most a pixel: the fold ends where the cuts meet. Not where two folds there snap onto
// two lines, where a chain there keeps its contour, nor where the junction is two corners a pixel
// edge apart. A chain leaving along the lattice row does not hold it; where that chain runs straight
// along the row to another junction, that one moves square onto the fold's line too (the run stays
// straight), unless it lies on another fold's line.
TEST(ChainPoints, AJunctionWhereAFoldSnapsMovesOntoItsLine) {
  const chains::LatticeScale lattice{20, 1.0};
  const Grid<float> none(40, 40, std::numeric_limits<float>::quiet_NaN());
  const chains::PictureBreaks no_breaks{none, none};
  // A chain from `from` through the given corners, one pixel edge (2 lattice steps) at a time.
  const auto path = [](std::int32_t left, std::int32_t right, LatticePoint from, std::vector<LatticePoint> to) {
    Chain chain{left, right, {from}};
    for (const LatticePoint corner : to)
      while (chain.corners.back().u != corner.u || chain.corners.back().v != corner.v) {
        const LatticePoint last = chain.corners.back();
        chain.corners.push_back({last.u + 2 * ((corner.u > last.u) - (corner.u < last.u)),
                                 last.v + 2 * ((corner.v > last.v) - (corner.v < last.v))});
      }
    return chain;
  };
  const LatticePoint junction{10, 10};
  const Chain fold = path(2, 3, junction, {{20, 10}, {20, 14}}), up = path(2, 4, junction, {{10, 2}, {6, 2}}),
              down = path(3, 4, junction, {{10, 18}, {14, 18}});
  const std::vector<Chain> chains = {fold, up, down};
  const double fold_Y = lattice.Y(junction.v) - 0.3;
  const chains::ChainEnds snaps{.fold_Y = {fold_Y, std::nullopt}};
  const chains::JunctionMoves moves = chains::moved_junctions(chains, lattice, no_breaks, {snaps, {}, {}});
  ASSERT_EQ(moves.moved.size(), 1u);
  const chains::MovedJunction& m = moves.moved[0];
  EXPECT_EQ(m.corner.u, junction.u);
  EXPECT_EQ(m.corner.v, junction.v);
  EXPECT_EQ(m.X, lattice.X(junction.u));
  EXPECT_EQ(m.u_on_lattice, junction.u);
  EXPECT_EQ(m.Y, fold_Y);
  EXPECT_EQ(m.on_fold_of, 0);
  EXPECT_EQ(moves.collapsed, (std::vector<bool>{false, false, false}));
  // Two folds onto one line move it; onto two, or a pixel and more away, or a chain pinned, none.
  EXPECT_EQ(chains::moved_junctions(chains, lattice, no_breaks, {snaps, snaps, {}}).moved.size(), 1u);
  const chains::ChainEnds other{.fold_Y = {fold_Y + 0.1, std::nullopt}};
  EXPECT_TRUE(chains::moved_junctions(chains, lattice, no_breaks, {snaps, other, {}}).moved.empty());
  const chains::ChainEnds far{.fold_Y = {lattice.Y(junction.v) - 1.25, std::nullopt}};
  EXPECT_TRUE(chains::moved_junctions(chains, lattice, no_breaks, {far, {}, {}}).moved.empty());
  EXPECT_TRUE(chains::moved_junctions(chains, lattice, no_breaks, {snaps, {}, {.pinned = true}}).moved.empty());
  EXPECT_TRUE(chains::moved_junctions(chains, lattice, no_breaks, {{}, {}, {}}).moved.empty());
  const chains::ChainEnds on_its_row{.fold_Y = {lattice.Y(junction.v), std::nullopt}};
  EXPECT_TRUE(chains::moved_junctions(chains, lattice, no_breaks, {on_its_row, {}, {}}).moved.empty());
  const Chain along_row = path(3, 5, junction, {{2, 10}, {2, 16}});
  const chains::JunctionMoves turning =
      chains::moved_junctions({fold, up, along_row}, lattice, no_breaks, {snaps, {}, {}});
  ASSERT_EQ(turning.moved.size(), 1u);
  EXPECT_EQ(turning.moved[0].Y, fold_Y);
  // Straight along the row to a junction {2, 10} where a chain leaves down: both move onto the line.
  const LatticePoint row_end{2, 10};
  const Chain row_run = path(3, 5, junction, {row_end}), down_from_other = path(5, 6, row_end, {{2, 16}});
  const chains::JunctionMoves both =
      chains::moved_junctions({fold, up, row_run, down_from_other}, lattice, no_breaks, {snaps, {}, {}, {}});
  ASSERT_EQ(both.moved.size(), 2u);
  for (const chains::MovedJunction& each : both.moved) {
    EXPECT_EQ(each.Y, fold_Y);
    EXPECT_EQ(each.on_fold_of, 0);
    EXPECT_EQ(each.u_on_lattice, each.corner.u);
    EXPECT_EQ(each.X, lattice.X(each.corner.u));
  }
  // Not where another run leaves that junction along the row, nor where a fold snapping there lies
  // on another line, more than a pixel off (within a pixel, that junction goes onto its own line).
  const LatticePoint middle{6, 10};
  const Chain to_middle = path(3, 5, junction, {middle}), on_along_row = path(3, 6, middle, {{2, 10}}),
              down_from_middle = path(5, 6, middle, {{6, 16}});
  EXPECT_EQ(chains::moved_junctions({fold, up, to_middle, on_along_row, down_from_middle}, lattice, no_breaks,
                                    {snaps, {}, {}, {}, {}})
                .moved.size(),
            1u);
  const chains::ChainEnds far_line{.fold_Y = {lattice.Y(row_end.v) - 1.25, std::nullopt}};
  EXPECT_EQ(
      chains::moved_junctions({fold, up, row_run, down_from_other}, lattice, no_breaks, {snaps, {}, {}, far_line})
          .moved.size(),
      1u);
  const chains::ChainEnds other_line{.fold_Y = {fold_Y + 0.1, std::nullopt}};
  const chains::JunctionMoves own =
      chains::moved_junctions({fold, up, row_run, down_from_other}, lattice, no_breaks, {snaps, {}, {}, other_line});
  ASSERT_EQ(own.moved.size(), 2u);
  for (const chains::MovedJunction& each : own.moved)
    EXPECT_EQ(each.Y, each.corner.u == row_end.u ? fold_Y + 0.1 : fold_Y);
  const Chain edge{2, 4, {junction, {10, 8}}}, up_beyond = path(2, 4, {10, 8}, {{10, 2}, {6, 2}});
  const chains::ChainEnds between{.fold_Y = {lattice.Y(junction.v) + 0.3, std::nullopt}};  // within a pixel of both
  EXPECT_TRUE(
      chains::moved_junctions({fold, edge, up_beyond, down}, lattice, no_breaks, {between, {}, {}, {}}).moved.empty());
}

// Beside a third face a level contour keeps to the pixel edges for a pixel: here the staircase's last
// two pixel edges are off the picture's break. Its leg reaches past them to the model's edge, and the
// junction moves onto it as where the break runs to the end; not where a support's side ends there
// (W wide on the lattice, it would tilt and be narrower than W).
TEST(ChainPoints, AJunctionsLegReachesPastTheContoursLastPixelEdgesUnlessBesideASupport) {
  StaircaseOnAnEdge s;
  s.right(s.steps, s.steps) = s.below(s.steps, s.steps - 1) = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Chain> chains = {s.stairs, s.row};
  s.expect_row_start_moved_onto_edge(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}}));
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {.beside_support = true}}).moved.empty());
  // Three edges off the break are more than a contour keeps beside a third face: no leg, no move.
  s.right(s.steps - 1, s.steps - 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}}).moved.empty());
}

// The staircase split at its corner (12, 12) into two chains on the model's edge, and a third
// leaving that corner down-left in single steps, on no break and no lattice line (a level
// contour): the edge runs through the junction and no leg crosses it, so the junction moves to the
// foot of the perpendicular from the corner onto the edge, 0.75 / sqrt 2 = 0.53 mm across, on no
// lattice line. Not where a chain holds it; not where the chain after it runs on a parallel edge
// 0.14 mm off; not where it has no leg on the edge. Where the third chain is a straight run on its
// lattice column, that leg crosses the edge and the junction moves along it (meeting_point).
TEST(ChainPoints, AJunctionTheModelsEdgeRunsThroughMovesSquareOntoIt) {
  StaircaseSplitAtJ s;
  const LatticePoint j = s.j;
  const Chain &before = s.before, &after = s.after;
  Chain contour{2, 4, {j}}, column{2, 4, {j}};
  for (int k = 1; k <= 4; ++k) {
    contour.corners.push_back({j.u - 2 * k, j.v + 2 * (k - 1)});
    contour.corners.push_back({j.u - 2 * k, j.v + 2 * k});
    column.corners.push_back({j.u, j.v + 2 * k});
  }
  const std::vector<Chain> chains = {before, after, contour};
  s.expect_moved_square_onto_edge(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {}}), j);
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {.pinned = true}}).moved.empty());
  // A straight run down the corner's lattice column crosses the edge: the junction moves along it.
  const chains::JunctionMoves along =
      chains::moved_junctions({before, after, column}, s.lattice, s.breaks(), {{}, {}, {}});
  ASSERT_EQ(along.moved.size(), 1u);
  EXPECT_EQ(along.moved[0].u_on_lattice, j.u);
  EXPECT_LE(s.off_edge(along.moved[0].X, along.moved[0].Y), 1e-9);
  // The chain after the junction on a parallel edge, 0.2 mm lower and 0.2 mm left at its crossings.
  StaircaseOnAnEdge shifted;
  for (int k = 6; k <= shifted.steps; ++k) shifted.below(k, k - 1) = 0.45f, shifted.right(k, k) = 0.55f;
  EXPECT_TRUE(chains::moved_junctions(chains, shifted.lattice, shifted.breaks(), {{}, {}, {}}).moved.empty());
  // Its first four pixel edges off the break, more than a level contour keeps beside a third face:
  // no leg on the edge after the junction.
  for (int k = 6; k <= 7; ++k) s.right(k, k) = s.below(k, k - 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {}}).moved.empty());
}

// The staircase's edge runs through its corner j = (12, 12); a third chain leaves j left and up,
// its pixel edges' points on the picture's break along a line through (6, 13.6) rising 1 in 2 to
// the left (slope -1/2, Y up). That leg crosses the edge at a sine of 1 / sqrt 10, 2.77 mm off, more
// than a pixel: the junction moves to the foot of the perpendicular from j onto the edge, 0.75 /
// sqrt 2 = 0.53 mm across, not to the crossing, and it had stayed on its corner. Where a fold snaps
// at j, or a support's side ends there, it stays.
TEST(ChainPoints, AJunctionTheModelsEdgeRunsThroughMovesOntoItWhereAThirdLegCrossesItFarOff) {
  StaircaseSplitAtJ s;
  const LatticePoint j = s.j;
  const Chain &before = s.before, &after = s.after;
  Chain third{2, 4, {j}};
  // Left, left, up, three times over, less the last up: 8 pixel edges, each point on the line.
  const double X0 = 6, Y0 = 13.6, slope = -0.5;  // Y - Y0 = slope (X - X0)
  for (int k = 0; k < 8; ++k) {
    const LatticePoint from = third.corners.back();
    const bool up = k % 3 == 2;
    const LatticePoint to = up ? LatticePoint{from.u, from.v - 2} : LatticePoint{from.u - 2, from.v};
    third.corners.push_back(to);
    const int u = (from.u + to.u) / 2, v = (from.v + to.v) / 2;
    float t = 0;
    if (up) {  // a column edge: its point at the line's X on its row's Y, from the left column's centre
      t = static_cast<float>((X0 + (s.lattice.Y(v) - Y0) / slope - s.lattice.X(u - 1)) / s.lattice.px_mm);
      s.right((u / 2) - 1, (v - 1) / 2) = t;
    } else {  // a row edge: its point at the line's Y on its column's X, down from the row above's centre
      t = static_cast<float>((s.lattice.Y(v - 1) - (Y0 + slope * (s.lattice.X(u) - X0))) / s.lattice.px_mm);
      s.below((u - 1) / 2, v / 2 - 1) = t;
    }
    ASSERT_GT(t, 0.0f);
    ASSERT_LT(t, 1.0f);
  }
  // Its leg lies on that line: on the break, not on the lattice.
  const std::optional<chains::Leg> leg = chains::leg_of(third, true, s.lattice, s.breaks());
  ASSERT_TRUE(leg);
  EXPECT_TRUE(leg->on_break);
  EXPECT_NEAR(leg->dy / leg->dx, slope, 1e-6);
  const std::vector<Chain> chains = {before, after, third};
  s.expect_moved_square_onto_edge(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {}}), j);
  // A fold snapping at j onto its line half a pixel below meets the edge 1.35 mm off: the junction
  // stays on its corner, not taken off the fold's line onto the edge.
  const chains::ChainEnds fold_below_j{.fold_Y = {s.lattice.Y(j.v) - 0.5, std::nullopt}};
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, fold_below_j}).moved.empty());
  // Where a support's side ends at j, it stays too: the side would tilt.
  EXPECT_TRUE(chains::moved_junctions(chains, s.lattice, s.breaks(), {{}, {}, {.beside_support = true}}).moved.empty());
}

// A loop (a slice's level contour closing round a dome, no junction on it) drawn on the picture's
// breaks all round: it starts and ends on its first edge's point, not on the lattice corner it was
// traced from, which the drawing went out to and back from in a spike.
TEST(ChainPoints, ALoopOnTheBreaksClosesOnTheBreaks) {
  const chains::LatticeScale lattice{20, 1.0};
  Grid<float> right(40, 40, std::numeric_limits<float>::quiet_NaN()), below = right;
  // A rectangle of 6 x 4 pixels, each pixel edge broken a quarter pixel inside it.
  Chain loop{2, 3, {{4, 4}}};
  const auto to = [&](LatticePoint corner) {
    while (loop.corners.back().u != corner.u || loop.corners.back().v != corner.v) {
      const LatticePoint a = loop.corners.back();
      const LatticePoint b{a.u + 2 * ((corner.u > a.u) - (corner.u < a.u)),
                           a.v + 2 * ((corner.v > a.v) - (corner.v < a.v))};
      if (a.v == b.v)  // between pixel rows v / 2 - 1 and v / 2: inside is below the top side
        below((a.u + b.u) / 4, a.v / 2 - 1) = a.v == 4 ? 0.75f : 0.25f;
      else  // between pixel columns u / 2 - 1 and u / 2: inside is right of the left side
        right(a.u / 2 - 1, (a.v + b.v) / 4) = a.u == 4 ? 0.75f : 0.25f;
      loop.corners.push_back(b);
    }
  };
  to({16, 4}), to({16, 12}), to({4, 12}), to({4, 4});
  ASSERT_EQ(loop.corners.size(), 21u);
  const chains::DrawnChain drawn = chains::simplified(loop, lattice, {right, below}, {0.1, 0.02});
  ASSERT_GE(drawn.points.size(), 5u);
  for (const chains::ChainPoint& p : drawn.points) {
    EXPECT_TRUE(p.on_break) << "a point on the lattice at u = " << p.lattice.u << ", v = " << p.lattice.v;
    // A quarter pixel inside the rectangle's sides.
    const bool on_side = std::abs(p.X - 2.25) < 1e-9 || std::abs(p.X - 7.75) < 1e-9 ||
                         std::abs(p.Y - lattice.Y(4) + 0.25) < 1e-9 || std::abs(p.Y - lattice.Y(12) - 0.25) < 1e-9;
    EXPECT_TRUE(on_side) << "X = " << p.X << ", Y = " << p.Y;
  }
  EXPECT_EQ(drawn.points.front().X, drawn.points.back().X);
  EXPECT_EQ(drawn.points.front().Y, drawn.points.back().Y);
}

// A lattice row whose pixel edges the picture breaks across on the row itself (a slice ending on a
// crease of the model) is still that row beside the junction: the staircase's corner moves along
// it as it does beside a row with no breaks.
TEST(ChainPoints, ARowOnACreaseStillTakesTheJunctionAlongIt) {
  StaircaseOnAnEdge s;
  const LatticePoint start = s.row.corners.front();
  for (int k = 0; k < 7; ++k) s.below(start.u / 2 + k, start.v / 2 - 1) = 0.5f;  // Y(v - 1) - 0.5 px: on the row
  const chains::JunctionMoves moves = chains::moved_junctions({s.stairs, s.row}, s.lattice, s.breaks(), {{}, {}});
  ASSERT_EQ(moves.moved.size(), 1u);
  EXPECT_EQ(moves.moved[0].v_on_lattice, start.v);
  EXPECT_NEAR(moves.moved[0].X, s.c - s.lattice.Y(start.v), 1e-9);
}

// Where the staircase's edge meets a fold's line near its end, within two pixels.
TEST(ChainPoints, ALegMeetsAFoldLineOnTheModelsEdge) {
  const StaircaseOnAnEdge s;
  const std::optional<double> X = chains::leg_meets_line(s.stairs, false, 7.1, s.lattice, s.breaks());
  ASSERT_TRUE(X.has_value());
  EXPECT_NEAR(*X, s.c - 7.1, 1e-9);
  EXPECT_FALSE(chains::leg_meets_line(s.stairs, false, 12.0, s.lattice, s.breaks()).has_value()) << "5 mm off";
}

}  // namespace
}  // namespace origamic
