// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/supports.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <random>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include <tbb/parallel_for.h>

namespace origamic {
namespace {

// A support: a W-wide (or wider) block of the raster plan between the face it holds and the face it
// reaches, turned into a face of its own.
struct Candidate {
  std::int32_t face = 0, target = 0;
  int c0 = 0, c1 = 0;      // pixel columns [c0, c1)
  int r0 = 0, r1 = 0;      // pixel rows [r0, r1) the support covers
  int face_row = 0;        // the row of `face` just outside the support
  int target_row = 0;      // the row of `target` just outside it, on the other side
  Orientation orientation = Orientation::V;
  double depth_mm = 0;
  double cost = 0;
  int taken = 0;           // rows of `face` the support takes, on its edge
};

bool needs_support(FaceStatus status, bool allow_dangling) {
  return status == FaceStatus::Floating || status == FaceStatus::Invalid ||
         (status == FaceStatus::Dangling && !allow_dangling);
}

class CandidateFinder {
 public:
  // Candidates will be asked of the faces in `wanted` only.
  CandidateFinder(const RasterMaps& maps, const SliceResult& slices, const std::vector<std::int32_t>& wanted, double split_cost)
      : grid_(maps.grid), face_(slices.face), faces_(slices.faces), split_cost_(split_cost),
        px_mm_(1 / maps.grid.px_per_mm), block_(slices.block_px), slot_(slices.faces.size(), -1) {
    for (const std::int32_t f : wanted)
      if (int& k = slot_[static_cast<std::size_t>(f)]; k < 0) k = static_cast<int>(columns_.size()), columns_.push_back({INT_MAX, -1});
    first_.assign(columns_.size() * static_cast<std::size_t>(face_.cols), -1);
    last_.assign(first_.size(), -1);
    for (int r = 0; r < face_.rows; ++r)
      for (int c = 0; c < face_.cols; ++c) {
        const std::int32_t f = face_(c, r);
        if (f < 0 || slot_[static_cast<std::size_t>(f)] < 0) continue;
        const auto slot = static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)]);
        const std::size_t k = slot * face_.cols + c;
        if (first_[k] < 0) first_[k] = r;
        last_[k] = r;
        auto& [lo, hi] = columns_[slot];
        lo = std::min(lo, c), hi = std::max(hi, c);
      }
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
    std::vector<int> starts;
    for (int c0 = std::max(0, lo) / block_ * block_; c0 <= hi && c0 + block_ <= face_.cols; c0 += block_) starts.push_back(c0);
    for (const int c0 : {lo, hi + 1 - block_})
      if (c0 >= 0 && c0 + block_ <= face_.cols && c0 % block_ != 0) starts.push_back(c0);
    for (const int c0 : starts) {
      const int c1 = c0 + block_;
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
      for (int taken = 0; taken <= 2 * block_ && (deepest - edge) * inward - taken >= 0; ++taken) {
        const int row = edge + taken * inward;  // f's row just outside the support
        if (face_(centre, row) != f || !mostly(f, c0, c1, row)) continue;
        const double edge_Y = grid_.Y(row) + (up ? px_mm_ / 2 : -px_mm_ / 2);
        const double h = face.orientation == Orientation::V ? edge_Y + face.depth_mm : face.depth_mm;
        const double d = face.orientation == Orientation::V ? face.depth_mm : face.depth_mm - edge_Y;
        if (auto c = walk(f, c0, c1, row, up, h, d)) {
          c->taken = taken;
          candidates.push_back(*c);
          if (c->cost < split_cost_) break;  // the first that cuts nothing: it takes least of f
        }
      }
    }
    return candidates;
  }

 private:
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
  std::size_t at(std::int32_t f, int c) const { return static_cast<std::size_t>(slot_[static_cast<std::size_t>(f)]) * face_.cols + c; }
  int first_row(std::int32_t f, int c) const { return first_[at(f, c)]; }
  int last_row(std::int32_t f, int c) const { return last_[at(f, c)]; }

  // Walks the block column away from the edge to the first face the support can fold onto: a V
  // face at depth d' on the row where Y = h - d', or an H face at height h' where Y = h' - d.
  std::optional<Candidate> walk(std::int32_t f, int c0, int c1, int edge, bool up, double h, double d) const {
    const int step = up ? -1 : 1;
    std::vector<std::int32_t> crossed;  // with repeats; a run of one face is one entry
    for (int r = edge + step; r >= 0 && r < face_.rows; r += step) {
      const std::int32_t g = face_((c0 + c1) / 2, r);
      if (g >= 0 && g != f && mostly(g, c0, c1, r)) {
        const RasterFace& target = faces_[static_cast<std::size_t>(g)];
        const double Y = grid_.Y(r);
        const bool beyond = up ? target.depth_mm < d : target.depth_mm > d;  // behind / in front
        const bool higher = up ? target.depth_mm > h : target.depth_mm < h;  // above / below
        const bool v_hit = target.orientation == Orientation::V && beyond && std::abs(h - target.depth_mm - Y) <= px_mm_ / 2;
        const bool h_hit = target.orientation == Orientation::H && higher && std::abs(target.depth_mm - d - Y) <= px_mm_ / 2;
        if (v_hit || h_hit) {
          const int near = edge + step, far = r - step;  // rows the support covers, near to far
          if ((far - near) * step < 0) return std::nullopt;  // no room: the faces touch already
          Candidate s;
          s.face = f, s.target = g, s.c0 = c0, s.c1 = c1;
          s.r0 = std::min(near, far), s.r1 = std::max(near, far) + 1;
          s.face_row = edge, s.target_row = r;
          s.orientation = v_hit ? Orientation::H : Orientation::V;
          s.depth_mm = v_hit ? h : d;
          s.cost = (s.r1 - s.r0) * px_mm_;
          std::ranges::sort(crossed);
          crossed.erase(std::unique(crossed.begin(), crossed.end()), crossed.end());
          for (const std::int32_t x : crossed)
            if (x != g && splits(x, s)) s.cost += split_cost_;
          return s;
        }
      }
      for (int c = c0; c < c1; ++c)
        if (const std::int32_t x = face_(c, r); x != f && (crossed.empty() || crossed.back() != x)) crossed.push_back(x);
    }
    return std::nullopt;
  }

  const PixelGrid& grid_;
  const Grid<std::int32_t>& face_;
  const std::vector<RasterFace>& faces_;
  double split_cost_, px_mm_;
  int block_;
  std::vector<int> slot_;  // per face: its place in the tables below, -1 for faces not wanted
  std::vector<int> first_, last_;  // per wanted face and column: its first and last row, -1 if none
  std::vector<std::pair<int, int>> columns_;  // per wanted face: its first and last column
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

std::vector<NarrowStrip> narrow_strips(const SliceResult& slices, const PixelGrid& grid) {
  const std::size_t n = slices.faces.size();
  std::vector<int> lo(n, INT_MAX), hi(n, -1), lo_row(n, 0);
  for (int r = 0; r < slices.face.rows; ++r)
    for (int c = 0; c < slices.face.cols; ++c) {
      const std::int32_t f = slices.face(c, r);
      if (f < 2) continue;
      const auto i = static_cast<std::size_t>(f);
      if (c < lo[i]) lo[i] = c, lo_row[i] = r;
      hi[i] = std::max(hi[i], c);
    }
  std::vector<NarrowStrip> narrow;
  for (std::size_t f = 2; f < n; ++f) {
    if (hi[f] < 0 || slices.faces[f].hole || hi[f] - lo[f] + 1 >= slices.block_px) continue;
    // Its place: its top pixel in its middle column, or its leftmost pixel if it has none there.
    int col = lo[f], row = lo_row[f];
    const int mid = (lo[f] + hi[f]) / 2;
    for (int r = 0; r < slices.face.rows; ++r)
      if (slices.face(mid, r) == static_cast<std::int32_t>(f)) {
        col = mid, row = r;
        break;
      }
    narrow.push_back({static_cast<std::int32_t>(f), slices.faces[f].support, (hi[f] - lo[f] + 1) / grid.px_per_mm,
                      {grid.X(col), grid.Y(row)}});
  }
  return narrow;
}

bool plan_stands(const Validity& validity, bool allow_dangling) {
  return validity.floating + validity.invalid == 0 && (allow_dangling || validity.dangling == 0);
}

namespace {

// What the loop needs to know of a plan: each face's status and which of its sides are folded.
struct Standing {
  Validity validity;
  std::vector<std::uint8_t> fold_on_top, fold_on_bottom;
};

Standing standing_of(const Plan& plan) {
  Standing s{plan.validity, {}, {}};
  for (const PlanFace& face : plan.faces) {
    s.fold_on_top.push_back(face.fold_on_top);
    s.fold_on_bottom.push_back(face.fold_on_bottom);
  }
  return s;
}

// The face graph read from the raster plan: a fold wherever a V(d) pixel and an H(h) pixel meet one
// above the other within `tolerance` of Y = h - d, as the exact plan snaps them (plan.hpp). Rebuilding
// the exact plan costs 50-700 ms; this costs a few, so rounds run on it and the exact plan only
// confirms (and overrides) its verdict.
Standing raster_standing(const PixelGrid& grid, const SliceResult& slices, double tolerance) {
  const Grid<std::int32_t>& face = slices.face;
  const std::size_t n = slices.faces.size();
  FaceGraph graph;
  graph.faces = static_cast<std::int32_t>(n);
  for (const RasterFace& f : slices.faces) graph.holes.push_back(f.hole);
  Standing s;
  s.fold_on_top.assign(n, 0);
  s.fold_on_bottom.assign(n, 0);
  std::map<double, std::int32_t> line_ids;
  std::set<std::tuple<std::int32_t, std::int32_t, std::int32_t>> seen;
  for (int r = 0; r + 1 < face.rows; ++r) {
    const double edge_Y = grid.Y(r) - 0.5 / grid.px_per_mm;  // between row r (above) and r + 1
    for (int c = 0; c < face.cols; ++c) {
      const std::int32_t upper = face(c, r), lower = face(c, r + 1);
      if (upper == lower || upper < 0 || lower < 0) continue;
      const RasterFace &fu = slices.faces[static_cast<std::size_t>(upper)], &fl = slices.faces[static_cast<std::size_t>(lower)];
      if (fu.orientation == fl.orientation || fu.hole || fl.hole) continue;
      const double fold_Y = fu.orientation == Orientation::H ? fu.depth_mm - fl.depth_mm : fl.depth_mm - fu.depth_mm;
      if (!(std::abs(edge_Y - fold_Y) <= tolerance)) continue;
      const auto line = line_ids.try_emplace(fold_Y, static_cast<std::int32_t>(line_ids.size())).first->second;
      s.fold_on_top[static_cast<std::size_t>(lower)] = 1;
      s.fold_on_bottom[static_cast<std::size_t>(upper)] = 1;
      if (seen.emplace(upper, lower, line).second) graph.folds.push_back({upper, lower, line});
    }
  }
  s.validity = validate(graph);
  return s;
}

std::vector<std::int32_t> unsupported(const Standing& standing, bool allow_dangling) {
  std::vector<std::int32_t> faces;
  for (std::size_t f = 2; f < standing.validity.status.size(); ++f)
    if (needs_support(standing.validity.status[f], allow_dangling)) faces.push_back(static_cast<std::int32_t>(f));
  return faces;
}

// One round of seed §4.4: supports for the given invalid faces, chosen greedily in their order,
// widened, never overlapping. Returns the chosen supports (not yet painted).
std::vector<Candidate> choose_supports(const RasterMaps& maps, const SliceResult& slices, const Standing& standing,
                                       const std::vector<std::int32_t>& invalid, const SupportOptions& options,
                                       bool allow_splits) {
  const CandidateFinder finder(maps, slices, invalid, options.split_cost_mm);
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
    // The candidates of every edge that wants them, found on both cores (the search only reads);
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
        if (!allow_splits && s.cost >= options.split_cost_mm) break;  // sorted: no cheaper one follows
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

// Paints the chosen supports as faces of their own. A support crossing a face can leave a strip of
// it beside the support, narrower than W and within the support's rows: a piece of paper too thin
// to hold, which becomes part of the support (a wider support, the same folds).
void paint_supports(const std::vector<Candidate>& chosen, const PixelGrid& grid, double tolerance, std::int64_t crumb_px,
                    SliceResult& slices) {
  Grid<std::int32_t>& face = slices.face;
  const auto first_support = static_cast<std::int32_t>(slices.faces.size());
  std::set<std::int32_t> crossed;
  for (const Candidate& s : chosen) {
    const auto id = static_cast<std::int32_t>(slices.faces.size());
    slices.faces.push_back({s.orientation, s.depth_mm, slices.faces[static_cast<std::size_t>(s.face)].segment, 0, true});
    for (int r = s.r0; r < s.r1; ++r)
      for (int c = s.c0; c < s.c1; ++c) crossed.insert(std::exchange(face(c, r), id));
    crossed.insert(s.face), crossed.insert(s.target);  // what is left of them may be a crumb
  }
  const std::vector<FacePart> parts =
      split_disconnected_faces(slices, std::vector<std::int32_t>(crossed.begin(), crossed.end()), crumb_px, 0);
  // The faces and parts a support crossed: their extent, and the support they touch (-1 none, -2
  // several).
  const std::size_t n = slices.faces.size();
  std::vector<std::uint8_t> candidate(n, 0);
  for (const std::int32_t f : crossed)
    if (f >= 2 && f < first_support) candidate[static_cast<std::size_t>(f)] = 1;
  for (const FacePart& p : parts) candidate[static_cast<std::size_t>(p.face)] = 1;
  std::vector<int> c_lo(n, INT_MAX), c_hi(n, -1), r_lo(n, INT_MAX), r_hi(n, -1);
  std::vector<std::int32_t> touches(n, -1);
  const auto supports_end = static_cast<std::int32_t>(first_support + chosen.size());
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c) {
      const std::int32_t f = face(c, r);
      if (f < 0 || !candidate[static_cast<std::size_t>(f)]) continue;
      const auto i = static_cast<std::size_t>(f);
      c_lo[i] = std::min(c_lo[i], c), c_hi[i] = std::max(c_hi[i], c);
      r_lo[i] = std::min(r_lo[i], r), r_hi[i] = std::max(r_hi[i], r);
      for (const auto& [dc, dr] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
        if (!face.contains(c + dc, r + dr)) continue;
        const std::int32_t g = face(c + dc, r + dr);
        if (g < first_support || g >= supports_end) continue;
        touches[i] = touches[i] == -1 || touches[i] == g ? g : -2;
      }
    }
  // A narrow one within the rows of the support it touches joins it; other parts go back to their
  // face: the exact plan decides whether they stand.
  std::vector<std::int32_t> into(n);
  std::iota(into.begin(), into.end(), 0);
  for (const FacePart& p : parts) into[static_cast<std::size_t>(p.face)] = p.from;
  for (std::size_t i = 0; i < n; ++i) {
    if (!candidate[i] || touches[i] < 0 || c_hi[i] - c_lo[i] + 1 >= slices.block_px) continue;
    const Candidate& s = chosen[static_cast<std::size_t>(touches[i] - first_support)];
    if (r_lo[i] >= s.r0 && r_hi[i] < s.r1) into[i] = touches[i];
  }
  for (auto& f : face.values)
    if (f >= 0) f = into[static_cast<std::size_t>(f)];
  merge_coplanar_faces(slices);
  align_folds_to_lines(slices, grid, tolerance);
}

}  // namespace

namespace {

constexpr int kSplitRetryRounds = 8;

// One greedy run of the support loop in the face order that `random` draws.
Supported supports_in_order(const RasterMaps& maps, SliceResult slices, const Sheet& sheet,
                            const PlanOptions& plan_options, const SupportOptions& options, std::mt19937& random,
                            bool last_order) {
  Supported result;
  SupportReport& report = result.report;
  report.round_bound = slices.face.cols / std::max(1, slices.block_px) + 1;
  const double tolerance = fold_snap_tolerance_mm(plan_options, slices, maps.grid);
  // A part of a face under W x W / 8 (a crumb left where a support or a slanted cut met it) joins a
  // neighbour rather than become a face to be supported.
  const std::int64_t crumb_px = std::int64_t{slices.block_px} * slices.block_px / 8;
  // The verdict of the raster graph, confirmed by the exact plan whenever the raster graph sees
  // nothing left to do: the exact plan always has the last word.
  bool exact = false;
  bool allow_splits = true;
  bool splits_retried = false;
  int split_rounds_left = 0;
  Standing standing;
  // Rounds run on the raster graph; the exact plan, built when they end, has the last word and
  // the next rounds start from its verdict.
  auto settle = [&] {
    standing = raster_standing(maps.grid, slices, aligned_fold_tolerance_mm(maps.grid));
    exact = false;
  };
  auto confirm = [&] {
    result.plan = build_plan(maps, slices, sheet, plan_options);
    ++report.exact_builds;
    standing = standing_of(result.plan);
    exact = true;
  };
  // Rounds of supports until every face stands or they stop helping; returns why they stopped.
  auto support_rounds = [&]() -> std::string {
    std::size_t fewest_invalid = SIZE_MAX;
    int rounds_without_progress = 0;
    for (;;) {
      std::vector<std::int32_t> invalid = unsupported(standing, options.allow_dangling);
      if (invalid.empty()) return {};
      // Supports that split other faces can leave as many invalid faces as they fixed: give up
      // when three rounds in a row made no progress.
      if (invalid.size() < fewest_invalid) fewest_invalid = invalid.size(), rounds_without_progress = 0;
      else if (++rounds_without_progress >= 3)
        return std::to_string(invalid.size()) + " faces still invalid: no progress in 3 rounds";
      if (report.rounds >= report.round_bound)
        return std::to_string(invalid.size()) + " faces still invalid after " + std::to_string(report.round_bound) +
               " rounds (the loop's bound)";
      ++report.rounds;
      std::shuffle(invalid.begin(), invalid.end(), random);
      const bool splits = allow_splits || split_rounds_left-- > 0;
      const std::vector<Candidate> chosen = choose_supports(maps, slices, standing, invalid, options, splits);
      if (chosen.empty()) return std::to_string(invalid.size()) + " faces invalid and no support reaches them";
      report.supports += static_cast<int>(chosen.size());
      paint_supports(chosen, maps.grid, tolerance, crumb_px, slices);
      settle();
    }
  };
  std::int64_t model_pixels = 0;
  for (std::size_t f = 2; f < slices.faces.size(); ++f) model_pixels += slices.faces[f].pixels;
  std::int64_t cut_out_pixels = 0;
  std::size_t fewest_exact = SIZE_MAX;
  settle();
  for (;;) {
    // A pass of rounds from an exact verdict that leaves at least as many faces invalid as it found
    // is undone: its supports held nothing, and the exact plan of the slices before it is at hand.
    std::optional<SliceResult> before;
    const std::size_t invalid_before = unsupported(standing, options.allow_dangling).size();
    if (exact) before = slices;
    const std::string why = support_rounds();
    if (before && !why.empty() && unsupported(standing, options.allow_dangling).size() >= invalid_before) {
      slices = std::move(*before);
      standing = standing_of(result.plan);
      exact = true;
      ++report.passes_undone;
    } else {
      confirm();
    }
    std::vector<std::int32_t> invalid = unsupported(standing, options.allow_dangling);
    const int loose = result.plan.loose_card_pieces;
    if (invalid.empty() && loose == 0) break;
    report.stop_reason = why.empty() ? std::to_string(invalid.size()) + " faces invalid in the exact plan" : why;
    if (loose > 0) report.stop_reason += "; " + std::to_string(loose) + " loose pieces of the back plane or the floor";
    std::vector<std::int32_t> apart = invalid;
    if (loose > 0) apart.insert(apart.end(), {kBackFace, kFloorFace});
    // The exact plan decides on pieces of paper: a face it finds invalid may be in pieces the raster
    // graph took for one. Those become faces of their own, and the rounds go on.
    // From then on no support may cut a face in two: the pieces it made would need supports of
    // their own, whose supports cut more faces, without end.
    if (report.rounds < report.round_bound && !split_disconnected_faces(slices, apart, crumb_px, slices.block_px).empty()) {
      allow_splits = false;
      merge_coplanar_faces(slices);
      settle();
      continue;
    }
    // The exact plan found fewer invalid faces than last time: another pass of rounds from its word.
    const bool progress = invalid.size() < fewest_exact;
    fewest_exact = std::min(fewest_exact, invalid.size());
    if (progress && report.rounds < report.round_bound) continue;
    if (invalid.empty()) break;  // only loose pieces the raster plan cannot tell apart
    // The last resort: the smaller half of the faces no support holds are cut out of the sheet
    // (holes, reported as "removed"). That can open the way for supports to the larger ones, so
    // the rounds resume. A card missing more than a quarter of its model is no likeness: then the
    // plan stays invalid, with the reason.
    if (!options.cut_out_unsupported) break;
    auto cut_out = [&](std::int32_t f) {
      slices.faces[static_cast<std::size_t>(f)].hole = true;
      ++report.cut_out;
    };
    // Pieces of the back plane or the floor that strips around them parted from it are card, not
    // model: a hole there takes nothing from the likeness, so they go first and free of the quota.
    const auto card_piece = [&](std::int32_t f) { return f > kFloorFace && slices.faces[static_cast<std::size_t>(f)].depth_mm == 0; };
    const auto model_faces = std::ranges::partition(invalid, card_piece);
    if (model_faces.begin() != invalid.begin()) {
      std::for_each(invalid.begin(), model_faces.begin(), cut_out);
    } else if (last_order && !splits_retried && report.rounds < report.round_bound) {
      // The last order, before any of the model is cut out: a few more rounds in which supports may
      // cut faces in two again, so that a face held only by reaching across others (a ring's top)
      // stands.
      splits_retried = true;
      split_rounds_left = kSplitRetryRounds;
      continue;
    } else {
      const auto pixels = [&](std::int32_t f) { return slices.faces[static_cast<std::size_t>(f)].pixels; };
      std::ranges::sort(invalid, [&](std::int32_t a, std::int32_t b) { return pixels(a) != pixels(b) ? pixels(a) < pixels(b) : a < b; });
      const std::int64_t limit = pixels(invalid[invalid.size() / 2]);
      std::int64_t more = 0;
      for (const std::int32_t f : invalid)
        if (pixels(f) <= limit) more += pixels(f);
      if (4 * (cut_out_pixels + more) > model_pixels) {
        report.stop_reason += "; cutting them out would remove over a quarter of the model";
        break;
      }
      cut_out_pixels += more;
      for (const std::int32_t f : invalid)
        if (pixels(f) <= limit) cut_out(f);
    }
    merge_coplanar_faces(slices);
    align_folds_to_lines(slices, maps.grid, tolerance);
    settle();
  }
  report.converged = report.cut_out == 0 && unsupported(standing, options.allow_dangling).empty() && result.plan.loose_card_pieces == 0;
  if (report.converged) report.stop_reason.clear();
  report.narrow = narrow_strips(slices, maps.grid);
  result.slices = std::move(slices);
  return result;
}

bool stands(const Supported& s, bool allow_dangling) {
  return plan_stands(s.plan.validity, allow_dangling) && s.plan.loose_card_pieces == 0;
}

// How far a plan is from standing: its faces no support holds, then the faces cut out.
std::pair<int, int> shortfall(const Supported& s, bool allow_dangling) {
  const Validity& v = s.plan.validity;
  return {v.floating + v.invalid + (allow_dangling ? 0 : v.dangling) + s.plan.loose_card_pieces, s.report.cut_out};
}

}  // namespace

Supported add_supports(const RasterMaps& maps, SliceResult slices, const Sheet& sheet, const PlanOptions& plan_options,
                       const SupportOptions& options) {
  // The greedy choice depends on the order the faces choose in, and one order can paint itself into
  // a corner that another avoids: the next orders of the same random sequence get their turn.
  std::mt19937 random(options.seed);
  std::optional<Supported> best;
  for (int order = 1; order <= std::max(1, options.orders); ++order) {
    const bool last = order >= options.orders;
    Supported run = supports_in_order(maps, last ? std::move(slices) : slices, sheet, plan_options, options, random, last);
    const bool done = stands(run, options.allow_dangling);
    const bool better = !best || shortfall(run, options.allow_dangling) < shortfall(*best, options.allow_dangling);
    if (done || better) best = std::move(run);
    best->report.orders = order;
    if (done) break;
  }
  return std::move(*best);
}

}  // namespace origamic
