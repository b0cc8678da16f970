// SPDX-License-Identifier: GPL-3.0-or-later
// The end of a round of supports (support_choice.hpp): the chosen supports painted into the raster
// plan as faces of their own, and what they leave of the faces they cross settled.
#include <algorithm>
#include <array>
#include <climits>
#include <numeric>
#include <set>
#include <utility>

#include "bands.hpp"
#include "raster_plan_edits.hpp"
#include "support_choice.hpp"

namespace origamic {

// Paints the chosen supports as faces of their own. A support crossing a face can leave a strip of
// it beside the support, narrower than W and within the support's rows: a piece of paper too thin
// to hold, which becomes part of the support (a wider support, the same folds).
RasterPlan paint_supports(RasterPlan raster_plan, const std::vector<Candidate>& chosen, const PixelGrid& grid,
                          double tolerance, std::int64_t crumb_px) {
  const auto first_support = static_cast<std::int32_t>(raster_plan.faces.size());
  std::set<std::int32_t> crossed;
  for (const Candidate& s : chosen) {
    const auto id = static_cast<std::int32_t>(raster_plan.faces.size());
    raster_plan.faces.push_back(
        {s.orientation, s.depth_mm, raster_plan.faces[static_cast<std::size_t>(s.face)].segment, 0, true});
    for (int r = s.r0; r < s.r1; ++r)
      for (int c = s.c0; c < s.c1; ++c) crossed.insert(std::exchange(raster_plan.face(c, r), id));
    crossed.insert(s.face), crossed.insert(s.target);  // what is left of them may be a crumb
  }
  SplitFaces split = split_disconnected_faces(std::move(raster_plan),
                                              std::vector<std::int32_t>(crossed.begin(), crossed.end()), crumb_px, 0);
  raster_plan = std::move(split.raster_plan);
  const std::vector<FacePart>& parts = split.parts;
  Grid<std::int32_t>& face = raster_plan.face;
  // The faces and parts a support crossed: their extent, and the support they touch (-1 none, -2
  // several).
  const std::size_t n = raster_plan.faces.size();
  std::vector<std::uint8_t> candidate(n, 0);
  for (const std::int32_t f : crossed)
    if (f >= 2 && f < first_support) candidate[static_cast<std::size_t>(f)] = 1;
  for (const FacePart& p : parts) candidate[static_cast<std::size_t>(p.face)] = 1;
  struct Extent {
    std::vector<int> c_lo, c_hi, r_lo, r_hi;
    std::vector<std::int32_t> touches;
  };
  const auto supports_end = static_cast<std::int32_t>(first_support + chosen.size());
  const auto touch = [](std::int32_t a, std::int32_t b) { return a == -1 || a == b ? b : b == -1 ? a : -2; };
  std::array<Extent, kBands> bands;
  for_bands(face.rows, [&](int band, int row_begin, int row_end) {
    auto& [c_lo, c_hi, r_lo, r_hi, touches] = bands[static_cast<std::size_t>(band)];
    c_lo.assign(n, INT_MAX), c_hi.assign(n, -1), r_lo.assign(n, INT_MAX), r_hi.assign(n, -1), touches.assign(n, -1);
    for (int r = row_begin; r < row_end; ++r)
      for (int c = 0; c < face.cols; ++c) {
        const std::int32_t f = face(c, r);
        if (f < 0 || !candidate[static_cast<std::size_t>(f)]) continue;
        const auto i = static_cast<std::size_t>(f);
        c_lo[i] = std::min(c_lo[i], c), c_hi[i] = std::max(c_hi[i], c);
        r_lo[i] = std::min(r_lo[i], r), r_hi[i] = std::max(r_hi[i], r);
        for (const auto& [dc, dr] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
          if (!face.contains(c + dc, r + dr)) continue;
          const std::int32_t g = face(c + dc, r + dr);
          if (g >= first_support && g < supports_end) touches[i] = touch(touches[i], g);
        }
      }
  });
  auto [c_lo, c_hi, r_lo, r_hi, touches] = std::move(bands[0]);
  for (std::size_t band = 1; band < kBands; ++band)
    for (std::size_t i = 0; i < n; ++i) {
      const Extent& e = bands[band];
      c_lo[i] = std::min(c_lo[i], e.c_lo[i]), c_hi[i] = std::max(c_hi[i], e.c_hi[i]);
      r_lo[i] = std::min(r_lo[i], e.r_lo[i]), r_hi[i] = std::max(r_hi[i], e.r_hi[i]);
      touches[i] = touch(touches[i], e.touches[i]);
    }
  // A narrow one within the rows of the support it touches joins it; other parts go back to their
  // face: the exact plan decides whether they stand.
  std::vector<std::int32_t> into(n);
  std::iota(into.begin(), into.end(), 0);
  for (const FacePart& p : parts) into[static_cast<std::size_t>(p.face)] = p.from;
  for (std::size_t i = 0; i < n; ++i) {
    if (!candidate[i] || touches[i] < 0 || c_hi[i] - c_lo[i] + 1 >= raster_plan.block_px) continue;
    const Candidate& s = chosen[static_cast<std::size_t>(touches[i] - first_support)];
    if (r_lo[i] >= s.r0 && r_hi[i] < s.r1) into[i] = touches[i];
  }
  for_bands(face.rows, [&](int, int row_begin, int row_end) {
    const std::size_t cols = static_cast<std::size_t>(face.cols);
    for (std::size_t i = row_begin * cols; i < row_end * cols; ++i)
      if (std::int32_t& f = face.values[i]; f >= 0) f = into[static_cast<std::size_t>(f)];
  });
  raster_plan = merge_coplanar_faces(std::move(raster_plan));
  raster_plan = align_folds_to_lines(std::move(raster_plan), grid, tolerance);
  return split_into_pieces(std::move(raster_plan), crumb_px);
}

RasterPlan split_into_pieces(RasterPlan raster_plan, std::int64_t crumb_px) {
  std::vector<std::int32_t> all(raster_plan.faces.size());
  std::iota(all.begin(), all.end(), 0);
  SplitFaces split = split_disconnected_faces(std::move(raster_plan), all, crumb_px, 0);
  if (split.parts.empty()) return std::move(split.raster_plan);
  return merge_coplanar_faces(std::move(split.raster_plan));
}

}  // namespace origamic
