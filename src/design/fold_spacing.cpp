// SPDX-License-Identifier: GPL-3.0-or-later
#include "fold_spacing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
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

using raster_card::ErrorCounts;
using raster_card::PixelAt;
using raster_card::RasterCard;

// The plane of a face of orientation `is` that puts its fold with a face of the other orientation
// and depth `other_mm` on the line Y.
double plane_for_fold(Orientation is, double other_mm, double Y) {
  return is == Orientation::H ? Y + other_mm : other_mm - Y;
}

// Two folds are moved this much more than W apart: the new plane is a double, a rounding (about
// 1e-14 mm) off the plane exactly W away, and the folds must come out W apart or more however it
// falls.
constexpr double kPastW_mm = 2 * kFoldLineTolerance_mm;

struct Move {
  std::int32_t face = -1;
  double to_mm = 0;
  std::optional<std::int32_t> onto;  // the face whose plane it takes, the strip closed (move_plane)
};

struct PixelBox {
  int first_col, last_col, first_row, last_row;
};

void grow(PixelBox& b, int c, int r) {
  b.first_col = std::min(b.first_col, c), b.last_col = std::max(b.last_col, c);
  b.first_row = std::min(b.first_row, r), b.last_row = std::max(b.last_row, r);
}

std::vector<PixelBox> face_boxes(const RasterPlan& raster_plan) {
  const Grid<std::int32_t>& face = raster_plan.face;
  std::vector<PixelBox> boxes(raster_plan.faces.size(), {face.cols, -1, face.rows, -1});
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c)
      if (const std::int32_t f = face(c, r); f >= 0) grow(boxes[static_cast<std::size_t>(f)], c, r);
  return boxes;
}

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
        if (apart > kFoldLineTolerance_mm && apart < W) pairs.push_back({last->above, a, b, apart});
      }
      last = Y ? std::optional<FoldAt>({a, b, *Y}) : std::nullopt;
    }
  }
  const auto key = [](const FoldPair& p) { return std::tuple{p.above, p.strip, p.below}; };
  std::ranges::sort(pairs, {}, key);
  pairs.erase(std::ranges::unique(pairs, {}, key).begin(), pairs.end());
  return pairs;
}

// The raster plan as the moves so far leave it, the card it shows (estimated on it) and its faces'
// boxes of pixels.
class Spreader {
 public:
  Spreader(const RasterMaps& maps, RasterPlan raster_plan, double tolerance_mm, bool allow_dangling,
           const FoldSpacingOptions& options, std::vector<bool> barred)
      : maps_(maps),
        plan_(std::move(raster_plan)),
        tolerance_mm_(tolerance_mm),
        allow_dangling_(allow_dangling),
        options_(options),
        card_(maps, plan_),
        start_(card_.counts().fares()),
        unheld_(faces_unheld_on_raster(maps.grid, plan_, allow_dangling)),
        boxes_(face_boxes(plan_)),
        barred_(std::move(barred)) {
    for (int r = 0; r < maps.grid.rows; ++r)
      for (int c = 0; c < maps.grid.cols; ++c) model_pixels_ += maps.kind(c, r) == HitKind::Model;
  }

  const RasterPlan& plan() const { return plan_; }
  // A move made: the face moved, the pixels it changed and the other face beside the strip it parted.
  struct Made {
    std::int32_t face = -1;
    std::vector<PixelAt> changed;
    std::int32_t other = -1;
  };
  const std::vector<Made>& made() const { return made_; }  // in order

  // The pair, if the moves so far left it, parted or closed: one of the faces beside the strip
  // moved (to W from the other's plane, or into it), the move the card bears best among those that
  // leave fewer pairs in its columns and no face unheld on the raster that was held. The move made,
  // if any.
  std::optional<RefitPlane> part(const FoldPair& pair) {
    const std::vector<FoldPair> now = pairs_in(plan_, pair.strip);
    const auto it = std::ranges::find_if(now, [&](const FoldPair& p) {
      return p.above == pair.above && p.strip == pair.strip && p.below == pair.below;
    });
    if (it == now.end()) return std::nullopt;
    const double W = plan_.min_strip_mm;
    const RasterFace &strip = face(it->strip), &above = face(it->above), &below = face(it->below);
    const double above_Y = fold_line_Y(above.orientation, above.depth_mm, strip.depth_mm);
    const double below_Y = fold_line_Y(strip.orientation, strip.depth_mm, below.depth_mm);
    // The strip parted (one face W from the other) or closed (one face in the other's plane, the
    // two folds one step: issue 23). The face closed becomes part of the other, a support or a face
    // of the model as that is: no face of the model closes onto a support (its edges would be drawn
    // as a support's, on the pixels), and none onto the back plane or the floor (it would show as
    // card). A support closing onto a face of the model closed 5 more pairs of the 188 at W = 3 mm.
    std::vector<Move> moves = {
        {it->above, plane_for_fold(above.orientation, strip.depth_mm, below_Y + W + kPastW_mm), {}},
        {it->below, plane_for_fold(below.orientation, strip.depth_mm, above_Y - W - kPastW_mm), {}}};
    const auto may_close = [&](std::int32_t f, std::int32_t onto) {
      return f > kFloorFace && onto > kFloorFace && (face(f).support || !face(onto).support);
    };
    if (may_close(it->above, it->below)) moves.push_back({it->above, below.depth_mm, it->below});
    if (may_close(it->below, it->above)) moves.push_back({it->below, above.depth_mm, it->above});
    // Of the moves that leave each face they take rows from W of its run there (or none), the one
    // the card bears best that leaves no face unheld on the raster that was held; where none does,
    // of those that leave such a face options_.giver_keeps_px.
    const auto holds = [&](const Tried& t) {
      std::vector<std::int32_t> unheld = faces_unheld_on_raster(maps_.grid, t.plan, allow_dangling_);
      std::erase_if(unheld, [&](std::int32_t g) { return t.plan.faces[static_cast<std::size_t>(g)].pixels == 0; });
      return std::ranges::includes(unheld_, unheld);
    };
    std::vector<Tried> tried;
    auto made = tried.end();
    for (const int giver_keeps_px : {plan_.block_px, options_.giver_keeps_px}) {
      tried.clear();
      for (const Move& move : moves)
        if (std::optional<Tried> t = try_move(move, giver_keeps_px)) tried.push_back(std::move(*t));
      std::ranges::stable_sort(tried, {}, &Tried::fared);
      made = std::ranges::find_if(tried, holds);
      if (made != tried.end() || !(0 < options_.giver_keeps_px && options_.giver_keeps_px < plan_.block_px)) break;
    }
    if (made == tried.end()) return std::nullopt;
    const RasterFace& f = face(made->move.face);
    RefitPlane moved{{}, f.orientation, f.support, f.depth_mm, made->move.to_mm, made->move.onto.has_value()};
    // Where the face is: a face closed onto another keeps no pixel, so it is found before the move.
    if (made->move.onto) moved.at = first_pixel(made->move.face);
    for (const auto [c, r] : made->changed) {
      card_.update(made->plan, c, r);
      if (const std::int32_t g = made->plan.face(c, r); g >= 0)
        grow(boxes_[static_cast<std::size_t>(g)], c, r);  // a box may hold more than its face
    }
    plan_ = std::move(made->plan);
    if (!made->move.onto) moved.at = first_pixel(made->move.face);
    made_.push_back({made->move.face, std::move(made->changed), made->move.face == it->above ? it->below : it->above});
    return moved;
  }

 private:
  // A move tried: the card it would show, the raster plan it makes and the pixels that change.
  struct Tried {
    std::pair<int, double> fared;
    Move move;
    RasterPlan plan;
    std::vector<PixelAt> changed;
  };

  const RasterFace& face(std::int32_t f) const { return plan_.faces[static_cast<std::size_t>(f)]; }

  // The centre of face f's first pixel, row by row.
  PlanPoint first_pixel(std::int32_t f) const {
    const PixelBox& box = boxes_[static_cast<std::size_t>(f)];
    for (int r = box.first_row; r <= box.last_row; ++r)
      for (int c = box.first_col; c <= box.last_col; ++c)
        if (plan_.face(c, r) == f) return {maps_.grid.X(c), maps_.grid.Y(r)};
    return {};
  }

  std::vector<FoldPair> pairs_in(const RasterPlan& plan, std::int32_t f) const {
    const PixelBox& box = boxes_[static_cast<std::size_t>(f)];
    return fold_pairs_in_columns(plan, maps_.grid, tolerance_mm_, box.first_col, box.last_col);
  }

  // The move (to a plane, or into another face's: move_plane's `onto`), if move_plane makes it with
  // each face it takes rows from keeping giver_keeps_px of its run there (or none), it leaves fewer
  // pairs in the face's columns and the card bears it; the card is left as it was.
  std::optional<Tried> try_move(const Move& move, int giver_keeps_px) {
    const RasterFace& f = face(move.face);
    if (move.face <= kFloorFace || f.hole || !(move.to_mm > 0) || barred_[static_cast<std::size_t>(move.face)])
      return std::nullopt;
    std::optional<RasterPlan> moved =
        move_plane(plan_, maps_.grid, move.face, move.to_mm, tolerance_mm_, giver_keeps_px,
                   std::pair{boxes_[static_cast<std::size_t>(move.face)].first_col,
                             boxes_[static_cast<std::size_t>(move.face)].last_col},
                   move.onto);
    if (!moved || pairs_in(*moved, move.face).size() >= pairs_in(plan_, move.face).size()) return std::nullopt;
    // The face's pixels show their new plane, and its folds moved at most as many rows past its box
    // as the plane moves.
    PixelBox box = boxes_[static_cast<std::size_t>(move.face)];
    const int rows = static_cast<int>(std::ceil(std::abs(move.to_mm - f.depth_mm) * maps_.grid.px_per_mm)) + 1;
    box.first_row = std::max(0, box.first_row - rows);
    box.last_row = std::min(maps_.grid.rows - 1, box.last_row + rows);
    Tried t{{}, move, std::move(*moved), {}};
    for (int r = box.first_row; r <= box.last_row; ++r)
      for (int c = box.first_col; c <= box.last_col; ++c)
        if (const std::int32_t g = t.plan.face(c, r); g != plan_.face(c, r) || g == move.face) {
          t.changed.push_back({c, r});
          card_.update(t.plan, c, r);
        }
    t.fared = card_.counts().fares();
    for (const auto [c, r] : t.changed) card_.update(plan_, c, r);
    const double W = plan_.min_strip_mm;
    const bool bearable =
        t.fared.first <= start_.first + std::lround(options_.may_add_p95_W * ErrorCounts::kBinsPerW) &&
        t.fared.second <= start_.second + options_.may_add_mean_W * W * static_cast<double>(model_pixels_);
    return bearable ? std::optional<Tried>(std::move(t)) : std::nullopt;
  }

  const RasterMaps& maps_;
  RasterPlan plan_;
  double tolerance_mm_;
  bool allow_dangling_;
  const FoldSpacingOptions& options_;
  RasterCard card_;
  std::pair<int, double> start_;  // the card as the plan was given
  std::vector<std::int32_t> unheld_;
  std::vector<PixelBox> boxes_;
  std::vector<bool> barred_;  // faces that may not move
  std::vector<Made> made_;
  std::int64_t model_pixels_ = 0;
};

// The faces of the moves that changed a pixel of, or next to, a face `plan` leaves unheld (in
// `spread_plan`, whose faces the exact plan's are, by index), barred from moving; whether any was
// not barred before. A plan that fails only by a loose piece of the back plane or the floor has no
// face unheld: nothing is barred.
bool bar_moves_beside_unheld(const Spreader& spreader, const RasterPlan& spread_plan, const Plan& plan,
                             bool allow_dangling, std::vector<bool>& barred) {
  const Grid<std::int32_t>& face = spread_plan.face;
  const auto unheld_at = [&](int c, int r) {
    if (c < 0 || r < 0 || c >= face.cols || r >= face.rows) return false;
    const std::int32_t f = face(c, r);
    return f >= 0 && needs_support(plan.faces[static_cast<std::size_t>(f)].status, allow_dangling);
  };
  bool more = false;
  for (const auto& [moved, changed, _] : spreader.made()) {
    if (barred[static_cast<std::size_t>(moved)]) continue;
    const bool beside = std::ranges::any_of(changed, [&](const PixelAt& p) {
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc)
          if (unheld_at(p.c + dc, p.r + dr)) return true;
      return false;
    });
    if (beside) barred[static_cast<std::size_t>(moved)] = true, more = true;
  }
  return more;
}

// The faces of the moves with more than one place `verdict` names worse than it names better within
// W of a pixel they changed (a move parts its pair, a place better: one place more is the trade the
// design accepts), and the other faces beside their strips (moving that one instead would change
// the same strip), barred from moving; whether any was barred. A place beside two moves counts
// against both. At W = 3 mm prim_cone's spread plan, 7 pairs parted at 9 more places, was refused
// whole; spread again without the moves beside those places, it parts 4 for 3 fewer places. Over
// the 37 models: fold pairs 95 -> 90, places 3,844 -> 3,833 (at 2 and 5 mm no plan changed).
bool bar_moves_adding_places(const Spreader& spreader, const PixelGrid& grid, double W,
                             const FoldSpacingVerdict& verdict, std::vector<bool>& barred) {
  const int reach_px = static_cast<int>(std::ceil(W * grid.px_per_mm));
  const auto pixels_of = [&](const std::vector<PlanPoint>& places) {
    std::vector<PixelAt> pixels;
    for (const PlanPoint p : places)
      pixels.push_back({static_cast<int>(std::floor(p.X * grid.px_per_mm)),
                        static_cast<int>(std::floor(grid.rows_above_fold - p.Y * grid.px_per_mm))});
    return pixels;
  };
  const std::vector<PixelAt> worse = pixels_of(verdict.worse_at), better = pixels_of(verdict.better_at);
  const std::vector<bool> barred_before = barred;  // each move weighed, whatever the others bar
  bool more = false;
  for (const auto& [moved, changed, other] : spreader.made()) {
    if (barred_before[static_cast<std::size_t>(moved)]) continue;
    const auto near = [&](const std::vector<PixelAt>& places) {
      return std::ranges::count_if(places, [&](PixelAt place) {
        return std::ranges::any_of(changed, [&](PixelAt p) {
          return std::abs(p.c - place.c) <= reach_px && std::abs(p.r - place.r) <= reach_px;
        });
      });
    };
    if (near(worse) - near(better) > 1) {
      barred[static_cast<std::size_t>(moved)] = true, more = true;
      if (other > kFloorFace) barred[static_cast<std::size_t>(other)] = true;
    }
  }
  return more;
}

}  // namespace

std::vector<FoldPair> fold_pairs_under_W(const RasterPlan& raster_plan, const PixelGrid& grid, double tolerance_mm) {
  return fold_pairs_in_columns(raster_plan, grid, tolerance_mm, 0, raster_plan.face.cols - 1);
}

SupportedPlan spread_fold_pairs(const RasterMaps& maps, SupportedPlan supported, const Sheet& sheet,
                                const PlanOptions& plan_options, bool allow_dangling, const FoldSpacingCheck& keep,
                                const FoldSpacingOptions& options, const PlanBuilder& build) {
  const double W = supported.raster_plan.min_strip_mm;
  const double tolerance = fold_snap_tolerance_mm(plan_options, supported.raster_plan, maps.grid);
  std::vector<FoldPair> pairs = fold_pairs_under_W(supported.raster_plan, maps.grid, tolerance);
  if (pairs.empty()) return supported;
  // The pairs nearest W apart first: their moves are the smallest.
  std::ranges::stable_sort(pairs, [](const FoldPair& a, const FoldPair& b) { return a.apart_mm > b.apart_mm; });
  std::optional<PlanFares> before;  // the plan given's, once a spread is to be judged against it
  std::vector<bool> barred(supported.raster_plan.faces.size(), false);
  for (int attempt = 0;; ++attempt) {
    Spreader spreader(maps, supported.raster_plan, tolerance, allow_dangling, options, barred);
    std::vector<RefitPlane> spread;
    for (const FoldPair& pair : pairs)
      if (std::optional<RefitPlane> moved = spreader.part(pair)) spread.push_back(*moved);
    if (spread.empty()) return supported;
    // Faces closed onto others, left without pixels, go (the ids close up).
    RasterPlan spread_plan =
        std::ranges::any_of(spread, &RefitPlane::closed) ? merge_coplanar_faces(spreader.plan()) : spreader.plan();
    Plan plan =
        build ? build(spread_plan) : build_plan(maps, spread_plan, sheet, plan_options, supported.plan.fallbacks);
    const PlanFares fared = plan_fares(maps, plan, W, allow_dangling);
    if (fared.fails) {
      // The exact plan snaps folds the raster plan's do not show: the moves that changed a pixel of,
      // or next to, a face it leaves unheld are not made again, and the rest are.
      if (attempt + 1 >= options.exact_builds ||
          !bar_moves_beside_unheld(spreader, spread_plan, plan, allow_dangling, barred))
        return supported;
      continue;
    }
    if (!before) before = plan_fares(maps, supported.plan, W, allow_dangling);
    if (fared.p95_W > before->p95_W + options.may_add_p95_W || fared.mean_W > before->mean_W + options.may_add_mean_W)
      return supported;
    if (const FoldSpacingVerdict verdict = keep ? keep(supported.plan, plan) : FoldSpacingVerdict{.keep = true};
        !verdict.keep) {
      // The moves beside the places the plan adds are not made again, and the rest are.
      if (attempt + 1 >= options.exact_builds || !bar_moves_adding_places(spreader, maps.grid, W, verdict, barred))
        return supported;
      continue;
    }
    supported.raster_plan = std::move(spread_plan);
    supported.plan = std::move(plan);
    if (!build) supported.report.drawn_in_mirror_image = false;  // drawn here, from the raster plan moved
    supported.report.narrow = narrow_strips(supported.raster_plan, maps.grid);
    supported.report.planes_spread = std::move(spread);
    return supported;
  }
}

}  // namespace origamic
