// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_candidates.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <climits>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>

#include "bands.hpp"
#include "face_pieces.hpp"
#include "origamic/plan.hpp"
#include "plane_numbers.hpp"

namespace origamic {
namespace {

// The reachable faces a support may fold onto past the first, along its ray: a support that crosses
// a face to reach one behind it can cost the picture less than one to a face that stands not.
constexpr int kTargetsPerRay = 3;
// A support's cost per mm of length, beside the error it adds to the picture (in mm, as below):
// among supports the picture does not see (through the back plane, the floor, under an overhang)
// the shortest.
constexpr double kCostPerLength = 0.25;

// Where a support leaves the face it holds: the face, its row just outside the support, which way
// the support runs (up the plan or down), and the OA point (h, d) of the face's edge there.
struct SupportStart {
  std::int32_t face;
  int row;
  bool up;
  double h, d;
};

}  // namespace

// The search behind CandidateFinder: per face its runs and box, its pieces once asked for, per
// wanted face its edge rows, per column where the raster plan changed since the exact plan, read
// by many walks at once.
class CandidateFinder::Search {
  using Run = FacePieces::RowRun;
  // Whether face x is cut in two by the pixels [c0, c1) x [r0, r1), as found by one thread's walks:
  // the walks of many faces cross a face between the same columns and rows.
  struct SplitMemo {
    using Key = std::pair<std::uint64_t, std::uint64_t>;
    static Key key(std::int32_t x, int c0, int c1, int r0, int r1) {  // each under 2^21
      assert(c1 < (1 << 21) && r1 < (1 << 21));
      return {
          static_cast<std::uint64_t>(x) << 21 | static_cast<std::uint64_t>(c0),
          static_cast<std::uint64_t>(c1) << 42 | static_cast<std::uint64_t>(r0) << 21 | static_cast<std::uint64_t>(r1)};
    }
    struct Hash {
      std::size_t operator()(const Key& k) const {
        return std::hash<std::uint64_t>{}(k.first * 0x9E3779B97F4A7C15ULL ^ k.second);
      }
    };
    std::unordered_map<Key, bool, Hash> known;
  };

 public:
  // Candidates will be asked of the faces in `wanted` only.
  Search(const SupportRound& round, const std::vector<std::int32_t>& wanted, const SupportPicture& picture,
         SupportReach reach)
      : exact_plan_(round.exact_plan),
        picture_(picture),
        painted_(round.painted),
        grid_(round.maps.grid),
        face_(round.raster_plan.face),
        faces_(round.raster_plan.faces),
        W_(round.raster_plan.min_strip_mm),
        split_faces_(reach.split_faces),
        below_tips_(reach.below_tips),
        corners_(reach.corners),
        px_mm_(1 / round.maps.grid.px_per_mm),
        block_(round.raster_plan.block_px),
        slot_(round.raster_plan.faces.size(), -1) {
    for (const std::int32_t f : wanted)
      if (int& k = slot_[static_cast<std::size_t>(f)]; k < 0)
        k = static_cast<int>(columns_.size()), columns_.push_back({INT_MAX, -1});
    {
      PlaneNumbers plane;
      for (const RasterFace& f : faces_) plane_now_.push_back(plane(f));
      for (const RasterFace& f : exact_plan_.faces()) plane_then_.push_back(plane(f));
      changed_.resize(static_cast<std::size_t>(face_.cols));
    }
    first_.assign(columns_.size() * static_cast<std::size_t>(face_.cols), -1);
    last_.assign(first_.size(), -1);
    // Bands of columns in parallel: each writes its own columns, and its own extents to merge.
    std::array<std::vector<std::pair<int, int>>, kBands> band_columns;
    for_bands(face_.cols, [&](int band, int c_begin, int c_end) {
      std::vector<std::pair<int, int>>& columns = band_columns[static_cast<std::size_t>(band)];
      columns.assign(columns_.size(), {INT_MAX, -1});
      const Grid<std::int32_t>& then = exact_plan_.face_map();
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
    face_runs_.resize(faces_.size());
    for (int r = 0; r < face_.rows; ++r) {
      const std::int32_t* row = &face_.values[face_.index(0, r)];
      for (int c = 0; c < face_.cols;) {
        int end = c + 1;
        while (end < face_.cols && row[end] == row[c]) ++end;
        if (row[c] >= 0) face_runs_[static_cast<std::size_t>(row[c])].push_back({r, c, end});
        c = end;
      }
    }
    face_pieces_.resize(faces_.size());
    face_pieces_once_ = std::make_unique<std::once_flag[]>(faces_.size());
    face_box_.resize(faces_.size(), {INT_MAX, INT_MIN, INT_MAX, INT_MIN});
    for (std::size_t f = 2; f < faces_.size(); ++f) {
      PixelRect& box = face_box_[f];
      for (const Run& run : face_runs_[f])
        box = {std::min(box.c0, run.c0), std::max(box.c1, run.c1), std::min(box.r0, run.row),
               std::max(box.r1, run.row + 1)};
    }
  }

  // Whether support s, as it is now (widened), cuts face x in two.
  bool cuts(std::int32_t x, const Candidate& s) const { return splits(x, s); }

  // Whether support s leaves face x in more pieces with the supports `with` than they leave it.
  bool cuts_with(std::int32_t x, std::span<const PixelRect> with, const PixelRect& s) const {
    if (x == kBackFace || x == kFloorFace) return false;
    const auto i = static_cast<std::size_t>(x);
    const PixelRect& box = face_box_[i];
    if (!overlaps(s, box)) return false;
    std::vector<PixelRect> taken;
    for (const PixelRect& c : with)
      if (overlaps(c, box)) taken.push_back(c);
    if (taken.empty()) return false;  // s alone: its own `cuts`
    const int before = pieces_less(face_runs_[i], taken);
    taken.push_back(s);
    return pieces_less(face_runs_[i], taken) > before;
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
    // With SupportReach::corners, one more at each end, extended a strip width beyond the face.
    struct Start {
      int c0, c1;
      double extra_cost;
    };
    std::vector<Start> starts;
    const bool wide = hi + 1 - lo >= block_;  // a block fits between f's ends
    for (int c0 = std::max(0, lo) / block_ * block_; c0 <= hi && c0 + block_ <= face_.cols; c0 += block_)
      starts.push_back({c0, c0 + block_, 0});
    for (const int c0 : {lo, hi + 1 - block_})
      if (c0 >= 0 && c0 + block_ <= face_.cols && c0 % block_ != 0) starts.push_back({c0, c0 + block_, 0});
    const double corner_cost = block_ * px_mm_;
    if (corners_ && lo - block_ >= 0 && lo + block_ <= face_.cols)
      starts.push_back({lo - block_, lo + block_, corner_cost});
    if (corners_ && hi + 1 - block_ >= 0 && hi + 1 + block_ <= face_.cols)
      starts.push_back({hi + 1 - block_, hi + 1 + block_, corner_cost});
    BlockColumn column;
    SplitMemo& memo = memos_.local();
    for (const auto [c0, c1, extra_cost] : starts) {
      column.reset(*this, c0, c1);
      column.paint(*this, painted_);
      // The edge row: f's top (bottom) at the block column's centre. A support needs f along at
      // least half of its near side and its target along half of its far side: slices of curved
      // surfaces cross a W-wide column at a slant, and the rest of either side is a cut.
      const int centre = (c0 + c1) / 2;
      const int edge = up ? first_row(f, centre) : last_row(f, centre);
      if (edge < 0) continue;
      // A block column reaching past f's end over the back plane or the floor there (not over
      // another face of the model), less than a block of it over f (a corner's holds a block).
      bool past_end = wide && std::min(c1, hi + 1) - std::max(c0, lo) < block_;
      for (int c = c0; c < c1 && past_end; ++c)
        if (c < lo || c > hi) past_end = face_(c, edge) <= kFloorFace;  // the back plane, the floor, no face
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
        const SupportStart start{f, row, up,
                                 face.orientation == Orientation::V ? edge_Y + face.depth_mm : face.depth_mm,
                                 face.orientation == Orientation::V ? face.depth_mm : face.depth_mm - edge_Y};
        bool cuts_nothing = false;
        for (Candidate& c : walk(start, column, memo)) {
          c.taken = taken;
          c.cost += extra_cost;
          c.past_end = past_end;
          cuts_nothing |= c.cuts.empty();
          candidates.push_back(c);
        }
        if (cuts_nothing) break;  // the first that cuts nothing: it takes least of f
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
  // Whether support s cuts face x in two: what is left of x falls into more pieces than x is in. A
  // support that only trims x's end leaves it one piece of paper, and so does one across a ring,
  // which stays joined around the other side.
  // The back plane and the floor reach round everything on them: a W-wide support parts neither.
  bool splits(std::int32_t x, const Candidate& s, SplitMemo* memo = nullptr) const {
    if (x == kBackFace || x == kFloorFace) return false;
    const auto i = static_cast<std::size_t>(x);
    // The support's pixels outside x's bounding box take nothing of x: the walks of many edges cross
    // a face between the same columns at many lengths, and each thread looks at it once.
    const PixelRect& box = face_box_[i];
    const int c0 = std::max(s.c0, box.c0), c1 = std::min(s.c1, box.c1), r0 = std::max(s.r0, box.r0),
              r1 = std::min(s.r1, box.r1);
    if (c0 >= c1 || r0 >= r1) return false;
    const SplitMemo::Key key = SplitMemo::key(x, c0, c1, r0, r1);
    if (memo)
      if (const auto known = memo->known.find(key); known != memo->known.end()) return known->second;
    const FacePieces& pieces = pieces_of(i);
    const bool split = pieces.pieces_without(c0, c1, r0, r1) > pieces.pieces();
    if (memo) memo->known.emplace(key, split);
    return split;
  }
  // Face i's pieces, counted on first asking (most faces no walk cuts across).
  const FacePieces& pieces_of(std::size_t i) const {
    std::call_once(face_pieces_once_[i], [&] { face_pieces_[i].emplace(face_runs_[i]); });
    return *face_pieces_[i];
  }
  std::size_t at(std::int32_t f, int c) const {
    return static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)]) * face_.cols + c;
  }
  int first_row(std::int32_t f, int c) const { return first_[at(f, c)]; }
  int last_row(std::int32_t f, int c) const { return last_[at(f, c)]; }

  // A block column [c0, c1) row by row, each row read once per thread and round: the walks out of
  // many faces' edges cross the same columns.
  class ColumnRows {
   public:
    ColumnRows(int c0, int c1, int rows)
        : c0_(c0), c1_(c1), known_(static_cast<std::size_t>(rows), 0), row_(static_cast<std::size_t>(rows)) {}
    struct Row {
      std::int32_t centre;     // the face at the block column's centre
      bool mostly;             // which fills at least half of the row's block
      std::uint32_t from, to;  // faces_[from, to): the faces along the row, a run of one face once
    };
    const Row& row(const Search& finder, int r) {
      Row& row = row_[static_cast<std::size_t>(r)];
      if (known_[static_cast<std::size_t>(r)]) return row;
      known_[static_cast<std::size_t>(r)] = 1;
      row.centre = finder.face_((c0_ + c1_) / 2, r);
      row.mostly = row.centre >= 0 && finder.mostly(row.centre, c0_, c1_, r);
      row.from = static_cast<std::uint32_t>(faces_.size());
      for (int c = c0_; c < c1_; ++c)
        if (const std::int32_t x = finder.face_(c, r); faces_.size() == row.from || faces_.back() != x)
          faces_.push_back(x);
      row.to = static_cast<std::uint32_t>(faces_.size());
      return row;
    }
    std::span<const std::int32_t> faces(const Row& row) const { return {faces_.data() + row.from, row.to - row.from}; }

   private:
    int c0_, c1_;
    std::vector<std::uint8_t> known_;
    std::vector<Row> row_;
    std::vector<std::int32_t> faces_;
  };
  // Per thread, the block columns its walks have read, by first and end column.
  using ColumnCache = std::unordered_map<std::uint64_t, ColumnRows>;

  // A block column [c0, c1) as the walks out of one face's edge see it: its rows, and what has
  // changed along its ray.
  class BlockColumn {
   public:
    using Row = ColumnRows::Row;
    void reset(const Search& finder, int c0, int c1) {
      ColumnCache& cache = finder.column_rows_.local();
      const std::uint64_t key = static_cast<std::uint64_t>(c0) << 32 | static_cast<std::uint32_t>(c1);
      rows_ = &cache.try_emplace(key, c0, c1, finder.face_.rows).first->second;
      painted_.clear();
      c0_ = c0, c1_ = c1;
    }
    // What has changed since the exact plan along its ray, down the centre column: the runs of
    // rows in another plane, between their pixel edges, and over them the supports painted since,
    // between their exact fold lines.
    void paint(const Search& finder, std::span<const Candidate> painted) {
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
    const Row& row(const Search& finder, int r) { return rows_->row(finder, r); }
    std::span<const std::int32_t> faces(const Row& row) const { return rows_->faces(row); }

   private:
    ColumnRows* rows_ = nullptr;
    std::vector<PaintedBand> painted_;
    int c0_ = 0, c1_ = 0;
  };

  // The first faces the support can fold onto, away from the edge, nearest first, at most
  // kTargetsPerRay of them: a V face at depth d' where
  // Y = h - d', or an H face at height h' where Y = h' - d, found on the exact plan and the supports
  // painted since. The ray is shot a quarter pixel right of the block column's centre (off the
  // lattice the plan's vertices lie on). The raster, which may have split, merged or renumbered
  // faces since, names the face there: one in the plane the ray met, filling half the block, as a
  // support's far side needs.
  std::vector<Candidate> walk(const SupportStart& start, BlockColumn& column, SplitMemo& memo) const {
    const auto [f, edge, up, h, d] = start;
    std::vector<Candidate> found;
    const int step = up ? -1 : 1;
    const int centre = (column.c0() + column.c1()) / 2;
    const double from_Y = grid_.Y(edge) + (up ? px_mm_ / 2 : -px_mm_ / 2);
    // A fold up to half a pixel short of a face counts as on it: the pixel row the fold falls in may
    // hold the face where its exact boundary, simplified, passes, and the support painted there has
    // its end within half a pixel of the fold, which the next plan snaps onto it.
    for (const ExactPlan::Reached& reached :
         exact_plan_.faces_reached({(centre + 0.75) * px_mm_, from_Y, up, h, d, column.painted(), px_mm_ / 2})) {
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
        if ((r - step - (edge + step)) * step < 0) return found;  // no room: the faces touch already
        std::vector<std::int32_t> crossed;
        BlockColumn::Row before{};  // a row with the faces of the row before adds none
        for (int between = edge + step; between != r; between += step) {
          const BlockColumn::Row row_between = column.row(*this, between);
          if (between != edge + step && std::ranges::equal(column.faces(row_between), column.faces(before))) continue;
          for (const std::int32_t x : column.faces(row_between))
            if (std::ranges::find(crossed, x) == crossed.end())
              crossed.push_back(x);  // f too: taking its rows may cut it
          before = row_between;
        }
        found.push_back(candidate(start, {row.centre, r, std::move(crossed)}, column, memo));
        break;
      }
      if (static_cast<int>(found.size()) >= kTargetsPerRay || beyond < 0 || beyond >= face_.rows) break;
    }
    return found;
  }

  // Where a walk found a face to fold onto: the face, its row just beyond the support, and the
  // faces the support crosses on the way.
  struct Landing {
    std::int32_t target;
    int row;
    std::vector<std::int32_t> crossed;
  };

  // The support from its start to its landing (both rows outside it), with its cost: the error it
  // adds to the picture (SupportPicture, per W x W of plan: a support W wide and L long that shows
  // the model k W off costs k L), a little for its length; and the faces it cuts in two
  // among those it crosses. One candidates_of drops (it cuts f, or a third face where none may be
  // cut) has no cost and names only the first face it cuts.
  Candidate candidate(const SupportStart& start, Landing landing, const BlockColumn& column, SplitMemo& memo) const {
    const auto [f, edge, up, h, d] = start;
    const std::int32_t g = landing.target;
    const int r = landing.row;
    std::vector<std::int32_t>& crossed = landing.crossed;
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
    // A support that cuts the face it holds in two holds nothing (candidates_of drops it): the faces
    // it crosses are then not asked (on seedlike/sphere a third of the candidates), nor, where no
    // third face may be cut, those after the first it cuts; nor is the picture, which only a support
    // kept is priced by.
    const bool crosses_f = std::ranges::find(crossed, f) != crossed.end();
    if (f != g && crosses_f && splits(f, s, &memo)) {
      s.cuts.push_back(f);
      return s;
    }
    std::ranges::sort(crossed);  // each face once already
    for (const std::int32_t x : crossed)
      if (x != g && x != f && splits(x, s, &memo)) {
        s.cuts.push_back(x);
        if (!split_faces_) return s;
      }
    // Onto its target it always folds; from f only where it leaves f's plane.
    const int centre = (s.c0 + s.c1) / 2;
    const bool folds_from_f = f != g && faces_[static_cast<std::size_t>(f)].orientation != s.orientation;
    {
      const double beyond_target = thin_strip_beyond(centre, s.target_row, step, s.far.h - s.far.d, s.orientation);
      const double beyond_face = folds_from_f
                                     ? thin_strip_beyond(centre, s.face_row, -step, s.near.h - s.near.d, s.orientation)
                                     : std::numeric_limits<double>::infinity();
      s.thin_strip_mm = std::min(beyond_target, beyond_face);
    }
    const double length = (s.r1 - s.r0) * px_mm_;
    s.picture_mm = std::max(0.0, picture_.added_error(s.orientation, s.depth_mm, s.pixels())) / (W_ * W_);
    s.cost = kCostPerLength * length + s.picture_mm;
    return s;
  }

  // Whether the face at (col, row), running on `step` by `step`, folds onto a face in the support's
  // orientation `o` less than W from the support's fold at `fold_Y`: the strip between the two folds,
  // measured on their lines, is too thin to fold. Its width if so, else infinity.
  double thin_strip_beyond(int col, int row, int step, double fold_Y, Orientation o) const {
    const double none = std::numeric_limits<double>::infinity();
    if (row < 0 || row >= face_.rows || face_(col, row) < 0) return none;
    const std::int32_t g = face_(col, row);
    int r = row;
    // A strip under W spans at most W's rows and the two it may share with its folds.
    while (r >= 0 && r < face_.rows && face_(col, r) == g && (r - row) * step <= block_ + 1) r += step;
    if (r < 0 || r >= face_.rows) return none;
    const std::int32_t x = face_(col, r);
    if (x < 0 || x == g) return none;
    const RasterFace &here = faces_[static_cast<std::size_t>(g)], &next = faces_[static_cast<std::size_t>(x)];
    if (next.hole || next.orientation != o || here.orientation == o) return none;
    const double strip = std::abs(fold_line_Y(here.orientation, here.depth_mm, next.depth_mm) - fold_Y);
    return strip < W_ - kFoldLineTolerance_mm ? strip : none;
  }

  const ExactPlan& exact_plan_;
  const SupportPicture& picture_;
  std::span<const Candidate> painted_;
  const PixelGrid& grid_;
  const Grid<std::int32_t>& face_;
  const std::vector<RasterFace>& faces_;
  double W_;
  bool split_faces_, below_tips_, corners_;
  double px_mm_;
  int block_;
  std::vector<int> slot_;                      // per face: its place in the tables below, -1 for faces not wanted
  std::vector<int> first_, last_;              // per wanted face and column: its first and last row, -1 if none
  std::vector<std::pair<int, int>> columns_;   // per wanted face: its first and last column
  std::vector<std::vector<Changed>> changed_;  // per column
  std::vector<std::vector<Run>> face_runs_;    // per face, its runs of pixels in row-major order
  mutable std::vector<std::optional<FacePieces>> face_pieces_;  // per face, its pieces once asked for
  std::unique_ptr<std::once_flag[]> face_pieces_once_;
  mutable tbb::enumerable_thread_specific<SplitMemo> memos_;
  mutable tbb::enumerable_thread_specific<ColumnCache> column_rows_;
  std::vector<PixelRect> face_box_;          // per face, its bounding box
  std::vector<int> plane_now_, plane_then_;  // per face of the raster plan and of the exact plan
};

CandidateFinder::CandidateFinder(const SupportRound& round, const std::vector<std::int32_t>& wanted,
                                 const SupportPicture& picture, SupportReach reach)
    : search_(std::make_unique<const Search>(round, wanted, picture, reach)) {}
CandidateFinder::~CandidateFinder() = default;

bool CandidateFinder::cuts(std::int32_t x, const Candidate& s) const { return search_->cuts(x, s); }

bool CandidateFinder::cuts_with(std::int32_t x, std::span<const PixelRect> with, const PixelRect& s) const {
  return search_->cuts_with(x, with, s);
}

std::vector<Candidate> CandidateFinder::from_edge(std::int32_t f, bool up) const { return search_->from_edge(f, up); }

// The candidates of both edges of the faces, found in parallel (each thread with its own caches),
// then taken in order; a support that cuts the face it holds, or the one it reaches, in two holds
// nothing.
std::vector<Candidate> candidates_of(const CandidateFinder& finder, const std::vector<std::int32_t>& faces,
                                     bool split_faces) {
  std::vector<std::vector<Candidate>> found(2 * faces.size());
  tbb::parallel_for(std::size_t{0}, found.size(),
                    [&](std::size_t k) { found[k] = finder.from_edge(faces[k / 2], k % 2 == 0); });
  std::vector<Candidate> candidates;
  for (std::vector<Candidate>& edge : found)
    for (Candidate& c : edge) {
      const auto cuts = [&](std::int32_t x) { return std::ranges::find(c.cuts, x) != c.cuts.end(); };
      if (!cuts(c.face) && !cuts(c.target) && (split_faces || c.cuts.empty())) candidates.push_back(std::move(c));
    }
  return candidates;
}

std::vector<Candidate> support_candidates(const SupportRound& round, const std::vector<std::int32_t>& faces,
                                          SupportReach reach) {
  const SupportPicture picture(round.maps, round.raster_plan);
  return candidates_of(CandidateFinder(round, faces, picture, reach), faces, reach.split_faces);
}

}  // namespace origamic
