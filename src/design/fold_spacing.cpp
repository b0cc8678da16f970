// SPDX-License-Identifier: GPL-3.0-or-later
#include "fold_spacing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "origamic/oa.hpp"
#include "plane_refit.hpp"
#include "raster_card.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

// The plane of a face of orientation `is` that puts its fold with a face of the other orientation
// and depth `other_mm` on the line Y.
double plane_for_fold(Orientation is, double other_mm, double Y) {
  return is == Orientation::H ? Y + other_mm : other_mm - Y;
}

// Two folds are moved this much more than W apart: the new plane is a double, a rounding off the
// plane exactly W away, and the validator finds a strip narrower than W below W less 1e-6 mm.
constexpr double kPastW_mm = 2 * kFoldLineTolerance_mm;

struct Move {
  std::int32_t face = -1;
  double to_mm = 0;
};

// fold_pairs_under_W in columns first_col .. last_col.
std::vector<FoldPair> fold_pairs_in_columns(const RasterPlan& raster_plan, const PixelGrid& grid, double tolerance_mm,
                                            int first_col, int last_col) {
  const double W = raster_plan.min_strip_mm;
  const Grid<std::int32_t>& face = raster_plan.face;
  const auto at = [&](std::int32_t f) -> const RasterFace& { return raster_plan.faces[static_cast<std::size_t>(f)]; };
  // The fold line between faces a (row r) and b below it, if their boundary is a fold.
  const auto fold_Y = [&](std::int32_t a, std::int32_t b, int r) -> std::optional<double> {
    if (a < 0 || b < 0 || at(a).orientation == at(b).orientation || at(a).hole || at(b).hole) return std::nullopt;
    const double Y = fold_line_Y(at(a).orientation, at(a).depth_mm, at(b).depth_mm);
    const double edge_Y = grid.Y(r) - 0.5 / grid.px_per_mm;
    if (!(std::abs(edge_Y - Y) <= tolerance_mm)) return std::nullopt;
    return Y;
  };
  std::vector<FoldPair> pairs;
  for (int c = first_col; c <= last_col; ++c) {
    struct FoldAt {
      std::int32_t above, below;
      double Y;
    };
    std::optional<FoldAt> last;  // the fold just above the run of rows being walked
    for (int r = 0; r + 1 < face.rows; ++r) {
      const std::int32_t a = face(c, r), b = face(c, r + 1);
      if (a == b) continue;
      const std::optional<double> Y = fold_Y(a, b, r);
      if (Y && last && last->below == a) {
        const double apart = last->Y - *Y;
        if (apart > 0 && apart < W - kFoldLineTolerance_mm) pairs.push_back({last->above, a, b, apart});
      }
      last = Y ? std::optional<FoldAt>({a, b, *Y}) : std::nullopt;
    }
  }
  const auto key = [](const FoldPair& p) { return std::tuple{p.above, p.strip, p.below}; };
  std::ranges::sort(pairs, {}, key);
  pairs.erase(std::ranges::unique(pairs, {}, key).begin(), pairs.end());
  return pairs;
}

}  // namespace

std::vector<FoldPair> fold_pairs_under_W(const RasterPlan& raster_plan, const PixelGrid& grid, double tolerance_mm) {
  return fold_pairs_in_columns(raster_plan, grid, tolerance_mm, 0, raster_plan.face.cols - 1);
}

SupportedPlan spread_fold_pairs(const RasterMaps& maps, SupportedPlan supported, const Sheet& sheet,
                                const PlanOptions& plan_options, bool allow_dangling, const FoldSpacingCheck& keep,
                                const FoldSpacingOptions& options) {
  const double W = supported.raster_plan.min_strip_mm;
  const double tolerance = fold_snap_tolerance_mm(plan_options, supported.raster_plan, maps.grid);
  RasterPlan raster_plan = supported.raster_plan;
  std::vector<FoldPair> pairs = fold_pairs_under_W(raster_plan, maps.grid, tolerance);
  if (pairs.empty()) return supported;
  // The first and last column of each face: a plane's folds move in its columns only.
  std::vector<std::pair<int, int>> columns(raster_plan.faces.size(), {maps.grid.cols, -1});
  std::int64_t model_pixels = 0;
  for (int r = 0; r < maps.grid.rows; ++r)
    for (int c = 0; c < maps.grid.cols; ++c) {
      if (const std::int32_t f = raster_plan.face(c, r); f >= 0) {
        auto& [first, last] = columns[static_cast<std::size_t>(f)];
        first = std::min(first, c), last = std::max(last, c);
      }
      model_pixels += maps.kind(c, r) == HitKind::Model;
    }
  RasterCard card(maps, raster_plan);
  const std::pair<int, double> start = card.counts().fares();
  const auto bearable = [&](const std::pair<int, double>& fared) {
    return fared.first <= start.first + static_cast<int>(options.may_add_p95_W * 256) &&
           fared.second <= start.second + options.may_add_mean_W * W * static_cast<double>(model_pixels);
  };
  const std::vector<std::int32_t> unheld = faces_unheld_on_raster(maps.grid, raster_plan, allow_dangling);
  std::vector<RefitPlane> spread;
  // The pairs nearest W apart first: their moves are the smallest.
  std::ranges::sort(pairs, [](const FoldPair& a, const FoldPair& b) { return a.apart_mm > b.apart_mm; });
  const auto pairs_in = [&](const RasterPlan& plan, std::int32_t f) {
    const auto [first_col, last_col] = columns[static_cast<std::size_t>(f)];
    return fold_pairs_in_columns(plan, maps.grid, tolerance, first_col, last_col);
  };
  for (const FoldPair& pair : pairs) {
    // The pair as the moves before left it: gone, or its folds elsewhere.
    const std::vector<FoldPair> now = pairs_in(raster_plan, pair.strip);
    const auto it = std::ranges::find_if(now, [&](const FoldPair& p) {
      return p.above == pair.above && p.strip == pair.strip && p.below == pair.below;
    });
    if (it == now.end()) continue;
    const RasterFace& strip = raster_plan.faces[static_cast<std::size_t>(it->strip)];
    const RasterFace &above = raster_plan.faces[static_cast<std::size_t>(it->above)],
                     &below = raster_plan.faces[static_cast<std::size_t>(it->below)];
    const double above_Y = fold_line_Y(above.orientation, above.depth_mm, strip.depth_mm);
    const double below_Y = fold_line_Y(strip.orientation, strip.depth_mm, below.depth_mm);
    const Move candidates[] = {{it->above, plane_for_fold(above.orientation, strip.depth_mm, below_Y + W + kPastW_mm)},
                               {it->below, plane_for_fold(below.orientation, strip.depth_mm, above_Y - W - kPastW_mm)}};
    // Each move that leaves fewer pairs in the face's columns, with the card it makes.
    struct Tried {
      std::pair<int, double> fared;
      Move move;
      RasterPlan plan;
    };
    std::vector<Tried> tried;
    for (const Move& move : candidates) {
      const RasterFace& f = raster_plan.faces[static_cast<std::size_t>(move.face)];
      if (move.face <= kFloorFace || f.hole || !(move.to_mm > 0)) continue;
      std::optional<RasterPlan> moved =
          move_plane(raster_plan, maps.grid, move.face, move.to_mm, tolerance, raster_plan.block_px);
      if (!moved || pairs_in(*moved, move.face).size() >= pairs_in(raster_plan, move.face).size()) continue;
      const auto [first_col, last_col] = columns[static_cast<std::size_t>(move.face)];
      std::vector<PixelAt> changed;
      for (int r = 0; r < maps.grid.rows; ++r)
        for (int c = first_col; c <= last_col; ++c)
          if (const std::int32_t g = moved->face(c, r); g != raster_plan.face(c, r) || g == move.face) {
            changed.push_back({c, r});
            card.update(*moved, c, r);
          }
      const std::pair<int, double> fared = card.counts().fares();
      for (const auto [c, r] : changed) card.update(raster_plan, c, r);
      if (bearable(fared)) tried.push_back({fared, move, std::move(*moved)});
    }
    // The one that shows the model best and, as the raster plan's folds say, leaves none unheld
    // that was held.
    std::ranges::sort(tried, {}, &Tried::fared);
    const auto made = std::ranges::find_if(tried, [&](const Tried& t) {
      return std::ranges::includes(unheld, faces_unheld_on_raster(maps.grid, t.plan, allow_dangling));
    });
    if (made == tried.end()) continue;
    const RasterFace& f = raster_plan.faces[static_cast<std::size_t>(made->move.face)];
    PixelAt at{-1, -1};
    const auto [first_col, last_col] = columns[static_cast<std::size_t>(made->move.face)];
    for (int r = 0; r < maps.grid.rows; ++r)
      for (int c = first_col; c <= last_col; ++c) {
        const std::int32_t g = made->plan.face(c, r);
        if (g != raster_plan.face(c, r) || g == made->move.face) card.update(made->plan, c, r);
        if (at.c < 0 && g == made->move.face) at = {c, r};
      }
    spread.push_back({{maps.grid.X(at.c), maps.grid.Y(at.r)}, f.orientation, f.support, f.depth_mm, made->move.to_mm});
    raster_plan = std::move(made->plan);
  }
  if (spread.empty()) return supported;
  const PlanFares before = plan_fares(maps, supported.plan, W, allow_dangling);
  Plan plan = build_plan(maps, raster_plan, sheet, plan_options);
  const PlanFares fared = plan_fares(maps, plan, W, allow_dangling);
  if (fared.fails || fared.p95_W > before.p95_W + options.may_add_p95_W ||
      fared.mean_W > before.mean_W + options.may_add_mean_W || (keep && !keep(supported.plan, plan)))
    return supported;
  supported.raster_plan = std::move(raster_plan);
  supported.plan = std::move(plan);
  supported.report.drawn_in_mirror_image = false;  // drawn here, from the raster plan moved
  supported.report.narrow = narrow_strips(supported.raster_plan, maps.grid);
  supported.report.planes_spread = std::move(spread);
  return supported;
}

}  // namespace origamic
