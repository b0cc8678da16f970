// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/supports.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <random>
#include <set>
#include <optional>

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
};

bool needs_support(FaceStatus status, bool allow_dangling) {
  return status == FaceStatus::Floating || status == FaceStatus::Invalid ||
         (status == FaceStatus::Dangling && !allow_dangling);
}

class CandidateFinder {
 public:
  CandidateFinder(const RasterMaps& maps, const SliceResult& slices, double split_cost)
      : grid_(maps.grid), face_(slices.face), faces_(slices.faces), split_cost_(split_cost),
        px_mm_(1 / maps.grid.px_per_mm), block_(slices.block_px),
        first_(slices.faces.size() * static_cast<std::size_t>(face_.cols), -1),
        last_(first_.size(), -1) {
    for (int r = 0; r < face_.rows; ++r)
      for (int c = 0; c < face_.cols; ++c) {
        const std::int32_t f = face_(c, r);
        if (f < 0) continue;
        const std::size_t k = static_cast<std::size_t>(f) * face_.cols + c;
        if (first_[k] < 0) first_[k] = r;
        last_[k] = r;
      }
  }

  // Candidates from the top (up = true) or bottom edge of face f, one per W-wide block column that
  // f fills on that edge. (h, d) is the OA point of the edge: a support leaving it is H(h) reaching
  // back (or forward) to a V face, or V(d) reaching up (or down) to an H face.
  std::vector<Candidate> from_edge(std::int32_t f, bool up) const {
    std::vector<Candidate> candidates;
    const RasterFace& face = faces_[static_cast<std::size_t>(f)];
    for (int c0 = 0; c0 + block_ <= face_.cols; c0 += block_) {
      const int c1 = c0 + block_;
      // The edge row: f's top (bottom) at the block column's centre. A support needs f along at
      // least half of its near side and its target along half of its far side: slices of curved
      // surfaces cross a W-wide column at a slant, and the rest of either side is a cut.
      const int edge = up ? first_row(f, (c0 + c1) / 2) : last_row(f, (c0 + c1) / 2);
      if (edge < 0 || !mostly(f, c0, c1, edge)) continue;
      const double edge_Y = grid_.Y(edge) + (up ? px_mm_ / 2 : -px_mm_ / 2);
      const double h = face.orientation == Orientation::V ? edge_Y + face.depth_mm : face.depth_mm;
      const double d = face.orientation == Orientation::V ? face.depth_mm : face.depth_mm - edge_Y;
      if (auto c = walk(f, c0, c1, edge, up, h, d)) candidates.push_back(*c);
    }
    return candidates;
  }

 private:
  bool mostly(std::int32_t f, int c0, int c1, int r) const {
    int n = 0;
    for (int c = c0; c < c1; ++c) n += face_(c, r) == f;
    return 2 * n >= c1 - c0;
  }
  int first_row(std::int32_t f, int c) const { return first_[static_cast<std::size_t>(f) * face_.cols + c]; }
  int last_row(std::int32_t f, int c) const { return last_[static_cast<std::size_t>(f) * face_.cols + c]; }

  // Walks the block column away from the edge to the first face the support can fold onto: a V
  // face at depth d' on the row where Y = h - d', or an H face at height h' where Y = h' - d.
  std::optional<Candidate> walk(std::int32_t f, int c0, int c1, int edge, bool up, double h, double d) const {
    const int step = up ? -1 : 1;
    std::set<std::int32_t> crossed;
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
          for (const std::int32_t x : crossed)
            if (x != g) s.cost += split_cost_;
          return s;
        }
      }
      for (int c = c0; c < c1; ++c)
        if (const std::int32_t x = face_(c, r); x != f) crossed.insert(x);
    }
    return std::nullopt;
  }

  const PixelGrid& grid_;
  const Grid<std::int32_t>& face_;
  const std::vector<RasterFace>& faces_;
  double split_cost_, px_mm_;
  int block_;
  std::vector<int> first_, last_;  // per face and column: its first and last row, -1 if none
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

bool plan_stands(const Validity& validity, bool allow_dangling) {
  return validity.floating + validity.invalid == 0 && (allow_dangling || validity.dangling == 0);
}

Supported add_supports(const RasterMaps& maps, SliceResult slices, const Sheet& sheet, const PlanOptions& plan_options,
                       const SupportOptions& options) {
  Supported result;
  result.report.round_bound = slices.face.cols / std::max(1, slices.block_px) + 1;
  std::mt19937 random(options.seed);
  result.plan = build_plan(maps, slices, sheet, plan_options);
  std::size_t fewest_invalid = SIZE_MAX;
  int rounds_without_progress = 0;
  for (;;) {
    ++result.report.rounds;
    std::vector<std::int32_t> invalid;
    for (std::size_t f = 2; f < result.plan.faces.size(); ++f)
      if (needs_support(result.plan.faces[f].status, options.allow_dangling)) invalid.push_back(static_cast<std::int32_t>(f));
    if (invalid.empty()) {
      result.report.converged = true;
      break;
    }
    // Supports that split other faces can leave as many invalid faces as they fixed: give up when
    // three rounds in a row made no progress.
    if (invalid.size() < fewest_invalid) fewest_invalid = invalid.size(), rounds_without_progress = 0;
    else if (++rounds_without_progress >= 3) {
      result.report.stop_reason = std::to_string(invalid.size()) + " faces still invalid: no progress in 3 rounds";
      break;
    }
    if (result.report.rounds > result.report.round_bound) {
      result.report.stop_reason = std::to_string(invalid.size()) + " faces still invalid after " +
                                  std::to_string(result.report.round_bound) + " rounds (the loop's bound)";
      break;
    }
    std::shuffle(invalid.begin(), invalid.end(), random);

    const CandidateFinder finder(maps, slices, options.split_cost_mm);
    Grid<std::uint8_t> claimed(slices.face.cols, slices.face.rows, 0);
    std::vector<Candidate> chosen;
    // Seed: an edge already folded to a face is not supported again; a floating face gets both. A
    // support chosen in this round joins the target's facing edge too, so that one is not supported
    // again from the other side.
    std::vector<std::uint8_t> top_joined(result.plan.faces.size()), bottom_joined(result.plan.faces.size());
    for (std::size_t f = 0; f < result.plan.faces.size(); ++f) {
      top_joined[f] = result.plan.faces[f].fold_on_top;
      bottom_joined[f] = result.plan.faces[f].fold_on_bottom;
    }
    // First the seed's rule: unjoined edges only. If that finds nothing, faces whose every edge is
    // folded but which hang from one plane only (a staircase standing on the floor, reaching
    // nowhere) are supported on the side of the missing plane: up towards the back plane when no
    // fold path reaches it, down towards the floor likewise.
    for (const bool by_missing_plane : {false, true}) {
      if (by_missing_plane && !chosen.empty()) break;
      for (const std::int32_t f : invalid) {
        const auto i = static_cast<std::size_t>(f);
        for (const bool up : {true, false}) {
          const bool wanted = by_missing_plane ? !(up ? result.plan.validity.in_X[i] : result.plan.validity.in_Y[i])
                                               : !(up ? top_joined[i] : bottom_joined[i]);
          if (!wanted) continue;
          std::vector<Candidate> candidates = finder.from_edge(f, up);
          std::ranges::sort(candidates, [](const Candidate& a, const Candidate& b) {
            return a.cost != b.cost ? a.cost < b.cost : a.c0 < b.c0;
          });
          for (Candidate& s : candidates) {
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
    }
    if (chosen.empty()) {
      result.report.stop_reason = std::to_string(invalid.size()) + " faces invalid and no support reaches them";
      break;
    }
    for (const Candidate& s : chosen) {
      const auto id = static_cast<std::int32_t>(slices.faces.size());
      slices.faces.push_back({s.orientation, s.depth_mm, slices.faces[static_cast<std::size_t>(s.face)].segment, 0, true});
      for (int r = s.r0; r < s.r1; ++r)
        for (int c = s.c0; c < s.c1; ++c) slices.face(c, r) = id;
    }
    result.report.supports += static_cast<int>(chosen.size());
    merge_coplanar_faces(slices);
    result.plan = build_plan(maps, slices, sheet, plan_options);
  }
  result.slices = std::move(slices);
  return result;
}

}  // namespace origamic
