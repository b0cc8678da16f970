// SPDX-License-Identifier: GPL-3.0-or-later
#include "chain_points.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "chain_legs.hpp"

namespace origamic::chains {
namespace {

// A chain's first edges on the picture's break are a straight leg if they lie within this of one
// line (refined points on a straight model edge scatter about 1e-4 mm: float rays, 1/1024 pixel).
constexpr double kLegStraightness_mm = 0.01;
// A fold's end moves along its line to the model's edge by at most this: a 30-degree edge meets
// the line up to 1.5 pixels from where the traced run reached it.
constexpr double kFoldEndMove_px = 2.0;

// The midpoint of the pixel edge from corner a to corner b, on the picture's break across it if
// there is one.
ChainPoint edge_point(LatticePoint a, LatticePoint b, const LatticeScale& lattice, const PictureBreaks& breaks) {
  ChainPoint point{{(a.u + b.u) / 2, (a.v + b.v) / 2}};
  if (breaks.right.size() == 0) return point;
  const int u = point.lattice.u, v = point.lattice.v;
  float t = std::numeric_limits<float>::quiet_NaN();
  if (a.v == b.v) {  // between pixel rows v/2 - 1 (above) and v/2, at column (u - 1)/2
    const int col = (u - 1) / 2, above = v / 2 - 1;
    if (breaks.below.contains(col, above)) t = breaks.below(col, above);
    if (!std::isnan(t)) point = {point.lattice, true, lattice.X(u), lattice.Y(v - 1) - t * lattice.px_mm};
  } else {  // between pixel columns u/2 - 1 and u/2, at row (v - 1)/2
    const int left = u / 2 - 1, row = (v - 1) / 2;
    if (breaks.right.contains(left, row)) t = breaks.right(left, row);
    if (!std::isnan(t)) point = {point.lattice, true, lattice.X(u - 1) + t * lattice.px_mm, lattice.Y(v)};
  }
  return point;
}

}  // namespace

// The chain's leg at its front (or back): its first edges along one lattice line, or else their
// points on the picture's break, if they lie on one line (a model edge).
std::optional<Leg> leg_of(const Chain& chain, bool front, const LatticeScale& lattice, const PictureBreaks& breaks,
                          std::size_t lattice_edges) {
  constexpr std::size_t kEdges = 3;  // 0.75 mm at 4 px/mm: a curve of radius 70 mm bends 0.001 mm in it
  const std::size_t n = chain.corners.size();
  const auto corner = [&](std::size_t k) { return chain.corners[front ? k : n - 1 - k]; };
  const std::size_t edges = std::min(kEdges, n - 1);
  if (edges < 2) return std::nullopt;
  std::vector<ChainPoint> from_end;  // the chain's edges' points from this end, each found once
  const auto edge = [&](std::size_t k) {
    for (std::size_t m = from_end.size(); m <= k; ++m)
      from_end.push_back(edge_point(corner(m), corner(m + 1), lattice, breaks));
    return from_end[k];
  };
  std::vector<ChainPoint> points;
  for (std::size_t k = 0; k < edges; ++k) points.push_back(edge(k));
  const LatticePoint j = corner(0);
  const bool along_u = std::ranges::all_of(points, [&](const ChainPoint& p) { return p.lattice.v == j.v; });
  const bool along_v = std::ranges::all_of(points, [&](const ChainPoint& p) { return p.lattice.u == j.u; });
  // Breaks on the lattice line itself (a slice ending on a crease of the model) leave it that line.
  const auto off_line = [&](const ChainPoint& p) {
    return p.on_break && std::abs(along_u ? p.Y - lattice.Y(j.v) : p.X - lattice.X(j.u)) > kLegStraightness_mm;
  };
  if ((along_u || along_v) && std::ranges::none_of(points, off_line))
    return Leg{lattice.X(j.u), lattice.Y(j.v), along_u ? 1.0 : 0.0, along_u ? 0.0 : 1.0, false, j};
  std::size_t skip = 0;
  while (skip < lattice_edges && skip < points.size() && !points[skip].on_break) ++skip;
  // On the model's edge only as simplified draws it: a run of kMinBreakRun edges from the end.
  if (n - 1 < skip + kMinBreakRun) return std::nullopt;
  for (std::size_t k = skip; k < skip + kMinBreakRun; ++k)
    if (!edge(k).on_break) return std::nullopt;
  if (skip > 0) {
    points.clear();
    for (std::size_t k = skip; k < skip + kEdges; ++k) points.push_back(edge(k));
  }
  const ChainPoint &a = points.front(), &b = points.back();
  const double length = std::hypot(b.X - a.X, b.Y - a.Y);
  if (!(length > 0)) return std::nullopt;
  const Leg leg{a.X, a.Y, (b.X - a.X) / length, (b.Y - a.Y) / length, true, j};
  for (const ChainPoint& p : points)
    if (std::abs((p.X - leg.X) * leg.dy - (p.Y - leg.Y) * leg.dx) > kLegStraightness_mm) return std::nullopt;
  return leg;
}

bool same(LatticePoint a, LatticePoint b) { return a.u == b.u && a.v == b.v; }

bool is_loop(const Chain& chain) { return same(chain.corners.front(), chain.corners.back()); }

namespace {

// Where a run of points on the model's edge meets a straight run along one lattice line (a support's
// side leaving a roof's edge), the corner between them moves onto the edge: the two lines' meeting
// point, on the lattice line exactly, if it is within a pixel of the corner; it is inserted, fixed,
// and the edge's points beyond it go.
void insert_corners(const LatticeScale& lattice, std::vector<ChainPoint>& points, std::vector<bool>& fixed) {
  // The corner two consecutive pixel edges share, from their midpoints (a corner's coordinates are
  // even, a midpoint's odd across its edge).
  const auto shared_corner = [](LatticePoint m1, LatticePoint m2) {
    const auto pick = [](int a, int b) { return a % 2 == 0 ? a : b % 2 == 0 ? b : (a + b) / 2; };
    return LatticePoint{pick(m1.u, m2.u), pick(m1.v, m2.v)};
  };
  constexpr std::size_t kRun = 3;  // points on each side that must make the two straight lines
  for (std::size_t k = kRun; k + kRun < points.size(); ++k) {
    // points[k] and points[k + 1], where both are edges' midpoints, are either side of a corner.
    for (const bool edge_first : {true, false}) {
      const std::size_t first_break = edge_first ? k + 1 - kRun : k + 1,
                        first_lattice = edge_first ? k + 1 : k + 1 - kRun;
      const auto all = [&](std::size_t from, bool on_break) {
        for (std::size_t m = from; m < from + kRun; ++m)
          if (points[m].on_break != on_break || fixed[m]) return false;
        return true;
      };
      if (!all(first_break, true) || !all(first_lattice, false)) continue;
      // The lattice run: its edges on one lattice line through the corner.
      const LatticePoint corner = shared_corner(points[k].lattice, points[k + 1].lattice);
      bool along_u = true, along_v = true;
      for (std::size_t m = first_lattice; m < first_lattice + kRun; ++m)
        along_u = along_u && points[m].lattice.v == corner.v, along_v = along_v && points[m].lattice.u == corner.u;
      if (along_u == along_v) continue;
      const ChainPoint &a = points[first_break], &b = points[first_break + kRun - 1];
      const double length = std::hypot(b.X - a.X, b.Y - a.Y);
      if (!(length > 0)) continue;
      const double dx = (b.X - a.X) / length, dy = (b.Y - a.Y) / length;
      bool straight = true;
      for (std::size_t m = first_break; m < first_break + kRun; ++m)
        straight = straight && std::abs((points[m].X - a.X) * dy - (points[m].Y - a.Y) * dx) <= kLegStraightness_mm;
      const double across = along_u ? dy : dx;  // the sine between the edge and the lattice line
      if (!straight || !(std::abs(across) > kLegMinSine)) continue;
      ChainPoint meet{corner, true};
      if (along_u) {
        meet.Y = lattice.Y(corner.v), meet.X = a.X + (meet.Y - a.Y) / dy * dx, meet.on_lattice_v = corner.v;
      } else {
        meet.X = lattice.X(corner.u), meet.Y = a.Y + (meet.X - a.X) / dx * dy, meet.on_lattice_u = corner.u;
      }
      // Where the edge meets the lattice line at a shallow angle, the pixels leave the corner up to
      // a pixel over the sine away along it (a 30-degree roof edge: 1.5 pixels).
      const double reach_px = std::min(kJunctionMove_px / std::abs(across), 2.0);
      if (!(std::hypot(meet.X - lattice.X(corner.u), meet.Y - lattice.Y(corner.v)) <= reach_px * lattice.px_mm))
        continue;
      // The edge's points past the meeting point (seen from the edge's run) go.
      const std::size_t inward = edge_first ? first_break : first_break + kRun - 1;
      const auto ahead = [&](const ChainPoint& p) {
        return (p.X - meet.X) * (points[inward].X - meet.X) + (p.Y - meet.Y) * (points[inward].Y - meet.Y) > 0;
      };
      if (edge_first) {
        std::size_t keep_to = k + 1;  // points[first_break .. k] are the edge's; drop those not ahead
        while (keep_to > first_break && !ahead(points[keep_to - 1])) --keep_to;
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(keep_to),
                     points.begin() + static_cast<std::ptrdiff_t>(k + 1));
        fixed.erase(fixed.begin() + static_cast<std::ptrdiff_t>(keep_to),
                    fixed.begin() + static_cast<std::ptrdiff_t>(k + 1));
        points.insert(points.begin() + static_cast<std::ptrdiff_t>(keep_to), meet);
        fixed.insert(fixed.begin() + static_cast<std::ptrdiff_t>(keep_to), true);
        k = keep_to;
      } else {
        std::size_t drop_to = k + 1;  // points[k + 1 ..] are the edge's; drop those not ahead
        while (drop_to < first_break + kRun && !ahead(points[drop_to])) ++drop_to;
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(k + 1),
                     points.begin() + static_cast<std::ptrdiff_t>(drop_to));
        fixed.erase(fixed.begin() + static_cast<std::ptrdiff_t>(k + 1),
                    fixed.begin() + static_cast<std::ptrdiff_t>(drop_to));
        points.insert(points.begin() + static_cast<std::ptrdiff_t>(k + 1), meet);
        fixed.insert(fixed.begin() + static_cast<std::ptrdiff_t>(k + 1), true);
        k = k + 1;
      }
      break;
    }
  }
}

// A chain's points being simplified: where each is drawn, and which must stay.
struct Candidates {
  std::vector<ChainPoint> points;
  std::vector<std::array<double, 2>> at;
  std::vector<bool> fixed;

  void erase(std::size_t k) {
    points.erase(points.begin() + static_cast<std::ptrdiff_t>(k));
    at.erase(at.begin() + static_cast<std::ptrdiff_t>(k));
    fixed.erase(fixed.begin() + static_cast<std::ptrdiff_t>(k));
  }
  double tolerance(std::size_t k, double lattice_mm, double break_mm) const {
    return points[k].on_break ? break_mm : lattice_mm;
  }
  // The distance of point k from the line through points a and b.
  double off_line(std::size_t k, std::size_t a, std::size_t b) const {
    const double ax = at[a][0], ay = at[a][1], dx = at[b][0] - ax, dy = at[b][1] - ay, length = std::hypot(dx, dy);
    const double px = at[k][0] - ax, py = at[k][1] - ay;
    return length > 0 ? std::abs(dx * py - dy * px) / length : std::hypot(px, py);
  }
};

// Where a chain turns between two straight runs of two pixel edges or more off the picture's
// breaks, it has a corner, not a staircase's step (a digital straight line runs single edges one
// way): the corner is a point to draw through, where the edges' midpoints either side would cut it
// by half a pixel (arch_fzk_haus: a wall W wide drawn 2.875 mm wide at its foot). `points` are the
// chain's ends and its edges' midpoints.
std::vector<ChainPoint> with_lattice_corners(const Chain& chain, std::vector<ChainPoint> points) {
  const std::vector<LatticePoint>& corners = chain.corners;
  const std::size_t edges = corners.size() - 1;
  const auto direction = [&](std::size_t e) {
    return std::pair{corners[e + 1].u - corners[e].u, corners[e + 1].v - corners[e].v};
  };
  const auto on_lattice = [&](std::size_t e) { return !points[e + 1].on_break; };  // edge e's midpoint
  // Corner k lies between edges k - 1 and k.
  const auto turns_between_runs = [&](std::size_t k) {
    return k >= 2 && k + 2 <= edges && direction(k - 1) != direction(k) && direction(k - 2) == direction(k - 1) &&
           direction(k) == direction(k + 1) && std::ranges::all_of(std::array{k - 2, k - 1, k, k + 1}, on_lattice);
  };
  std::vector<ChainPoint> out;
  out.reserve(points.size());
  out.push_back(points[0]);
  for (std::size_t k = 1; k < corners.size(); ++k) {
    out.push_back(points[k]);
    if (turns_between_runs(k)) out.push_back({corners[k]});
  }
  out.push_back(points.back());
  return out;
}

// The chain's ends and its edges' midpoints, on the picture's breaks along runs of kMinBreakRun
// edges or more: shorter runs are a slice's end touching a crease here and there, and stay on the
// lattice, as their neighbours do, rather than notch the boundary by half a pixel. With them, its
// corners between straight lattice runs.
std::vector<ChainPoint> edge_points(const Chain& chain, const LatticeScale& lattice, const PictureBreaks& breaks) {
  std::vector<ChainPoint> points = {{chain.corners.front()}};
  for (std::size_t i = 1; i < chain.corners.size(); ++i)
    points.push_back(edge_point(chain.corners[i - 1], chain.corners[i], lattice, breaks));
  points.push_back({chain.corners.back()});
  for (std::size_t k = 0; k < points.size();) {
    std::size_t end = k;
    while (end < points.size() && points[end].on_break) ++end;
    if (end - k < kMinBreakRun)
      for (std::size_t m = k; m < end; ++m) points[m].on_break = false;
    k = end + 1;
  }
  return with_lattice_corners(chain, std::move(points));
}

// Ends whose junctions moved are drawn there, and the points near such an end that lie beyond it
// (its last pixel edge ran past where the model's edge meets the other line) go.
void move_ends(const MovedEnds& moved_ends, Candidates& c) {
  if (moved_ends[0]) c.at.front() = *moved_ends[0];
  if (moved_ends[1]) c.at.back() = *moved_ends[1];
  const std::size_t n = c.points.size(), reach = std::min<std::size_t>(6, n - 1);
  std::vector<bool> beyond(n, false);
  for (const bool front : {true, false}) {
    if (!moved_ends[front ? 0 : 1]) continue;
    const auto index = [&](std::size_t k) { return front ? k : n - 1 - k; };
    const std::array<double, 2> end = c.at[index(0)], inward = c.at[index(reach)];
    for (std::size_t k = 1; k < reach; ++k) {
      const std::array<double, 2> p = c.at[index(k)];
      beyond[index(k)] = (p[0] - end[0]) * (inward[0] - end[0]) + (p[1] - end[1]) * (inward[1] - end[1]) <= 0;
    }
  }
  for (std::size_t k = n; k-- > 0;)
    if (beyond[k] && !c.fixed[k]) c.erase(k);
}

// Douglas-Peucker between the fixed points: the indices kept.
std::vector<std::size_t> douglas_peucker(const Candidates& c, double lattice_mm, double break_mm) {
  std::vector<bool> keep = c.fixed;
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  for (std::size_t k = 0, previous = 0; k < c.points.size(); ++k)
    if (k > 0 && c.fixed[k]) stack.emplace_back(std::exchange(previous, k), k);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j <= i + 1) continue;
    // The point farthest off as a share of its tolerance; of points as far off (a straight run
    // parallel to the chord), the one nearest the middle, so a chain walked the other way (the
    // model mirrored) keeps the same points.
    double worst = 1;
    std::size_t worst_k = i;
    const auto off_middle = [&](std::size_t k) { return k + k > i + j ? k + k - i - j : i + j - k - k; };
    for (std::size_t k = i + 1; k < j; ++k) {
      const double share = c.off_line(k, i, j) / c.tolerance(k, lattice_mm, break_mm);
      const bool as_far = std::abs(share - worst) <= 1e-9 && worst_k != i;
      if ((share > worst && !as_far) || (as_far && off_middle(k) < off_middle(worst_k)))
        worst = std::max(worst, share), worst_k = k;
    }
    if (worst_k != i) {
      keep[worst_k] = true;
      stack.emplace_back(i, worst_k);
      stack.emplace_back(worst_k, j);
    }
  }
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < keep.size(); ++k)
    if (keep[k]) kept.push_back(k);
  // A kept point whose neighbours' segment passes every point between them within its tolerance
  // goes (the middle of a straight run, kept for a chord the run was parallel to).
  const auto spans = [&](std::size_t a, std::size_t b) {
    for (std::size_t k = a + 1; k < b; ++k)
      if (c.off_line(k, a, b) > c.tolerance(k, lattice_mm, break_mm)) return false;
    return true;
  };
  for (std::size_t m = 1; m + 1 < kept.size();)
    if (!c.fixed[kept[m]] && spans(kept[m - 1], kept[m + 1]))
      kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(m));
    else
      ++m;
  return kept;
}

// The kept points, and the farthest the segments between them pass from the points on breaks.
DrawnChain drawing(const Candidates& c, const std::vector<std::size_t>& kept) {
  DrawnChain drawn;
  for (std::size_t m = 0; m < kept.size(); ++m) {
    drawn.points.push_back(c.points[kept[m]]);
    if (m == 0) continue;
    const std::array<double, 2> a = c.at[kept[m - 1]], b = c.at[kept[m]];
    const double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    for (std::size_t k = kept[m - 1] + 1; k < kept[m]; ++k) {
      if (!c.points[k].on_break) continue;
      const double px = c.at[k][0] - a[0], py = c.at[k][1] - a[1];
      const double t = l2 > 0 ? std::clamp((px * dx + py * dy) / l2, 0.0, 1.0) : 0.0;
      drawn.off_edge_mm = std::max(drawn.off_edge_mm, std::hypot(t * dx - px, t * dy - py));
    }
  }
  return drawn;
}

}  // namespace

std::optional<double> leg_meets_line(const Chain& chain, bool front, double Y, const LatticeScale& lattice,
                                     const PictureBreaks& breaks) {
  if (breaks.right.size() == 0) return std::nullopt;
  const std::optional<Leg> leg = leg_of(chain, front, lattice, breaks);
  if (!leg || !leg->on_break || !(std::abs(leg->dy) > kLegMinSine)) return std::nullopt;
  const double X = leg->X + (Y - leg->Y) / leg->dy * leg->dx;
  const LatticePoint end = front ? chain.corners.front() : chain.corners.back();
  if (!(std::hypot(X - lattice.X(end.u), Y - lattice.Y(end.v)) <= kFoldEndMove_px * lattice.px_mm)) return std::nullopt;
  return X;
}

DrawnChain simplified(const Chain& chain, const LatticeScale& lattice, const PictureBreaks& breaks,
                      DrawTolerance tolerance, const MovedEnds& moved_ends) {
  if (tolerance.lattice_mm <= 0) {
    // On the pixel contour, each straight run one segment: its turning corners and its ends.
    const std::vector<LatticePoint>& corners = chain.corners;
    DrawnChain contour;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      if (k > 0 && k + 1 < corners.size()) {
        const LatticePoint &a = corners[k - 1], &b = corners[k], &c = corners[k + 1];
        if ((b.u - a.u) * (c.v - b.v) == (b.v - a.v) * (c.u - b.u)) continue;
      }
      contour.points.push_back({corners[k]});
    }
    return contour;
  }
  Candidates c{edge_points(chain, lattice, breaks), {}, {}};
  c.fixed.assign(c.points.size(), false);
  c.fixed.front() = c.fixed.back() = true;
  insert_corners(lattice, c.points, c.fixed);
  // A loop has no junction to hold its first corner: drawn there, a contour on the picture's break
  // went out to the lattice corner and back, a spike a fraction of a pixel long (seedlike/sphere:
  // one on each ring). It starts and ends on its first edge's point instead.
  if (is_loop(chain) && !moved_ends[0] && !moved_ends[1] && c.points.size() > 3 && c.points[1].on_break &&
      c.points[c.points.size() - 2].on_break && !c.fixed[1]) {
    c.points.erase(c.points.begin());
    c.fixed.erase(c.fixed.begin());
    c.points.back() = c.points.front();
    c.fixed.front() = c.fixed.back() = true;
  }
  for (const ChainPoint& p : c.points)
    c.at.push_back(p.on_break ? std::array{p.X, p.Y} : std::array{lattice.X(p.lattice.u), lattice.Y(p.lattice.v)});
  move_ends(moved_ends, c);
  return drawing(c, douglas_peucker(c, tolerance.lattice_mm, tolerance.break_mm));
}

}  // namespace origamic::chains
