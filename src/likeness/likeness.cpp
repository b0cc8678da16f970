// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/likeness.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>
#include <vector>

#include "disc_width.hpp"

namespace origamic {
namespace {

CardSurface surface_of(Orientation orientation, double depth_mm, bool support) {
  if (depth_mm == 0) return orientation == Orientation::V ? CardSurface::Back : CardSurface::Floor;
  return support ? CardSurface::Support : CardSurface::Model;
}

CardView empty_view(const PixelGrid& grid) {
  return {Grid<double>(grid.cols, grid.rows, 0.0), Grid<CardSurface>(grid.cols, grid.rows, CardSurface::Outside)};
}

}  // namespace

CardView card_view(const PixelGrid& grid, const Grid<std::int32_t>& face, const std::vector<RasterFace>& faces) {
  CardView card = empty_view(grid);
  tbb::parallel_for(0, grid.rows, [&](int row) {
    const double Y = grid.Y(row);
    for (int col = 0; col < grid.cols; ++col) {
      const std::int32_t f = face(col, row);
      if (f < 0) continue;
      const RasterFace& rf = faces[static_cast<std::size_t>(f)];
      const CardSurface surface = rf.hole ? CardSurface::Hole : surface_of(rf.orientation, rf.depth_mm, rf.support);
      card.surface(col, row) = surface;
      card.key_mm(col, row) = shown_key(rf.orientation, rf.depth_mm, rf.hole, Y);
    }
  });
  return card;
}

namespace {

// Calls fill(row, first, end) for each run of pixels [first, end) of a row whose centres lie in the
// region's rings (even-odd, edges half-open): the rings' crossings with the rows of pixel centres,
// taken in pairs.
template <typename Fill>
void for_each_run(const PixelGrid& grid, const PlanRegion& region, Fill fill) {
  const double px = grid.px_per_mm;
  std::vector<std::pair<int, double>> crossings;  // (row, X)
  for (const std::vector<PlanPoint>& ring : region.rings)
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const PlanPoint &a = ring[k], &b = ring[(k + 1) % ring.size()];
      if (a.Y == b.Y) continue;
      const auto [lo, hi] = std::minmax(a.Y, b.Y);
      // Rows whose centre Y lies in [lo, hi): row r has centre (rows_above_fold - r - 0.5) / px.
      const int first = std::max(0, static_cast<int>(std::floor(grid.rows_above_fold - hi * px - 0.5)));
      const int last = std::min(grid.rows - 1, static_cast<int>(std::ceil(grid.rows_above_fold - lo * px - 0.5)));
      for (int row = first; row <= last; ++row) {
        const double Y = grid.Y(row);
        if (Y < lo || Y >= hi) continue;
        crossings.emplace_back(row, a.X + (Y - a.Y) * (b.X - a.X) / (b.Y - a.Y));
      }
    }
  std::ranges::sort(crossings);
  for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
    const auto [row, x0] = crossings[k];
    const double x1 = crossings[k + 1].second;
    assert(crossings[k + 1].first == row);
    // Centres X = (col + 0.5) / px in [x0, x1).
    const int c0 = std::max(0, static_cast<int>(std::ceil(x0 * px - 0.5)));
    const int c1 = std::min(grid.cols, static_cast<int>(std::ceil(x1 * px - 0.5)));
    if (c0 < c1) fill(row, c0, c1);
  }
}

}  // namespace

CardView card_view(const PixelGrid& grid, std::span<const PlanRegion> regions, const std::vector<bool>& support) {
  CardView card = empty_view(grid);
  tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t i) {
    const PlanRegion& region = regions[i];
    const bool hole = !region.placed || region.status == FaceStatus::Removed;
    const bool is_support =
        region.face >= 0 && static_cast<std::size_t>(region.face) < support.size() && support[region.face];
    const CardSurface surface = hole ? CardSurface::Hole : surface_of(region.orientation, region.depth_mm, is_support);
    for_each_run(grid, region, [&](int row, int c0, int c1) {
      const double key = shown_key(region.orientation, region.depth_mm, hole, grid.Y(row));
      for (int col = c0; col < c1; ++col) {
        card.surface(col, row) = surface;
        card.key_mm(col, row) = key;
      }
    });
  });
  return card;
}

std::vector<double> widest_discs_px(const PixelGrid& grid, std::span<const PlanRegion> regions) {
  std::vector<double> widths(regions.size());
  tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t i) {
    std::vector<std::pair<int, int>> pixels;
    for_each_run(grid, regions[i], [&](int row, int c0, int c1) {
      for (int col = c0; col < c1; ++col) pixels.emplace_back(col, row);
    });
    widths[i] = widest_disc_px(pixels);
  });
  return widths;
}

CardView card_view(const PixelGrid& grid, const Plan& plan) {
  std::vector<bool> support;
  for (const PlanFace& face : plan.faces) support.push_back(face.support);
  return card_view(grid, plan.regions, support);
}

namespace {

Grid<double> error_map(const RasterMaps& maps, const CardView& card) {
  Grid<double> error(maps.grid.cols, maps.grid.rows, -1.0);
  tbb::parallel_for(0, maps.grid.rows, [&](int row) {
    for (int col = 0; col < maps.grid.cols; ++col) {
      if (maps.kind(col, row) != HitKind::Model) continue;
      const double model_key = maps.h_mm(col, row) + maps.d_mm(col, row);
      const double card_key = card.surface(col, row) == CardSurface::Outside
                                  ? shown_key(Orientation::V, 0, true, maps.grid.Y(row))
                                  : card.key_mm(col, row);
      error(col, row) = std::abs(card_key - model_key);
    }
  });
  return error;
}

}  // namespace

Grid<float> likeness_error_map(const RasterMaps& maps, const CardView& card) {
  const Grid<double> error = error_map(maps, card);
  Grid<float> out(error.cols, error.rows);
  for (std::size_t i = 0; i < error.size(); ++i) out.values[i] = static_cast<float>(error.values[i]);
  return out;
}

Likeness likeness(const RasterMaps& maps, const CardView& card, double W) {
  assert(W > 0);
  const Grid<double> error = error_map(maps, card);
  std::vector<double> errors;
  errors.reserve(maps.model_pixels);
  std::int64_t shown = 0, supports = 0, holes = 0;
  for (std::size_t i = 0; i < error.size(); ++i) {
    if (error.values[i] < 0) continue;
    errors.push_back(error.values[i]);
    const CardSurface s = card.surface.values[i];
    shown += s == CardSurface::Model || s == CardSurface::Support;
    supports += s == CardSurface::Support;
    holes += s == CardSurface::Hole || s == CardSurface::Outside;
  }
  Likeness l;
  l.model_pixels = static_cast<std::int64_t>(errors.size());
  if (errors.empty()) return l;
  double sum = 0;
  for (const double e : errors) sum += e;
  const auto n = static_cast<double>(errors.size());
  l.mean_mm = sum / n;
  const auto p95 = errors.begin() + static_cast<std::ptrdiff_t>(0.95 * (n - 1));
  std::nth_element(errors.begin(), p95, errors.end());
  l.p95_mm = *p95;
  l.mean_W = l.mean_mm / W;
  l.p95_W = l.p95_mm / W;
  l.coverage = static_cast<double>(shown) / n;
  l.support_share = static_cast<double>(supports) / n;
  l.cut_out_share = static_cast<double>(holes) / n;
  return l;
}

}  // namespace origamic
