// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_choice.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <optional>
#include <span>
#include <tuple>
#include <utility>

#include "bands.hpp"
#include "origamic/plan.hpp"
#include "plane_numbers.hpp"

namespace origamic {
namespace {

class CandidateFinder {
 public:
  // Candidates will be asked of the faces in `wanted` only.
  CandidateFinder(const RasterMaps& maps, const SliceResult& slices, const PlanBuild& exact,
                  std::span<const Candidate> painted, const std::vector<std::int32_t>& wanted, double split_cost,
                  Reach reach)
      : exact_(exact),
        painted_(painted),
        grid_(maps.grid),
        face_(slices.face),
        faces_(slices.faces),
        split_cost_(split_cost),
        below_tips_(reach.below_tips),
        corners_(reach.corners),
        px_mm_(1 / maps.grid.px_per_mm),
        block_(slices.block_px),
        slot_(slices.faces.size(), -1) {
    for (const std::int32_t f : wanted)
      if (int& k = slot_[static_cast<std::size_t>(f)]; k < 0)
        k = static_cast<int>(columns_.size()), columns_.push_back({INT_MAX, -1});
    {
      PlaneNumbers plane;
      for (const RasterFace& f : faces_) plane_now_.push_back(plane(f));
      for (const RasterFace& f : exact_.faces()) plane_then_.push_back(plane(f));
      changed_.resize(static_cast<std::size_t>(face_.cols));
    }
    first_.assign(columns_.size() * static_cast<std::size_t>(face_.cols), -1);
    last_.assign(first_.size(), -1);
    // Bands of columns in parallel: each writes its own columns, and its own extents to merge.
    std::array<std::vector<std::pair<int, int>>, kBands> band_columns;
    for_bands(face_.cols, [&](int band, int c_begin, int c_end) {
      std::vector<std::pair<int, int>>& columns = band_columns[static_cast<std::size_t>(band)];
      columns.assign(columns_.size(), {INT_MAX, -1});
      const Grid<std::int32_t>& then = exact_.face_map();
      for (int r = 0; r < face_.rows; ++r) {
        const std::int32_t* row = &face_.values[face_.index(0, r)];
        const std::int32_t* was_row = &then.values[then.index(0, r)];
        // Run by run of one face now and one then: most runs are neither wanted nor changed.
        for (int c = c_begin; c < c_end;) {
          const std::int32_t f = row[c], was = was_row[c];
          int end = c + 1;
          while (end < c_end && row[end] == f && was_row[end] == was) ++end;
          if (changed(f, was))
            for (int k = c; k < end; ++k) note_change(r, k, f);
          if (f >= 0 && slot_[static_cast<std::size_t>(f)] >= 0) {
            const auto slot = static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)]);
            for (int k = c; k < end; ++k) {
              const std::size_t i = slot * face_.cols + k;
              if (first_[i] < 0) first_[i] = r;
              last_[i] = r;
            }
            auto& [lo, hi] = columns[slot];
            lo = std::min(lo, c), hi = std::max(hi, end - 1);
          }
          c = end;
        }
      }
    });
    for (const auto& band : band_columns)
      for (std::size_t slot = 0; slot < columns_.size(); ++slot)
        columns_[slot] = {std::min(columns_[slot].first, band[slot].first),
                          std::max(columns_[slot].second, band[slot].second)};
  }

  // Candidates from the top (up = true) or bottom edge of face f, one per W-wide block column that
  // f fills on that edge. (h, d) is the OA point of the edge: a support leaving it is H(h) reaching
  // back (or forward) to a V face, or V(d) reaching up (or down) to an H face.
  std::vector<Candidate> from_edge(std::int32_t f, bool up) const {
    std::vector<Candidate> candidates;
    const RasterFace& face = faces_[static_cast<std::size_t>(f)];
    // The block columns, and the two flush with the face's ends: a support there trims the faces it
    // crosses where they end with the face, instead of cutting them in two.
    const auto [lo, hi] = columns_[static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)])];
    if (lo > hi) return candidates;  // no pixels left: no edge to hold
    // With Reach::corners, one more at each end, extended a strip width beyond the face.
    struct Start {
      int c0, c1;
      double extra_cost;
    };
    std::vector<Start> starts;
    for (int c0 = std::max(0, lo) / block_ * block_; c0 <= hi && c0 + block_ <= face_.cols; c0 += block_)
      starts.push_back({c0, c0 + block_, 0});
    for (const int c0 : {lo, hi + 1 - block_})
      if (c0 >= 0 && c0 + block_ <= face_.cols && c0 % block_ != 0) starts.push_back({c0, c0 + block_, 0});
    const double corner_cost = block_ * px_mm_;
    if (corners_ && lo - block_ >= 0 && lo + block_ <= face_.cols)
      starts.push_back({lo - block_, lo + block_, corner_cost});
    if (corners_ && hi + 1 - block_ >= 0 && hi + 1 + block_ <= face_.cols)
      starts.push_back({hi + 1 - block_, hi + 1 + block_, corner_cost});
    BlockColumn column(face_.rows);
    for (const auto [c0, c1, extra_cost] : starts) {
      column.reset(c0, c1);
      column.paint(*this, painted_);
      // The edge row: f's top (bottom) at the block column's centre. A support needs f along at
      // least half of its near side and its target along half of its far side: slices of curved
      // surfaces cross a W-wide column at a slant, and the rest of either side is a cut.
      const int centre = (c0 + c1) / 2;
      const int edge = up ? first_row(f, centre) : last_row(f, centre);
      if (edge < 0) continue;
      // The support may also start inside f, taking its first rows: between two thin slices the
      // fold onto the next one then lands inside it rather than beyond it, and neither is cut.
      const int inward = up ? 1 : -1;
      const int deepest = up ? last_row(f, centre) : first_row(f, centre);
      // Up to 2 W rows; with below_tips, a face that fills half the block only farther in (the tip
      // of a tapering facet) is held where it does, 2 W rows at most past there.
      const int height = (deepest - edge) * inward;
      auto fills = [&](int taken) {
        const int row = edge + taken * inward;
        return face_(centre, row) == f && mostly(f, c0, c1, row);
      };
      int first_taken = 0;
      while (below_tips_ && first_taken <= height && !fills(first_taken)) ++first_taken;
      if (!below_tips_ || first_taken <= 2 * block_) first_taken = 0;
      for (int taken = first_taken; taken <= first_taken + 2 * block_ && taken <= height; ++taken) {
        if (!fills(taken)) continue;
        const int row = edge + taken * inward;  // f's row just outside the support
        const double edge_Y = grid_.Y(row) + (up ? px_mm_ / 2 : -px_mm_ / 2);
        const double h = face.orientation == Orientation::V ? edge_Y + face.depth_mm : face.depth_mm;
        const double d = face.orientation == Orientation::V ? face.depth_mm : face.depth_mm - edge_Y;
        if (auto c = walk(f, column, row, up, h, d)) {
          c->taken = taken;
          c->cost += extra_cost;
          candidates.push_back(*c);
          if (c->cost < split_cost_) break;  // the first that cuts nothing: it takes least of f
        }
      }
    }
    return candidates;
  }

 private:
  // Where the raster plan has changed since the exact plan was built (supports painted, narrow parts
  // joined to a neighbour, boundaries aligned): the runs of each column's rows whose face lies in
  // another plane than the exact plan's there. Rays meet these, not what the plan held.
  struct Changed {
    int r0, r1;  // rows [r0, r1)
    std::int32_t face;
  };
  // Whether the plane at a pixel now (face f) differs from the exact plan's there (face was).
  bool changed(std::int32_t f, std::int32_t was) const {
    const int now = f < 0 ? -1 : plane_now_[static_cast<std::size_t>(f)];
    return now >= 0 && (was < 0 || plane_then_[static_cast<std::size_t>(was)] != now);
  }
  void note_change(int r, int c, std::int32_t f) {
    std::vector<Changed>& runs = changed_[static_cast<std::size_t>(c)];
    if (!runs.empty() && runs.back().r1 == r && runs.back().face == f)
      ++runs.back().r1;
    else
      runs.push_back({r, r + 1, f});
  }

  bool mostly(std::int32_t f, int c0, int c1, int r) const {
    int n = 0;
    for (int c = c0; c < c1; ++c) n += face_(c, r) == f;
    return 2 * n >= c1 - c0;
  }
  // Whether support s cuts face x in two: x lies on both sides of it, within its rows. A support
  // that only trims x's end leaves it one piece of paper.
  bool splits(std::int32_t x, const Candidate& s) const {
    bool left = false, right = false;
    for (int r = s.r0; r < s.r1; ++r) {
      left |= s.c0 > 0 && face_(s.c0 - 1, r) == x;
      right |= s.c1 < face_.cols && face_(s.c1, r) == x;
    }
    return left && right;
  }
  std::size_t at(std::int32_t f, int c) const {
    return static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)]) * face_.cols + c;
  }
  int first_row(std::int32_t f, int c) const { return first_[at(f, c)]; }
  int last_row(std::int32_t f, int c) const { return last_[at(f, c)]; }

  // A block column [c0, c1) row by row as the walks out of one face's edge see it, read once for
  // all of them (one per row the support may take of the face, each from its own start row).
  class BlockColumn {
   public:
    explicit BlockColumn(int rows) : known_(static_cast<std::size_t>(rows), 0), row_(static_cast<std::size_t>(rows)) {}
    void reset(int c0, int c1) {
      for (const int r : touched_) known_[static_cast<std::size_t>(r)] = 0;
      touched_.clear();
      faces_.clear();
      painted_.clear();
      c0_ = c0, c1_ = c1;
    }
    // What has changed since the exact plan along its ray, down the centre column: the runs of
    // rows in another plane, between their pixel edges, and over them the supports painted since,
    // between their exact fold lines.
    void paint(const CandidateFinder& finder, std::span<const Candidate> painted) {
      const int centre = (c0_ + c1_) / 2;
      const PixelGrid& grid = finder.grid_;
      const auto edge_Y = [&](int r) { return FoldLine{(grid.rows_above_fold - r) / grid.px_per_mm, 0}; };
      for (const Changed& run : finder.changed_[static_cast<std::size_t>(centre)]) {
        const RasterFace& face = finder.faces_[static_cast<std::size_t>(run.face)];
        painted_.push_back({face.orientation, face.depth_mm, edge_Y(run.r0), edge_Y(run.r1)});
      }
      for (const Candidate& s : painted)
        if (s.c0 <= centre && centre < s.c1) painted_.push_back({s.orientation, s.depth_mm, s.near, s.far});
    }
    std::span<const PaintedBand> painted() const { return painted_; }
    int c0() const { return c0_; }
    int c1() const { return c1_; }
    struct Row {
      std::int32_t centre;   // the face at the block column's centre
      bool mostly;           // which fills at least half of the row's block
      double Y;              // the row's plan Y
      std::size_t from, to;  // faces_[from, to): the faces along the row, a run of one face once
    };
    const Row& row(const CandidateFinder& finder, int r) {
      Row& row = row_[static_cast<std::size_t>(r)];
      if (known_[static_cast<std::size_t>(r)]) return row;
      known_[static_cast<std::size_t>(r)] = 1;
      touched_.push_back(r);
      row.centre = finder.face_((c0_ + c1_) / 2, r);
      row.mostly = row.centre >= 0 && finder.mostly(row.centre, c0_, c1_, r);
      row.Y = finder.grid_.Y(r);
      row.from = faces_.size();
      for (int c = c0_; c < c1_; ++c)
        if (const std::int32_t x = finder.face_(c, r); faces_.size() == row.from || faces_.back() != x)
          faces_.push_back(x);
      row.to = faces_.size();
      return row;
    }
    std::span<const std::int32_t> faces(const Row& row) const { return {faces_.data() + row.from, row.to - row.from}; }

   private:
    std::vector<std::uint8_t> known_;
    std::vector<Row> row_;
    std::vector<int> touched_;
    std::vector<std::int32_t> faces_;
    std::vector<PaintedBand> painted_;
    int c0_ = 0, c1_ = 0;
  };

  // The first face the support can fold onto, away from the edge: a V face at depth d' where
  // Y = h - d', or an H face at height h' where Y = h' - d, found on the exact plan and the supports
  // painted since. The ray is shot a quarter pixel right of the block column's centre (off the
  // lattice the plan's vertices lie on). The raster, which may have split, merged or renumbered
  // faces since, names the face there: one in the plane the ray met, filling half the block, as a
  // support's far side needs.
  std::optional<Candidate> walk(std::int32_t f, BlockColumn& column, int edge, bool up, double h, double d) const {
    const int step = up ? -1 : 1;
    const int centre = (column.c0() + column.c1()) / 2;
    const double from_Y = grid_.Y(edge) + (up ? px_mm_ / 2 : -px_mm_ / 2);
    // A fold up to half a pixel short of a face counts as on it: the pixel row the fold falls in may
    // hold the face where its exact boundary, simplified, passes, and the support painted there has
    // its end within half a pixel of the fold, which the next plan snaps onto it.
    for (const PlanBuild::Reached& reached :
         exact_.faces_reached({(centre + 0.75) * px_mm_, from_Y, up, h, d, column.painted(), px_mm_ / 2})) {
      // The row the fold falls in; on a row's edge, the row beyond, so that the support ends on the
      // fold, or else the row before, where the target may fill the block when it does not beyond.
      // A fold a rounding short of the edge counts as on it, as faces_reached took it.
      const double Y = reached.Y + (up ? kFoldLineTolerance_mm : -kFoldLineTolerance_mm);
      const double rows_down = grid_.rows_above_fold - Y * grid_.px_per_mm;
      const int beyond = up ? static_cast<int>(std::ceil(rows_down)) - 1 : static_cast<int>(std::floor(rows_down));
      const double into_row = up ? beyond + 1 - rows_down : rows_down - beyond;  // rows from its near edge
      const bool on_edge = into_row * px_mm_ <= 2 * kFoldLineTolerance_mm;
      for (const int r : {beyond, beyond - step}) {
        if (r != beyond && !on_edge) break;
        if (r < 0 || r >= face_.rows) continue;
        const BlockColumn::Row& row = column.row(*this, r);
        if (row.centre < 0 || !row.mostly) continue;
        const RasterFace& target = faces_[static_cast<std::size_t>(row.centre)];
        if (target.hole || target.orientation != reached.orientation || target.depth_mm != reached.depth_mm) continue;
        if ((r - step - (edge + step)) * step < 0) return std::nullopt;  // no room: the faces touch already
        std::vector<std::int32_t> crossed;
        for (int between = edge + step; between != r; between += step)
          for (const std::int32_t x : column.faces(column.row(*this, between)))
            if (x != f && (crossed.empty() || crossed.back() != x)) crossed.push_back(x);
        return candidate(f, row.centre, column, edge, r, up, h, d, std::move(crossed));
      }
      if (beyond < 0 || beyond >= face_.rows) break;
    }
    return std::nullopt;
  }

  // The support from f's row `edge` to g's row `r` (both outside it), with its cost: its length, and
  // the split cost for each face it cuts in two among those it crosses.
  Candidate candidate(std::int32_t f, std::int32_t g, const BlockColumn& column, int edge, int r, bool up, double h,
                      double d, std::vector<std::int32_t> crossed) const {
    const int step = up ? -1 : 1;
    const int near = edge + step, far = r - step;  // rows the support covers, near to far
    Candidate s;
    s.face = f, s.target = g, s.c0 = column.c0(), s.c1 = column.c1();
    s.r0 = std::min(near, far), s.r1 = std::max(near, far) + 1;
    s.face_row = edge, s.target_row = r;
    const RasterFace& target = faces_[static_cast<std::size_t>(g)];
    const bool onto_v = target.orientation == Orientation::V;
    s.orientation = onto_v ? Orientation::H : Orientation::V;
    s.depth_mm = onto_v ? h : d;
    s.near = {h, d};
    s.far = support_fold(target.orientation, target.depth_mm, h, d);
    s.cost = (s.r1 - s.r0) * px_mm_;
    std::ranges::sort(crossed);
    crossed.erase(std::unique(crossed.begin(), crossed.end()), crossed.end());
    for (const std::int32_t x : crossed)
      if (x != g && splits(x, s)) s.cost += split_cost_;
    return s;
  }

  const PlanBuild& exact_;
  std::span<const Candidate> painted_;
  const PixelGrid& grid_;
  const Grid<std::int32_t>& face_;
  const std::vector<RasterFace>& faces_;
  double split_cost_;
  bool below_tips_, corners_;
  double px_mm_;
  int block_;
  std::vector<int> slot_;                     // per face: its place in the tables below, -1 for faces not wanted
  std::vector<int> first_, last_;             // per wanted face and column: its first and last row, -1 if none
  std::vector<std::pair<int, int>> columns_;  // per wanted face: its first and last column
  std::vector<std::vector<Changed>> changed_;  // per column
  std::vector<int> plane_now_, plane_then_;    // per face of the raster plan and of the exact plan
};

bool claimed_anywhere(const Grid<std::uint8_t>& claimed, int c0, int c1, int r0, int r1) {
  for (int r = r0; r < r1; ++r)
    for (int c = c0; c < c1; ++c)
      if (claimed(c, r)) return true;
  return false;
}

// Seed §4.4, last part: a support grows a column at a time to either side while that column still
// joins the same two faces and covers no other face.
void widen(const Grid<std::int32_t>& face, const Grid<std::uint8_t>& claimed, Candidate& s) {
  auto column_fits = [&](int c) {
    if (c < 0 || c >= face.cols || face(c, s.face_row) != s.face || face(c, s.target_row) != s.target) return false;
    for (int r = s.r0; r < s.r1; ++r)
      if (claimed(c, r) || (face(c, r) != s.face && face(c, r) != s.target)) return false;
    return true;
  };
  while (column_fits(s.c0 - 1)) --s.c0;
  while (column_fits(s.c1)) ++s.c1;
}

}  // namespace

Standing standing_of(const Plan& plan) {
  Standing s{plan.validity, {}, {}};
  for (const PlanFace& face : plan.faces) {
    s.fold_on_top.push_back(face.fold_on_top);
    s.fold_on_bottom.push_back(face.fold_on_bottom);
  }
  return s;
}

std::vector<Candidate> choose_supports(const RasterMaps& maps, const SliceResult& slices, const PlanBuild& exact,
                                       std::span<const Candidate> painted, const Standing& standing,
                                       const std::vector<std::int32_t>& invalid, const SupportOptions& options,
                                       Reach reach) {
  const CandidateFinder finder(maps, slices, exact, painted, invalid, options.split_cost_mm, reach);
  Grid<std::uint8_t> claimed(slices.face.cols, slices.face.rows, 0);
  std::vector<Candidate> chosen;
  // Seed: an edge already folded to a face is not supported again; a floating face gets both. A
  // support chosen in this round joins the target's facing edge too, so that one is not supported
  // again from the other side.
  std::vector<std::uint8_t> top_joined = standing.fold_on_top, bottom_joined = standing.fold_on_bottom;
  // First the seed's rule: unjoined edges only. If that finds nothing, faces whose every edge is
  // folded but which hang from one plane only (a staircase standing on the floor, reaching
  // nowhere) are supported on the side of the missing plane: up towards the back plane when no
  // fold path reaches it, down towards the floor likewise.
  for (const bool by_missing_plane : {false, true}) {
    if (by_missing_plane && !chosen.empty()) break;
    auto wanted = [&](std::size_t i, bool up) {
      return by_missing_plane ? !(up ? standing.validity.in_X[i] : standing.validity.in_Y[i])
                              : !(up ? top_joined[i] : bottom_joined[i]);
    };
    // The candidates of every edge that wants them, found in parallel (the search only reads);
    // the greedy choice below stays in order, and skips edges an earlier choice joined.
    std::vector<std::vector<Candidate>> found(2 * invalid.size());
    tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t k) {
      const std::int32_t f = invalid[k / 2];
      const bool up = k % 2 == 0;
      if (!wanted(static_cast<std::size_t>(f), up)) return;
      found[k] = finder.from_edge(f, up);
      std::ranges::sort(found[k], [](const Candidate& a, const Candidate& b) {
        return std::tie(a.cost, a.taken, a.c0) < std::tie(b.cost, b.taken, b.c0);
      });
    });
    for (std::size_t k = 0; k < found.size(); ++k) {
      const std::int32_t f = invalid[k / 2];
      const auto i = static_cast<std::size_t>(f);
      const bool up = k % 2 == 0;
      if (!wanted(i, up)) continue;
      for (Candidate& s : found[k]) {
        if (!reach.split_faces && s.cost >= options.split_cost_mm) break;  // sorted: no cheaper one follows
        if (claimed_anywhere(claimed, s.c0, s.c1, s.r0, s.r1)) continue;
        widen(slices.face, claimed, s);
        for (int r = s.r0; r < s.r1; ++r)
          for (int c = s.c0; c < s.c1; ++c) claimed(c, r) = 1;
        chosen.push_back(s);
        (up ? top_joined[i] : bottom_joined[i]) = 1;
        (up ? bottom_joined[static_cast<std::size_t>(s.target)] : top_joined[static_cast<std::size_t>(s.target)]) = 1;
        break;
      }
    }
  }
  return chosen;
}

}  // namespace origamic
