// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/segment.hpp"

#include <cmath>
#include <numbers>
#include <type_traits>

#include <glm/geometric.hpp>

namespace origamic {
namespace {

constexpr int kStep[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

// Quadratic extrapolation through values at distances 1, 2, 3 (fewer when the segment has fewer
// in-line pixels: linear through two, constant through one).
template <class T>
T extrapolate(const T* v, int n) {
  using Scalar = std::conditional_t<std::is_same_v<T, double>, double, float>;
  if (n >= 3) return Scalar(3) * v[0] - Scalar(3) * v[1] + v[2];
  if (n == 2) return Scalar(2) * v[0] - v[1];
  return v[0];
}

}  // namespace

Segmentation segment(const RasterMaps& maps, const SegmentOptions& options) {
  const int cols = maps.grid.cols, rows = maps.grid.rows;
  Segmentation result;
  result.segment = Grid<std::int32_t>(cols, rows, kNoSegment);
  result.pixels = {0, 0};
  Grid<std::int32_t>& S = result.segment;
  for (std::size_t i = 0; i < S.size(); ++i) {
    const HitKind kind = maps.kind.values[i];
    if (kind == HitKind::Back) S.values[i] = kBackSegment, ++result.pixels[0];
    if (kind == HitKind::Floor) S.values[i] = kFloorSegment, ++result.pixels[1];
  }

  const float cos_tol = static_cast<float>(std::cos(options.normal_tol_deg * std::numbers::pi / 180));
  // The 45-degree depth in mm along the view (h + d) varies smoothly on a smooth surface.
  auto depth = [&](int col, int row) { return maps.h_mm(col, row) + maps.d_mm(col, row); };
  std::vector<std::pair<int, int>> queue;
  for (int row0 = 0; row0 < rows; ++row0)
    for (int col0 = 0; col0 < cols; ++col0) {
      if (maps.kind(col0, row0) != HitKind::Model || S(col0, row0) != kNoSegment) continue;
      const std::int32_t id = result.count++;
      std::int64_t size = 0;
      queue.assign(1, {col0, row0});
      S(col0, row0) = id;
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const auto [col, row] = queue[head];
        ++size;
        for (const auto& step : kStep) {
          const int c = col + step[0], r = row + step[1];
          if (!S.contains(c, r) || S(c, r) != kNoSegment || maps.kind(c, r) != HitKind::Model) continue;
          // The in-line neighbours behind (col, row), seen from (c, r), that are in the segment.
          double depths[3] = {};
          glm::vec3 normals[3] = {};
          int n = 0;
          for (int k = 1; k <= 3; ++k) {
            const int cc = c - k * step[0], rr = r - k * step[1];
            if (!S.contains(cc, rr) || S(cc, rr) != id) break;
            depths[n] = depth(cc, rr);
            normals[n] = maps.normal(cc, rr);
            ++n;
          }
          double predicted_depth = extrapolate(depths, n);
          if (n == 1) {
            // One in-line neighbour gives no slope: take it from that pixel's tangent plane, on which
            // a plan step (dX, dY) moves the depth d by -(n_x dX + n_h dY) / (n_h + n_d).
            const glm::vec3& m = normals[0];
            const double dX = step[0] / maps.grid.px_per_mm, dY = -step[1] / maps.grid.px_per_mm;
            const double dd = m.y + m.z > 0.05f ? -(m.x * dX + m.y * dY) / (m.y + m.z) : 0.0;
            predicted_depth += dY + 2 * dd;
          }
          const glm::vec3 predicted_normal = extrapolate(normals, n);
          const float length = glm::length(predicted_normal);
          const double step_mm = n >= 2 ? std::abs(depths[0] - depths[1]) : 0.0;
          if (std::abs(predicted_depth - depth(c, r)) > options.depth_tol_mm + options.depth_tol_of_step * step_mm)
            continue;
          if (!(length > 0) || glm::dot(predicted_normal, maps.normal(c, r)) < cos_tol * length) continue;
          S(c, r) = id;
          queue.emplace_back(c, r);
        }
      }
      result.pixels.push_back(size);
    }
  return result;
}

}  // namespace origamic
