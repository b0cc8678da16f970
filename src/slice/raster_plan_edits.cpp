// SPDX-License-Identifier: GPL-3.0-or-later
// Edits of a raster plan's face map that slicing and the support loop share: coplanar faces merged,
// faces in parts split, V/H boundaries moved onto their fold lines.
#include "raster_plan_edits.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <climits>
#include <cmath>
#include <map>
#include <optional>
#include <ranges>
#include <set>
#include <tuple>
#include <utility>

#include "bands.hpp"
#include "four_neighbours.hpp"
#include "origamic/slice.hpp"
#include "plane_numbers.hpp"
#include "union_find.hpp"

namespace origamic {

RasterPlan merge_coplanar_faces(RasterPlan result) {
  const std::size_t n = result.faces.size();
  UnionFind<std::int32_t> sets(n);
  Grid<std::int32_t>& face = result.face;
  std::vector<std::int64_t> pixels(n, 0);
  bool merged = false;
  // Faces numbered by plane, so that the scan keeps only the meetings of coplanar faces. Holes
  // (all numbered -1) merge with each other whatever plane they came from, and never with paper.
  std::vector<std::int32_t> plane(n);
  {
    PlaneNumbers number;
    for (std::size_t f = 0; f < n; ++f) plane[f] = number(result.faces[f]);
  }
  auto join = [&](std::int32_t f, std::int32_t g) { merged = sets.join(f, g) || merged; };
  // Run by run along the rows, in bands in parallel: a run's pixels are counted at once, and a
  // stretch of one face below it is met once. Joining is the same in any order.
  std::array<std::vector<std::int64_t>, kBands> band_pixels;
  std::array<std::vector<std::pair<std::int32_t, std::int32_t>>, kBands> band_meets;
  for_bands(face.rows, [&](int band, int row_begin, int row_end) {
    std::vector<std::int64_t>& count = band_pixels[static_cast<std::size_t>(band)];
    std::vector<std::pair<std::int32_t, std::int32_t>>& meets = band_meets[static_cast<std::size_t>(band)];
    count.assign(n, 0);
    for (int row = row_begin; row < row_end; ++row) {
      const std::int32_t* here = &face.values[face.index(0, row)];
      const std::int32_t* below = row + 1 < face.rows ? here + face.cols : nullptr;
      for (int col = 0; col < face.cols;) {
        const std::int32_t f = here[col];
        int end = col + 1;
        while (end < face.cols && here[end] == f) ++end;
        if (f >= 0) count[static_cast<std::size_t>(f)] += end - col;
        if (f >= 2) {
          const auto meet = [&](std::int32_t g) {
            if (g >= 2 && g != f && plane[static_cast<std::size_t>(g)] == plane[static_cast<std::size_t>(f)] &&
                (meets.empty() || meets.back() != std::pair{f, g}))
              meets.emplace_back(f, g);
          };
          if (end < face.cols) meet(here[end]);
          if (below)
            for (int c = col; c < end; ++c)
              if (c == col || below[c] != below[c - 1]) meet(below[c]);
        }
        col = end;
      }
    }
  });
  for (std::size_t band = 0; band < kBands; ++band) {
    for (std::size_t f = 0; f < n; ++f) pixels[f] += band_pixels[band][f];
    for (const auto& [f, g] : band_meets[band]) join(f, g);
  }
  const bool emptied =
      std::any_of(pixels.begin() + std::min<std::size_t>(2, n), pixels.end(), [](std::int64_t p) { return p == 0; });
  if (!merged && !emptied) {  // the ids stay as they are: no pass over the pixels to relabel them
    for (std::size_t f = 0; f < n; ++f) result.faces[f].pixels = pixels[f];
    return result;
  }
  for (std::size_t f = 0; f < n; ++f)
    if (const auto r = static_cast<std::size_t>(sets.root(static_cast<std::int32_t>(f))); r != f)
      pixels[r] += std::exchange(pixels[f], 0);
  std::vector<std::int32_t> new_id(n, -1);
  std::vector<RasterFace> faces;
  for (std::size_t f = 0; f < n; ++f)
    if (sets.root(static_cast<std::int32_t>(f)) == static_cast<std::int32_t>(f) && (f < 2 || pixels[f] > 0)) {
      new_id[f] = static_cast<std::int32_t>(faces.size());
      faces.push_back(result.faces[f]);
      faces.back().pixels = pixels[f];
    }
  for (std::size_t f = 0; f < n; ++f)
    new_id[f] = new_id[static_cast<std::size_t>(sets.root(static_cast<std::int32_t>(f)))];
  for_bands(face.rows, [&](int, int row_begin, int row_end) {
    const std::size_t cols = static_cast<std::size_t>(face.cols);
    for (std::size_t i = row_begin * cols; i < row_end * cols; ++i)
      if (std::int32_t& f = face.values[i]; f >= 0) f = new_id[static_cast<std::size_t>(f)];
  });
  result.faces = std::move(faces);
  return result;
}

namespace {

struct Run {
  int row, c0, c1;  // pixels [c0, c1) of the row
  std::int32_t face;
};

// The 4-connected parts of some faces, each as its runs, in the order of their first pixel.
struct FaceParts {
  std::vector<Run> runs;                            // row-major
  std::vector<std::vector<std::uint32_t>> runs_of;  // per part
  std::vector<std::int32_t> face;                   // per part
  std::vector<std::int64_t> size;                   // per part, in pixels
};

FaceParts parts_of(const Grid<std::int32_t>& face, const std::vector<std::uint8_t>& wanted) {
  // The wanted faces as runs of pixels along the rows; runs of one face that overlap in
  // neighbouring rows are 4-connected. Union-find keeps the first run in row-major order as each
  // part's root, so the parts come out in the order of their first pixel.
  FaceParts parts;
  std::vector<Run>& runs = parts.runs;
  UnionFind<std::uint32_t> sets;
  std::size_t previous_row = 0;  // where the runs of the row above begin
  for (int row = 0; row < face.rows; ++row) {
    const std::int32_t* line = &face.values[face.index(0, row)];
    const std::size_t this_row = runs.size();
    for (int c = 0; c < face.cols;) {
      const std::int32_t f = line[c];
      int end = c + 1;
      while (end < face.cols && line[end] == f) ++end;
      if (f >= 0 && wanted[static_cast<std::size_t>(f)]) {
        runs.push_back({row, c, end, f});
        sets.add();
      }
      c = end;
    }
    // Both rows' runs are sorted by column: one merge-like sweep finds the overlapping pairs.
    for (std::size_t a = previous_row, b = this_row; a < this_row && b < runs.size();) {
      if (runs[a].row == row - 1 && runs[a].face == runs[b].face && runs[a].c0 < runs[b].c1 &&
          runs[b].c0 < runs[a].c1)
        sets.join(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
      (runs[a].c1 < runs[b].c1 ? a : b) += 1;
    }
    previous_row = this_row;
  }
  std::vector<std::int32_t> part_of_root(runs.size(), -1);
  for (std::uint32_t i = 0; i < runs.size(); ++i) {
    std::int32_t& part = part_of_root[sets.root(i)];
    if (part < 0) {
      part = static_cast<std::int32_t>(parts.runs_of.size());
      parts.runs_of.emplace_back();
      parts.face.push_back(runs[i].face);
      parts.size.push_back(0);
    }
    parts.runs_of[static_cast<std::size_t>(part)].push_back(i);
    parts.size[static_cast<std::size_t>(part)] += runs[i].c1 - runs[i].c0;
  }
  return parts;
}

// The face a part shares the most pixel sides with, neither its own nor a hole; -1 if none.
std::int32_t most_sides_with(const RasterPlan& plan, const FaceParts& parts, std::size_t part) {
  const Grid<std::int32_t>& face = plan.face;
  const std::int32_t own = parts.face[part];
  std::map<std::int32_t, int> sides;
  for (const std::uint32_t k : parts.runs_of[part]) {
    const Run& run = parts.runs[k];
    for (int c = run.c0; c < run.c1; ++c)
      for (const auto& [dc, dr] : kFourNeighbours)
        if (face.contains(c + dc, run.row + dr)) {
          const std::int32_t g = face(c + dc, run.row + dr);
          if (g >= 0 && g != own && !plan.faces[static_cast<std::size_t>(g)].hole) ++sides[g];
        }
  }
  if (sides.empty()) return -1;
  return std::ranges::max_element(sides, {}, [](const auto& s) { return s.second; })->first;
}

}  // namespace

SplitFaces split_disconnected_faces(RasterPlan result, const std::vector<std::int32_t>& faces, std::int64_t min_part_px,
                                    int min_part_cols) {
  Grid<std::int32_t>& face = result.face;
  std::vector<std::uint8_t> wanted(result.faces.size(), 0);
  for (const std::int32_t f : faces)
    if (f >= 0 && !result.faces[static_cast<std::size_t>(f)].hole) wanted[static_cast<std::size_t>(f)] = 1;
  const FaceParts parts = parts_of(face, wanted);
  const auto paint = [&](std::size_t part, std::int32_t id) {
    for (const std::uint32_t k : parts.runs_of[part]) {
      const Run& run = parts.runs[k];
      std::fill_n(&face.values[face.index(run.c0, run.row)], run.c1 - run.c0, id);
    }
  };
  // The largest part of each face keeps its id (the first of equals, for determinism).
  std::vector<std::int32_t> keeper(result.faces.size(), -1);
  for (std::size_t i = 0; i < parts.runs_of.size(); ++i) {
    std::int32_t& k = keeper[static_cast<std::size_t>(parts.face[i])];
    if (k < 0 || parts.size[i] > parts.size[static_cast<std::size_t>(k)]) k = static_cast<std::int32_t>(i);
  }
  std::vector<FacePart> created;
  for (std::size_t i = 0; i < parts.runs_of.size(); ++i) {
    const auto f = static_cast<std::size_t>(parts.face[i]);
    const std::int64_t size = parts.size[i];
    const bool kept = keeper[f] == static_cast<std::int32_t>(i);
    if (kept && (f < 2 || size >= min_part_px)) {
      result.faces[f].pixels = size;
      continue;
    }
    int lo = INT_MAX, hi = -1;
    for (const std::uint32_t k : parts.runs_of[i])
      lo = std::min(lo, parts.runs[k].c0), hi = std::max(hi, parts.runs[k].c1 - 1);
    if (size < min_part_px || (!kept && hi - lo + 1 < min_part_cols)) {
      // A crumb joins the face it shares the most pixel sides with.
      if (const std::int32_t into = most_sides_with(result, parts, i); into >= 0) {
        paint(i, into);
        result.faces[static_cast<std::size_t>(into)].pixels += size;
        if (kept) result.faces[f].pixels = 0;
        continue;
      }
      if (kept) {
        result.faces[f].pixels = size;
        continue;
      }
    }
    const auto id = static_cast<std::int32_t>(result.faces.size());
    RasterFace piece = result.faces[f];
    piece.pixels = size;
    result.faces.push_back(piece);
    paint(i, id);
    created.push_back({id, static_cast<std::int32_t>(f)});
  }
  return {std::move(result), std::move(created)};
}

namespace {

// Where the raster plan's V/H boundaries belong: the pixel row edge nearest each fold line.
struct FoldRows {
  const PixelGrid& grid;
  double tolerance_mm;

  // Where faces a (row r) and b (row r + 1 below it) should meet: their fold line Y = h - d lies
  // between rows t and t + 1, Y = (rows_above_fold - t - 1) / px_per_mm. -1 when they meet on no
  // fold within tolerance_mm of their boundary (and for a line above the sheet, which nothing can
  // reach).
  int row(const RasterPlan& plan, std::int32_t a, std::int32_t b, int r) const {
    if (a == b || a < 0 || b < 0) return -1;
    const RasterFace &fa = plan.faces[static_cast<std::size_t>(a)], &fb = plan.faces[static_cast<std::size_t>(b)];
    if (fa.orientation == fb.orientation || fa.hole || fb.hole) return -1;
    const double fold_Y = fold_line_Y(fa.orientation, fa.depth_mm, fb.depth_mm);
    const double edge_Y = grid.Y(r) - 0.5 / grid.px_per_mm;
    if (!(std::abs(edge_Y - fold_Y) <= tolerance_mm)) return -1;
    return row_above(fold_Y);
  }

  // The row above the pixel edge nearest the line Y = fold_Y.
  int row_above(double fold_Y) const {
    return static_cast<int>(std::lround(grid.rows_above_fold - 1 - fold_Y * grid.px_per_mm));
  }
};

// The last row of the run of face(col, start) in its column, from `start` on the way `away` (+1
// down, -1 up).
int run_end(const Grid<std::int32_t>& face, int col, int start, int away) {
  int end = start;
  while (0 <= end + away && end + away < face.rows && face(col, end + away) == face(col, start)) end += away;
  return end;
}

// Face g's run in a column from its boundary with f (below row r if f is above it, else above it)
// to where it meets face `onto`: its first and last rows, and onto's row beyond them; none if the
// run ends on another face.
struct RunTo {
  int first, last, beyond;
};
std::optional<RunTo> run_to(const Grid<std::int32_t>& face, int col, int r, bool f_above, std::int32_t onto) {
  const int start = f_above ? r + 1 : r, away = f_above ? 1 : -1;
  const int end = run_end(face, col, start, away);
  const int beyond = end + away;
  if (beyond < 0 || beyond >= face.rows || face(col, beyond) != onto) return std::nullopt;
  return RunTo{std::min(start, end), std::max(start, end), beyond};
}

// One sweep of align_folds_to_lines over one column; returns how many pixels changed face.
std::int64_t align_column(RasterPlan& result, const FoldRows& folds, int col) {
  std::int64_t moved = 0;
  Grid<std::int32_t>& face = result.face;
  auto count = [&](std::int32_t f, int delta) { result.faces[static_cast<std::size_t>(f)].pixels += delta; };
  for (int r = 0; r + 1 < face.rows; ++r) {
    const std::int32_t a = face(col, r), b = face(col, r + 1);  // a above, b below
    const int t = folds.row(result, a, b, r);
    if (t == -1 || t == r) continue;
    if (t < r) {  // up: b takes rows t + 1 .. r if they are all a and a keeps row t
      bool free = t >= 0 && face(col, t) == a;
      for (int k = t + 1; free && k <= r; ++k) free = face(col, k) == a;
      if (!free) continue;
      for (int k = t + 1; k <= r; ++k) face(col, k) = b, count(a, -1), count(b, 1), ++moved;
    } else {  // down: a takes rows r + 1 .. t if they are all b and b keeps row t + 1
      bool free = t + 1 < face.rows && face(col, t + 1) == b;
      for (int k = r + 1; free && k <= t; ++k) free = face(col, k) == b;
      if (!free) continue;
      for (int k = r + 1; k <= t; ++k) face(col, k) = a, count(b, -1), count(a, 1), ++moved;
      r = t;  // continue below the moved boundary
    }
  }
  return moved;
}

// The first sweep of align_folds_to_lines; returns the columns in which pixels changed face.
// Columns are independent, so only those with a boundary off its line are walked: a row-major scan
// finds them far faster than walking every column down.
std::vector<int> align_sweep(RasterPlan& result, const FoldRows& folds) {
  const Grid<std::int32_t>& face = result.face;
  std::vector<std::uint8_t> off_line(static_cast<std::size_t>(face.cols), 0);
  for (int r = 0; r + 1 < face.rows; ++r) {
    const std::int32_t* above = &face.values[face.index(0, r)];
    const std::int32_t* below = above + face.cols;
    bool last_off = false;  // FoldRows::row of the previous column's pair: the same pair gives the same row
    for (int col = 0; col < face.cols; ++col) {
      if (above[col] == below[col]) continue;
      if (col == 0 || above[col] != above[col - 1] || below[col] != below[col - 1]) {
        const int t = folds.row(result, above[col], below[col], r);
        last_off = t != -1 && t != r;
      }
      off_line[static_cast<std::size_t>(col)] |= last_off;
    }
  }
  std::vector<int> moved;
  for (int col = 0; col < face.cols; ++col)
    if (off_line[static_cast<std::size_t>(col)] && align_column(result, folds, col) > 0) moved.push_back(col);
  return moved;
}

}  // namespace

std::optional<RasterPlan> move_plane(const RasterPlan& plan, const PixelGrid& grid, std::int32_t f, double depth_mm,
                                     double tolerance_mm, int min_run_px, std::optional<std::pair<int, int>> columns,
                                     std::optional<std::int32_t> onto) {
  assert(f > kFloorFace && static_cast<std::size_t>(f) < plan.faces.size() &&
         !plan.faces[static_cast<std::size_t>(f)].hole);
  assert(!onto || (*onto != f && !plan.faces[static_cast<std::size_t>(*onto)].hole &&
                   plan.faces[static_cast<std::size_t>(*onto)].orientation ==
                       plan.faces[static_cast<std::size_t>(f)].orientation &&
                   plan.faces[static_cast<std::size_t>(*onto)].depth_mm == depth_mm));
  // The folds are found on the planes as they are, then moved to the new plane's lines: first each
  // move is checked (most that fail, fail here), then the plan copied and the moves made.
  const FoldRows old_folds{grid, tolerance_mm};
  const auto new_row = [&](std::int32_t a, std::int32_t b) {  // FoldRows::row of a above b, f moved
    const RasterFace &fa = plan.faces[static_cast<std::size_t>(a)], &fb = plan.faces[static_cast<std::size_t>(b)];
    return old_folds.row_above(
        fold_line_Y(fa.orientation, a == f ? depth_mm : fa.depth_mm, b == f ? depth_mm : fb.depth_mm));
  };
  struct Rows {
    int col, first, last;
    std::int32_t taker, giver;
    int kept_row, away;      // the giver's first row kept (-1: none), and the way its run goes on
    bool closes;             // a strip between f and `onto`: the giver keeps none
    bool gives_all = false;  // the giver's run ends short of the new line: it keeps none
  };
  std::vector<Rows> given;
  const Grid<std::int32_t>& face = plan.face;
  const auto [first_col, last_col] = columns.value_or(std::pair{0, face.cols - 1});
  for (int col = first_col; col <= last_col; ++col)
    for (int r = 0; r + 1 < face.rows; ++r) {
      const std::int32_t a = face(col, r), b = face(col, r + 1);  // a above, b below
      if (a == b || (a != f && b != f)) continue;
      // A strip between f and `onto` closes: folded to both, f takes all its rows; else it would
      // lie between two parts of onto, and nothing moves.
      if (const std::int32_t g = a == f ? b : a; onto && g != *onto)
        if (const std::optional<RunTo> strip = run_to(face, col, r, a == f, *onto)) {
          const bool folded =
              old_folds.row(plan, a, b, r) != -1 &&
              old_folds.row(plan, a == f ? g : *onto, a == f ? *onto : g, a == f ? strip->last : strip->beyond) != -1;
          if (!folded) return std::nullopt;
          given.push_back({col, strip->first, strip->last, f, g, strip->beyond, a == f ? 1 : -1, true});
          continue;
        }
      // A boundary the exact plan would snap onto its fold moves with it, as far off it as before
      // (one that could not be aligned stays so: res_dragon_full's ends of a fold 5-7 px off it).
      const int on_line = old_folds.row(plan, a, b, r);
      if (on_line == -1) continue;
      const int t = r + new_row(a, b) - on_line;
      if (t == r) continue;
      if (t < 0 || t + 1 >= face.rows) return std::nullopt;
      // Rows r + 1 .. t go to a, or t + 1 .. r to b, as the fold moves down or up; no other face
      // lies between, and the face that gives them keeps a row beyond (min_run_px once all move);
      // or it keeps none, its run there ending short of the new line: it gives the whole run.
      auto [first, last, taker] = t > r ? std::tuple{r + 1, t, a} : std::tuple{t + 1, r, b};
      const std::int32_t giver = taker == a ? b : a;
      const int kept_row = taker == a ? t + 1 : t, away = taker == a ? 1 : -1;
      if (face(col, kept_row) != giver) {
        // The taker then meets the face beyond the run (across a cut, or a fold where their line
        // falls there): not f itself (the giver lay between two parts of f), and where f gives,
        // not across a fold of f's (that fold moves with f too, and the two moves would not
        // agree). While every such move was refused, the 37 models at W = 3 mm had 179 faces
        // between two folds under W apart (now 171) and a mean p95 of 1.765 W (now 1.756 W: the
        // refits move more faces, res_knot 2.06 -> 1.99 W).
        const int end = run_end(face, col, away > 0 ? first : last, away), beyond = end + away;
        assert(0 <= beyond && beyond < face.rows);  // the run ends before kept_row, on the sheet
        const std::int32_t x = face(col, beyond);
        const bool folded =
            away > 0 ? old_folds.row(plan, giver, x, end) != -1 : old_folds.row(plan, x, giver, beyond) != -1;
        if (x == f || (giver == f && folded)) return std::nullopt;
        if (away > 0)
          last = end;
        else
          first = end;
        given.push_back({col, first, last, taker, giver, -1, away, false, true});
        continue;
      }
      for (int k = first; k <= last; ++k)
        if (face(col, k) != giver) return std::nullopt;
      given.push_back({col, first, last, taker, giver, kept_row, away, false});
    }
  if (onto && std::ranges::none_of(given, &Rows::closes)) return std::nullopt;
  // The face at a pixel once the moves are made: the taker of the last run given there (the runs
  // are listed column by column), else the face there now, f in onto's plane part of onto.
  const auto moved_face = [&](int col, int row) {
    const auto in_col = std::ranges::equal_range(given, col, {}, &Rows::col);
    const auto covering = std::ranges::find_if(std::views::reverse(in_col),
                                               [&](const Rows& g) { return g.first <= row && row <= g.last; });
    const std::int32_t now = covering != std::views::reverse(in_col).end() ? covering->taker : face(col, row);
    return onto && now == f ? *onto : now;
  };
  // Each face that gave rows keeps min_run_px of its run there, counted as the move leaves it: f
  // moving gives rows at one fold as it takes as many at the other (a support W wide keeps W; on
  // the plan before the move, 107 of the 434 moves refused over the 37 models at W = 3 mm). A face
  // whose run there was shorter than min_run_px before the move is a place narrower than W
  // already: it need only keep a row (kept_row, above), or give its whole run. Refusing those too,
  // the refits and fold spreads of the 37 models at W = 3 mm left res_knot at 2.13 W with 10
  // planes refit (then 1.99 W, 15) and 183 faces between two folds closer than W (then 178; places
  // in all 3,880 and 3,879). Checked before the plan is copied: most moves that come this far are
  // refused here (res_dragon_full: 76 of 132).
  for (const auto& [col, first, last, taker, giver, kept_row, away, closes, gives_all] : given) {
    if (closes || gives_all) continue;
    int run_before = 0;  // from its row beside the old boundary on, up to min_run_px
    for (int row = away > 0 ? first : last;
         run_before < min_run_px && 0 <= row && row < face.rows && face(col, row) == giver; row += away)
      ++run_before;
    if (run_before < min_run_px) continue;
    const std::int32_t kept = giver == f && onto ? *onto : giver;
    for (int k = 1; k < min_run_px; ++k) {
      const int row = kept_row + away * k;
      if (row < 0 || row >= face.rows || moved_face(col, row) != kept) return std::nullopt;
    }
  }
  RasterPlan moved_planes = plan;
  moved_planes.faces[static_cast<std::size_t>(f)].depth_mm = depth_mm;
  std::vector<std::uint8_t> gave(plan.faces.size(), 0);
  for (const auto& [col, first, last, taker, giver, kept_row, away, closes, gives_all] : given) {
    for (int k = first; k <= last; ++k) moved_planes.face(col, k) = taker;
    moved_planes.faces[static_cast<std::size_t>(giver)].pixels -= last - first + 1;
    moved_planes.faces[static_cast<std::size_t>(taker)].pixels += last - first + 1;
    gave[static_cast<std::size_t>(giver)] = 1;
  }
  // f, in onto's plane, becomes part of it (it touches it where a strip closed).
  if (onto) {
    for (std::int32_t& g : moved_planes.face.values)
      if (g == f) g = *onto;
    moved_planes.faces[static_cast<std::size_t>(*onto)].pixels +=
        std::exchange(moved_planes.faces[static_cast<std::size_t>(f)].pixels, 0);
    gave[static_cast<std::size_t>(*onto)] = 1;  // and is one piece of paper with it
  }
  // A face that gave pixels and is now in two parts would be two pieces of paper, the one without
  // the fold unheld.
  const auto parts_per_face = [&](const Grid<std::int32_t>& map) {
    std::vector<int> parts(plan.faces.size(), 0);
    for (const std::int32_t g : parts_of(map, gave).face) ++parts[static_cast<std::size_t>(g)];
    return parts;
  };
  // (A face in one part or none after the move is in no more than before: the plan before is
  // searched only when one is in more, which few moves leave.)
  const std::vector<int> after = parts_per_face(moved_planes.face);
  if (std::ranges::any_of(after, [](int parts) { return parts > 1; })) {
    const std::vector<int> before = parts_per_face(plan.face);
    for (std::size_t g = 0; g < before.size(); ++g)
      if (after[g] > before[g]) return std::nullopt;
  }
  return moved_planes;
}

RasterPlan align_folds_to_lines(RasterPlan plan, const PixelGrid& grid, double tolerance_mm) {
  // A moved boundary can free another one in its column: sweep those columns again until nothing
  // moves, so that aligning an aligned plan changes nothing (build_plan aligns what it is given).
  // Columns are independent, so one in which nothing moved would not move on a later sweep.
  const FoldRows folds{grid, tolerance_mm};
  std::vector<int> moved = align_sweep(plan, folds);
  for (int sweep = 1; sweep < 8 && !moved.empty(); ++sweep)
    std::erase_if(moved, [&](int col) { return align_column(plan, folds, col) == 0; });
  return plan;
}

}  // namespace origamic

namespace origamic {

RasterPlan merge_near_coplanar_faces(RasterPlan result, double tolerance_mm) {
  const Grid<std::int32_t>& face = result.face;
  const std::size_t n = result.faces.size();
  // The pairs of faces of one orientation that touch, each once.
  std::set<std::pair<std::int32_t, std::int32_t>> touching;
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c) {
      const std::int32_t f = face(c, r);
      if (f < 0) continue;
      for (const auto& [dc, dr] : {std::pair{1, 0}, {0, 1}}) {
        if (!face.contains(c + dc, r + dr)) continue;
        const std::int32_t g = face(c + dc, r + dr);
        if (g < 0 || g == f) continue;
        const RasterFace &a = result.faces[static_cast<std::size_t>(f)], &b = result.faces[static_cast<std::size_t>(g)];
        if (a.orientation != b.orientation || a.hole || b.hole || a.support || b.support) continue;
        if (std::abs(a.depth_mm - b.depth_mm) <= tolerance_mm) touching.emplace(std::min(f, g), std::max(f, g));
      }
    }
  if (touching.empty()) return result;
  // Closest pairs first; a group's depths stay within the tolerance of each other.
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs(touching.begin(), touching.end());
  const auto gap = [&](const std::pair<std::int32_t, std::int32_t>& p) {
    return std::abs(result.faces[static_cast<std::size_t>(p.first)].depth_mm -
                    result.faces[static_cast<std::size_t>(p.second)].depth_mm);
  };
  std::ranges::stable_sort(pairs, {}, gap);
  UnionFind<std::int32_t> sets(n);
  std::vector<double> lo(n), hi(n), weighted(n);
  std::vector<std::int64_t> pixels(n);
  for (std::size_t f = 0; f < n; ++f) {
    lo[f] = hi[f] = result.faces[f].depth_mm;
    pixels[f] = std::max<std::int64_t>(1, result.faces[f].pixels);
    weighted[f] = result.faces[f].depth_mm * static_cast<double>(pixels[f]);
  }
  bool merged = false;
  for (const auto& [f, g] : pairs) {
    const auto a = static_cast<std::size_t>(sets.root(f)), b = static_cast<std::size_t>(sets.root(g));
    if (a == b || std::max(hi[a], hi[b]) - std::min(lo[a], lo[b]) > tolerance_mm) continue;
    if (a < 2 && b < 2) continue;
    const std::size_t into = std::min(a, b), from = std::max(a, b);  // the back plane and the floor keep their ids
    sets.join(static_cast<std::int32_t>(a), static_cast<std::int32_t>(b));
    lo[into] = std::min(lo[a], lo[b]), hi[into] = std::max(hi[a], hi[b]);
    weighted[into] += weighted[from], pixels[into] += pixels[from];
    merged = true;
  }
  if (!merged) return result;
  for (std::size_t f = 0; f < n; ++f)
    if (sets.root(static_cast<std::int32_t>(f)) == static_cast<std::int32_t>(f) && f >= 2)
      result.faces[f].depth_mm = weighted[f] / static_cast<double>(pixels[f]);
  for (std::int32_t& f : result.face.values)
    if (f >= 0) f = sets.root(f);
  return merge_coplanar_faces(std::move(result));
}

}  // namespace origamic
