// SPDX-License-Identifier: GPL-3.0-or-later
#include "level_contours.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "bands.hpp"
#include "chain_points.hpp"

namespace origamic {
namespace {

// Where between two pixel centres, with depths a and b, the depth crosses `level` (strictly between
// them): rounded to 1/1024 from the lower depth's side, so that the mirror image (the centres
// swapped) gets 1 - t exactly, and kept off the centres as the picture's breaks are.
float crossing(double a, double b, double level) {
  const double from_lower = a < b ? (level - a) / (b - a) : (level - b) / (a - b);
  const double k = std::clamp(std::round(from_lower * 1024), 1.0, 1023.0);
  return static_cast<float>((a < b ? k : 1024 - k) / 1024);
}

// The depths either side of the boundary between two slices: the highest on the nearer slice's
// side, the lowest on the farther's.
struct Sides {
  double near_highest = -std::numeric_limits<double>::infinity();
  double far_lowest = std::numeric_limits<double>::infinity();
};

// Each pixel's slice: its face where that is a face of the model's picture (no support, no hole),
// -1 elsewhere.
Grid<std::int32_t> slice_map(const RasterMaps& maps, const Grid<std::int32_t>& face,
                             const std::vector<RasterFace>& faces) {
  Grid<std::int32_t> slice(face.cols, face.rows, -1);
  for_bands(face.rows, [&](int, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r)
      for (int c = 0; c < face.cols; ++c) {
        const std::int32_t f = face(c, r);
        if (f <= kFloorFace || maps.kind(c, r) != HitKind::Model) continue;
        const RasterFace& plane = faces[static_cast<std::size_t>(f)];
        if (!plane.support && !plane.hole) slice(c, r) = f;
      }
  });
  return slice;
}

// Along one column of pixel edges (edge k between the pixels of row k, for k in [0, n): `seen(k)`,
// the picture's break there, NaN where the rays saw none; `at(k)`, the fraction drawn there;
// `boundary(k)`, whether two faces meet across it and no third lies beside them), the edges of a
// boundary with neither a break nor a level that run on from a straight model edge take its
// fraction: a run of kMinBreakRun or more edges of the boundary that the picture breaks across at
// one fraction, next to them (on both sides, at the same one: two edges meeting there leave it to
// the junction). A box's top folding back to the back plane passes over the back plane's pixels,
// where the rays see no edge: its sides ran on the lattice there, a pixel's fraction beside the
// box's, and its fold onto the back plane ended on the lattice, a jog in the cut and a sliver beside
// it (the demo house: 13 places narrower than W -> 11; the 37 models at W = 3 mm: 4,393 -> 4,390,
// measured before junction_moves.cpp took fold ends along, which left 4,391).
// Along the rows the same made notches at slices' ends and was left out (the half cylinder 14 -> 23
// places), as was filling beside a third face.
template <typename Seen, typename At, typename Boundary>
void extend_straight_breaks(int n, Seen seen, At at, Boundary boundary) {
  // The run the chains are drawn on the model's edge for: a shorter one is no edge a chain would
  // follow. Its own measure hardly moves (runs of 4 / 8 / 16: 4,392 / 4,391 / 4,390 places over the
  // 37 models at W = 3 mm, the demo house 8 each); it is kept one with the chains' for that reason.
  constexpr int kStraightRun = static_cast<int>(chains::kMinBreakRun);
  const auto straight = [&](int from, int step) -> std::optional<float> {  // a run from `from` on, away
    const float t = seen(from);
    if (std::isnan(t)) return std::nullopt;
    int count = 0;
    for (int k = from; k >= 0 && k < n && boundary(k) && seen(k) == t; k += step) ++count;
    return count >= kStraightRun ? std::optional<float>(t) : std::nullopt;
  };
  for (int k = 0; k < n;) {
    if (!boundary(k) || !std::isnan(at(k))) {
      ++k;
      continue;
    }
    int end = k;  // the gap [k, end)
    while (end < n && boundary(end) && std::isnan(at(end))) ++end;
    const std::optional<float> before = k > 0 && boundary(k - 1) ? straight(k - 1, -1) : std::nullopt;
    const std::optional<float> after = end < n && boundary(end) ? straight(end, 1) : std::nullopt;
    const std::optional<float> t = before && after ? (*before == *after ? before : std::nullopt)
                                   : before        ? before
                                                   : after;
    for (int m = k; t && m < end; ++m) at(m) = *t;
    k = end;
  }
}

}  // namespace

BreaksAndLevels breaks_and_levels(const RasterMaps& maps, const Grid<std::int32_t>& face,
                                  const std::vector<RasterFace>& faces) {
  BreaksAndLevels out{maps.break_right, maps.break_below};
  if (out.right.size() == 0) return out;  // maps made by hand: no picture to follow
  const Grid<std::int32_t> slice = slice_map(maps, face, faces);
  // Whether the pixels beside the pair (c, r), (c2, r2), across the edge between them, are of its two
  // faces: near a junction the contour stays on the lattice, where the other lines end (drawn off it,
  // res_armadillo's contour leaving a fold's end crossed into the face beyond).
  const auto only_these_beside = [&](int c, int r, int c2, int r2, std::int32_t a, std::int32_t b) {
    const int dc = r2 - r, dr = c2 - c;  // across the pair
    for (const int side : {-1, 1})
      for (const auto& [pc, pr] : {std::pair{c + side * dc, r + side * dr}, std::pair{c2 + side * dc, r2 + side * dr}})
        if (face.contains(pc, pr) && face(pc, pr) != a && face(pc, pr) != b) return false;
    return true;
  };
  // Each pair of neighbouring pixels of two slices in one orientation that no break parts, its first
  // pixel in rows [row_begin, row_end).
  const auto for_each_pair = [&](int row_begin, int row_end, auto visit) {
    for (int r = row_begin; r < row_end; ++r)
      for (int c = 0; c < face.cols; ++c) {
        const std::int32_t a = slice(c, r);
        if (a < 0) continue;
        for (const auto& [c2, r2, grid] : {std::tuple{c + 1, r, &out.right}, std::tuple{c, r + 1, &out.below}}) {
          if (!face.contains(c2, r2) || !std::isnan((*grid)(c, r))) continue;
          const std::int32_t b = slice(c2, r2);
          if (b < 0 || b == a || !only_these_beside(c, r, c2, r2, a, b)) continue;
          const RasterFace &fa = faces[static_cast<std::size_t>(a)], &fb = faces[static_cast<std::size_t>(b)];
          if (fa.orientation != fb.orientation || fa.depth_mm == fb.depth_mm) continue;
          const Grid<double>& depth = fa.orientation == Orientation::V ? maps.d_mm : maps.h_mm;
          visit(a, b, fa.depth_mm < fb.depth_mm, depth(c, r), depth(c2, r2), (*grid)(c, r));
        }
      }
  };
  // The level the slicing cut two slices at lies between their depths on either side of their
  // boundary; where those overlap (slices of two segments), the boundary is no level contour. Bands
  // of rows gather their own extremes, taken together after (the same in any order); each pixel pair
  // then writes its own crossing.
  using Pair = std::pair<std::int32_t, std::int32_t>;
  std::array<std::map<Pair, Sides>, kBands> band_sides;
  for_bands(face.rows, [&](int band, int row_begin, int row_end) {
    std::map<Pair, Sides>& sides = band_sides[static_cast<std::size_t>(band)];
    for_each_pair(row_begin, row_end, [&](std::int32_t a, std::int32_t b, bool a_nearer, double da, double db, float&) {
      Sides& s = sides[a_nearer ? Pair{a, b} : Pair{b, a}];
      s.near_highest = std::max(s.near_highest, a_nearer ? da : db);
      s.far_lowest = std::min(s.far_lowest, a_nearer ? db : da);
    });
  });
  std::map<Pair, Sides> sides;
  for (const std::map<Pair, Sides>& band : band_sides)
    for (const auto& [pair, side] : band) {
      Sides& s = sides[pair];
      s.near_highest = std::max(s.near_highest, side.near_highest);
      s.far_lowest = std::min(s.far_lowest, side.far_lowest);
    }
  for_bands(face.rows, [&](int, int row_begin, int row_end) {
    for_each_pair(row_begin, row_end, [&](std::int32_t a, std::int32_t b, bool a_nearer, double da, double db, float& t) {
      const Sides& s = sides.at(a_nearer ? Pair{a, b} : Pair{b, a});
      if (s.near_highest < s.far_lowest) t = crossing(da, db, (s.near_highest + s.far_lowest) / 2);
    });
  });
  // Columns in parallel: each reads the picture's breaks and writes its own edges.
  tbb::parallel_for(0, face.cols - 1, [&](int c) {
    extend_straight_breaks(
        face.rows, [&](int r) { return maps.break_right(c, r); }, [&](int r) -> float& { return out.right(c, r); },
        [&](int r) {
          const std::int32_t a = face(c, r), b = face(c + 1, r);
          return a != b && only_these_beside(c, r, c + 1, r, a, b);
        });
  });
  return out;
}

}  // namespace origamic
