// SPDX-License-Identifier: GPL-3.0-or-later
// The face graph the support rounds run on, read from the raster plan's own folds (support_choice.hpp).
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "bands.hpp"
#include "origamic/supports.hpp"
#include "support_choice.hpp"

namespace origamic {

std::vector<FoldEdge> raster_folds(const PixelGrid& grid, const RasterPlan& raster_plan, double tolerance) {
  const Grid<std::int32_t>& face = raster_plan.face;
  std::array<std::vector<FoldEdge>, kBands> bands;
  for_bands(face.rows - 1, [&](int band, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      const double edge_Y = grid.Y(r) - 0.5 / grid.px_per_mm;  // between row r (above) and r + 1
      const std::int32_t* above = &face.values[face.index(0, r)];
      const std::int32_t* below = above + face.cols;
      for (int c = 0; c < face.cols; ++c) {
        const std::int32_t upper = above[c], lower = below[c];
        if (upper == lower || upper < 0 || lower < 0) continue;
        if (c > 0 && upper == above[c - 1] && lower == below[c - 1]) continue;  // the same pair, already seen
        const RasterFace &fu = raster_plan.faces[static_cast<std::size_t>(upper)],
                         &fl = raster_plan.faces[static_cast<std::size_t>(lower)];
        if (fu.orientation == fl.orientation || fu.hole || fl.hole) continue;
        const double fold_Y = fold_line_Y(fu.orientation, fu.depth_mm, fl.depth_mm);
        if (std::abs(edge_Y - fold_Y) <= tolerance)
          bands[static_cast<std::size_t>(band)].push_back({upper, lower, fold_Y});
      }
    }
  });
  std::vector<FoldEdge> folds;
  std::set<std::tuple<std::int32_t, std::int32_t, double>> seen;
  for (const std::vector<FoldEdge>& band : bands)
    for (const FoldEdge& f : band)
      if (seen.emplace(f.a, f.b, f.Y).second) folds.push_back(f);
  return folds;
}

FaceVerdicts raster_verdicts(const PixelGrid& grid, const RasterPlan& raster_plan, double tolerance) {
  const std::size_t n = raster_plan.faces.size();
  FaceGraph graph;
  graph.faces = static_cast<std::int32_t>(n);
  for (const RasterFace& f : raster_plan.faces) graph.holes.push_back(f.hole);
  FaceVerdicts s;
  s.fold_on_top.assign(n, 0);
  s.fold_on_bottom.assign(n, 0);
  std::map<double, std::int32_t> line_ids;
  for (const auto& [upper, lower, fold_Y] : raster_folds(grid, raster_plan, tolerance)) {
    const auto line = line_ids.try_emplace(fold_Y, static_cast<std::int32_t>(line_ids.size())).first->second;
    s.fold_on_top[static_cast<std::size_t>(lower)] = 1;
    s.fold_on_bottom[static_cast<std::size_t>(upper)] = 1;
    graph.folds.push_back({upper, lower, line});
  }
  s.validity = validity_of(graph);
  return s;
}

std::vector<std::int32_t> unsupported(const FaceVerdicts& standing, bool allow_dangling) {
  std::vector<std::int32_t> faces;
  for (std::size_t f = 2; f < standing.validity.status.size(); ++f)
    if (needs_support(standing.validity.status[f], allow_dangling)) faces.push_back(static_cast<std::int32_t>(f));
  return faces;
}

std::vector<std::int32_t> faces_unheld_on_raster(const PixelGrid& grid, const RasterPlan& raster_plan,
                                                 bool allow_dangling) {
  return unsupported(raster_verdicts(grid, raster_plan, aligned_fold_tolerance_mm(grid)), allow_dangling);
}

}  // namespace origamic
