// SPDX-License-Identifier: GPL-3.0-or-later
// Cuts on the model's edges (issue 23): models made in code, standing clear of the back plane at a
// known place, whose edges' plan positions are known in closed form. Where the plan draws such an
// edge, it draws it within 0.05 mm, and a straight edge with no vertex between its junctions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "helpers.hpp"
#include "origamic/design.hpp"

namespace origamic {
namespace {

// OA points (x, h, d) as model points (x, y, z) read with up y, at scale 1 and offset 0.
using Floor = test::Floor;

Plan design_in_place(const TriangleMesh& mesh) {
  DesignOptions options;
  options.placement.scale = 1;
  options.placement.offset_mm = glm::dvec3(0.0);
  const DesignResult result = design(LoadedMesh{.mesh = mesh, .format = "obj"}, options);
  EXPECT_TRUE(result.plan.validity.ok());
  return result.plan;
}

struct Segment {
  PlanPoint a, b;
};

std::vector<Segment> drawn_segments(const Plan& plan) {
  std::vector<Segment> segments;
  for (const PlanPolyline& line : plan.lines)
    if (line.kind != LineKind::Outline)
      for (std::size_t i = 1; i < line.points.size(); ++i) segments.push_back({line.points[i - 1], line.points[i]});
  return segments;
}

// How the plan draws a model edge from a to b, sampled every 0.1 mm: a sample is drawn where the
// nearest line of the plan runs along the edge there (within 10 degrees, within 0.15 mm, the
// sample's foot inside it; elsewhere a support or a fold stands in for the edge).
struct EdgeDrawing {
  int samples = 0, drawn = 0;
  double worst_mm = 0;  // the farthest drawn sample from its line
};

EdgeDrawing drawing_of(const std::vector<Segment>& segments, PlanPoint a, PlanPoint b) {
  EdgeDrawing result;
  const double ex = b.X - a.X, ey = b.Y - a.Y, length = std::hypot(ex, ey);
  const int steps = std::max(1, static_cast<int>(length / 0.1));
  for (int i = 0; i <= steps; ++i) {
    const double px = a.X + ex * i / steps, py = a.Y + ey * i / steps;
    double nearest = 1e300;
    const Segment* by = nullptr;
    double foot = 0;
    for (const Segment& s : segments) {
      const double dx = s.b.X - s.a.X, dy = s.b.Y - s.a.Y, l2 = dx * dx + dy * dy;
      if (l2 == 0) continue;
      const double t = ((px - s.a.X) * dx + (py - s.a.Y) * dy) / l2, c = std::clamp(t, 0.0, 1.0);
      const double distance = std::hypot(s.a.X + c * dx - px, s.a.Y + c * dy - py);
      if (distance < nearest) nearest = distance, by = &s, foot = t;
    }
    ++result.samples;
    if (!by || nearest > 0.15 || foot <= 0 || foot >= 1) continue;
    const double dx = by->b.X - by->a.X, dy = by->b.Y - by->a.Y;
    const double sine = std::abs(dx * ey - dy * ex) / (std::hypot(dx, dy) * length);
    if (sine > std::sin(10 * std::numbers::pi / 180)) continue;
    ++result.drawn;
    result.worst_mm = std::max(result.worst_mm, nearest);
  }
  return result;
}

// The plan's vertices along a straight edge's interior (within 0.05 mm of it, 0.5 mm clear of its
// ends) where the drawing runs on along the edge and meets nothing: exactly two segments end there,
// both lying along the edge.
int vertices_between_junctions(const std::vector<Segment>& segments, PlanPoint a, PlanPoint b) {
  const double ex = b.X - a.X, ey = b.Y - a.Y, length = std::hypot(ex, ey);
  const auto off = [&](PlanPoint p) { return std::abs((p.X - a.X) * ey - (p.Y - a.Y) * ex) / length; };
  const auto along = [&](PlanPoint p) { return ((p.X - a.X) * ex + (p.Y - a.Y) * ey) / length; };
  const auto same = [](PlanPoint p, PlanPoint q) { return std::abs(q.X - p.X) <= 1e-9 && std::abs(q.Y - p.Y) <= 1e-9; };
  int count = 0;
  for (const Segment& s : segments)
    for (const PlanPoint& p : {s.a, s.b}) {
      if (off(p) > 0.05 || along(p) < 0.5 || along(p) > length - 0.5) continue;
      std::vector<PlanPoint> others;  // the far ends of the segments ending at p
      for (const Segment& t : segments) {
        if (same(t.a, p)) others.push_back(t.b);
        if (same(t.b, p)) others.push_back(t.a);
      }
      if (others.size() == 2 && off(others[0]) <= 0.05 && off(others[1]) <= 0.05) ++count;
    }
  return count / 2;  // each such vertex is met from both of its segments
}

PlanPoint top_point(const std::array<double, 2>& corner, double height) {
  return {corner[0], height - corner[1]};  // H(h): Y = h - d
}

// A box turned 30 degrees about the up axis, 60 x 40 x 50 mm, 50 mm in front of the back plane at
// its nearest: its top's two back edges are silhouettes against the back plane.
TEST(ModelEdges, TheBackEdgesOfABoxTurned30DegreesAreDrawnOnTheirLines) {
  const double turn = 30 * std::numbers::pi / 180, c = std::cos(turn), s = std::sin(turn), height = 50;
  Floor floor;
  for (const auto& [u, v] : {std::array{-30.0, -20.0}, {30.0, -20.0}, {30.0, 20.0}, {-30.0, 20.0}})
    floor.push_back({105 + c * u - s * v, 70 + s * u + c * v});
  const Plan plan = design_in_place(test::prism(floor, 0, height));
  const std::vector<Segment> segments = drawn_segments(plan);
  EXPECT_LE(plan.off_model_edges_mm, 0.02);
  // The back corner (smallest d) and the edges leaving it.
  const std::size_t back = static_cast<std::size_t>(
      std::ranges::min_element(floor, {}, [](const std::array<double, 2>& p) { return p[1]; }) - floor.begin());
  for (const std::size_t other : {(back + 1) % 4, (back + 3) % 4}) {
    const PlanPoint a = top_point(floor[back], height), b = top_point(floor[other], height);
    SCOPED_TRACE("edge to corner " + std::to_string(other));
    const EdgeDrawing drawing = drawing_of(segments, a, b);
    EXPECT_GE(drawing.drawn, 0.9 * drawing.samples) << "the edge is drawn almost all along";
    EXPECT_LE(drawing.worst_mm, 0.05);
    EXPECT_EQ(vertices_between_junctions(segments, a, b), 0);
  }
}

// A 96-sided drum 35 mm in radius, 40 high, its axis 70 mm in front of the back plane: the back
// half of its top's rim is a silhouette against the back plane.
TEST(ModelEdges, TheBackRimOfA96SidedDrumIsDrawnOnItsPolygon) {
  constexpr int sides = 96;
  const double radius = 35, height = 40;
  Floor floor;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    floor.push_back({105 + radius * std::cos(a), 70 + radius * std::sin(a)});
  }
  const Plan plan = design_in_place(test::prism(floor, 0, height));
  const std::vector<Segment> segments = drawn_segments(plan);
  EdgeDrawing rim;
  for (int k = 0; k < sides; ++k) {
    const auto& p = floor[static_cast<std::size_t>(k)];
    const auto& q = floor[static_cast<std::size_t>((k + 1) % sides)];
    if (p[1] > 70 || q[1] > 70) continue;  // the back half: d below the axis
    const EdgeDrawing side = drawing_of(segments, top_point(p, height), top_point(q, height));
    rim.samples += side.samples, rim.drawn += side.drawn, rim.worst_mm = std::max(rim.worst_mm, side.worst_mm);
  }
  EXPECT_GE(rim.drawn, 0.85 * rim.samples);
  EXPECT_LE(rim.worst_mm, 0.05);
}

// A gable-fronted house 60 wide and 40 deep, walls 40 and ridge 60 high, its back wall 40 mm in
// front of the back plane: the back gable's two roof edges are silhouettes against the back plane.
TEST(ModelEdges, TheRoofEdgesOfAGableHouseAreDrawnOnTheirLines) {
  const double x0 = 75, x1 = 135, xm = 105, d0 = 40, d1 = 80, wall = 40, ridge = 60;
  TriangleMesh house;
  const auto vertex = [&](double x, double h, double d) {
    house.positions.emplace_back(x, h, d);
    return static_cast<std::uint32_t>(house.positions.size() - 1);
  };
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    house.triangles.push_back({a, b, c});
    house.triangles.push_back({a, c, d});
  };
  for (const double d : {d1, d0}) {  // the gable walls, the front facing +d and the back -d
    const std::uint32_t a = vertex(x0, 0, d), b = vertex(x1, 0, d), c = vertex(x1, wall, d), r = vertex(xm, ridge, d),
                        e = vertex(x0, wall, d);
    const std::array<std::uint32_t, 5> ring = d == d1 ? std::array{a, b, c, r, e} : std::array{a, e, r, c, b};
    for (std::size_t i = 1; i < 4; ++i) house.triangles.push_back({ring[0], ring[i], ring[i + 1]});
  }
  quad(vertex(x1, 0, d1), vertex(x1, 0, d0), vertex(x1, wall, d0), vertex(x1, wall, d1));
  quad(vertex(x0, 0, d0), vertex(x0, 0, d1), vertex(x0, wall, d1), vertex(x0, wall, d0));
  quad(vertex(x1, wall, d1), vertex(x1, wall, d0), vertex(xm, ridge, d0), vertex(xm, ridge, d1));
  quad(vertex(x0, wall, d0), vertex(x0, wall, d1), vertex(xm, ridge, d1), vertex(xm, ridge, d0));
  quad(vertex(x0, 0, d0), vertex(x1, 0, d0), vertex(x1, 0, d1), vertex(x0, 0, d1));
  const Plan plan = design_in_place(house);
  const std::vector<Segment> segments = drawn_segments(plan);
  // On the back gable V(d0): Y = h - d0.
  for (const auto& [a, b] : {std::pair{PlanPoint{x0, wall - d0}, PlanPoint{xm, ridge - d0}},
                             std::pair{PlanPoint{xm, ridge - d0}, PlanPoint{x1, wall - d0}}}) {
    SCOPED_TRACE("edge from X " + std::to_string(a.X));
    const EdgeDrawing drawing = drawing_of(segments, a, b);
    // Supports rise from the roof to the back plane across a third of the edge.
    EXPECT_GE(drawing.drawn, 0.6 * drawing.samples);
    EXPECT_LE(drawing.worst_mm, 0.05);
    EXPECT_EQ(vertices_between_junctions(segments, a, b), 0);
  }
}

// A box 60 x 30 x 50 mm, square to the card, 30 mm in front of the back plane, its sides at X =
// 40.1 and 100.1 (between pixel edges): its top folds back to the back plane over pixels of the
// back plane, where the rays see no edge. The top's sides run on straight along the box's sides,
// which the rays do see, to the valley fold on the back plane, and that fold ends on them: every
// plan vertex within a pixel of a side lies on it, to a micrometre.
TEST(ModelEdges, TheSidesOfABoxsTopRunStraightOnToTheBackPlane) {
  const double x0 = 40.1, x1 = 100.1, d0 = 30, d1 = 60, height = 50;
  const Plan plan = design_in_place(test::prism({{x0, d0}, {x1, d0}, {x1, d1}, {x0, d1}}, 0, height));
  int on_sides = 0;
  for (const PlanPolyline& line : plan.lines) {
    if (line.kind == LineKind::Outline) continue;
    for (const PlanPoint& p : line.points)
      for (const double side : {x0, x1}) {
        if (std::abs(p.X - side) > 0.25 || p.Y < height - d1 || p.Y > height) continue;
        SCOPED_TRACE("vertex (" + std::to_string(p.X) + ", " + std::to_string(p.Y) + ")");
        EXPECT_NEAR(p.X, side, 1e-3);
        ++on_sides;
      }
  }
  EXPECT_GE(on_sides, 4) << "each side's cut ends at the top's front fold and at the back plane's fold";
  // The fold of the top onto the back plane, at Y = 50, runs from side to side.
  bool back_fold = false;
  for (const PlanPolyline& line : plan.lines)
    if (line.kind == LineKind::Valley && line.points.front().Y == height && line.points.back().Y == height) {
      const auto [lo, hi] = std::minmax(line.points.front().X, line.points.back().X);
      back_fold = back_fold || (std::abs(lo - x0) <= 1e-3 && std::abs(hi - x1) <= 1e-3);
    }
  EXPECT_TRUE(back_fold);
}

// A slice ends where the model's depth crosses its level (seed §4.3): on a leaning, turned wall,
// d = 50 + 0.2 (x - 60) - 0.15 h, those contours are straight lines slanting across the plan. Each
// cut inside the wall is drawn on one of them, not on the pixels' staircase along it: the wall's
// depth at the two ends of every cut segment there is the same to 0.01 mm (a pixel's step of the
// staircase changes it by 0.03-0.04 mm), and the segment runs from one of the wall's edges to another.
TEST(ModelEdges, SlicesOfALeaningWallEndOnItsLevelContours) {
  const auto front = [](double x, double h) { return 50 + 0.2 * (x - 60) - 0.15 * h; };
  TriangleMesh wall;
  for (const bool at_front : {false, true})
    for (const auto& [x, h] : {std::pair{60.0, 0.0}, {150.0, 0.0}, {150.0, 100.0}, {60.0, 100.0}})
      wall.positions.emplace_back(x, h, at_front ? front(x, h) : 20.0);
  wall.triangles = {{4, 5, 6}, {4, 6, 7}, {0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4},
                    {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  const Plan plan = design_in_place(wall);
  // The wall's depth under a plan point of its front: h - d = Y with d = front(X, h).
  const auto depth_at = [&](PlanPoint p) {
    const double h = (p.Y + 50 - 0.2 * 60 + 0.2 * p.X) / 1.15;
    return h - p.Y;
  };
  const auto inside = [&](PlanPoint p) {
    const double h = p.Y + depth_at(p);
    return p.X > 70 && p.X < 140 && h > 10 && h < 90;  // clear of the supports at the wall's edges
  };
  int contours = 0;
  for (const PlanPolyline& line : plan.lines) {
    if (line.kind != LineKind::Cut) continue;
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      const PlanPoint a = line.points[i - 1], b = line.points[i];
      if (!inside({(a.X + b.X) / 2, (a.Y + b.Y) / 2})) continue;
      ++contours;
      SCOPED_TRACE("cut from (" + std::to_string(a.X) + ", " + std::to_string(a.Y) + ") to (" + std::to_string(b.X) +
                   ", " + std::to_string(b.Y) + ")");
      EXPECT_LE(std::abs(depth_at(a) - depth_at(b)), 0.01);
      EXPECT_GE(std::hypot(b.X - a.X, b.Y - a.Y), 20) << "a contour is one segment from edge to edge";
    }
  }
  EXPECT_GE(contours, 5) << "the wall's 33 mm of depth is sliced into levels 3 mm apart";
}

}  // namespace
}  // namespace origamic
