// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_mirror.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "bands.hpp"

namespace origamic {
namespace {

// A grid with its columns in reverse order.
template <class T>
Grid<T> columns_reversed(Grid<T> grid) {
  for (int r = 0; r < grid.rows; ++r) {
    const auto row = grid.values.begin() + static_cast<std::ptrdiff_t>(grid.index(0, r));
    std::reverse(row, row + grid.cols);
  }
  return grid;
}

// A copy of a grid with its columns in reverse order, written once (bands of rows in parallel), not
// copied and then reversed.
template <class T>
Grid<T> mirrored_copy(const Grid<T>& grid) {
  Grid<T> out = Grid<T>::unfilled(grid.cols, grid.rows);
  for_bands(grid.rows, [&](int, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      const T* from = &grid.values[grid.index(0, r)];
      T* to = &out.values[out.index(0, r)] + grid.cols;
      for (int c = 0; c < grid.cols; ++c) *--to = from[c];
    }
  });
  return out;
}

// What a pixel of the raster plan is, whatever the ids: the kind of paper there, its plane, whether
// a face begins there (another is above it) and whether it runs on towards the model's middle
// (`inward` columns over).
using PixelKind = std::tuple<int, double, bool, bool>;
PixelKind pixel_kind(const RasterPlan& plan, int c, int r, int inward) {
  const std::int32_t f = plan.face(c, r);
  if (f < 0) return {0, 0.0, false, false};
  const RasterFace& face = plan.faces[static_cast<std::size_t>(f)];
  const int kind = f == kBackFace                       ? 1
                   : f == kFloorFace                    ? 2
                   : face.hole                          ? 3
                   : face.orientation == Orientation::V ? 4
                                                        : 5;
  return {kind, face.depth_mm, r == 0 || plan.face(c, r - 1) != f, plan.face(c + inward, r) == f};
}

PlanPoint mirrored(PlanPoint p, double width_mm) { return {width_mm - p.X, p.Y}; }

}  // namespace

SupportFrame first_support_frame(const RasterPlan& raster_plan, const PixelGrid& grid, const Sheet& sheet) {
  const Grid<std::int32_t>& face = raster_plan.face;
  // The lattice's mirror image must be the sheet's: PixelGrid::covering rounds its width as here.
  if (face.cols != grid.cols || std::abs(grid.cols / grid.px_per_mm - sheet.width_mm) > 1e-9) return SupportFrame::Only;
  // The model's columns: those with a face of the model in them.
  int lo = INT_MAX, hi = -1;
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c)
      if (face(c, r) > kFloorFace) lo = std::min(lo, c), hi = std::max(hi, c);
  for (int left = lo, right = hi; left < right; ++left, --right)
    for (int r = 0; r < face.rows; ++r) {
      const PixelKind a = pixel_kind(raster_plan, left, r, 1), b = pixel_kind(raster_plan, right, r, -1);
      if (a != b) return a < b ? SupportFrame::Plan : SupportFrame::MirrorImage;
    }
  return SupportFrame::Only;
}

// Every map the supports read written once into its mirror image, in parallel (seedlike/chapel's
// second frame: copying the maps and then reversing them took 3.5% of its samples, now 2.4%, mostly
// the first touches of their memory). The normals (12 bytes a pixel), which nothing reads in the
// mirror image, are left out: with the maps' own 53 -> 37 bytes a pixel (raster.hpp), peak memory
// of seedlike/torus, whose supports are chosen there, 213 -> 162 MB. Each member is named: a grid
// added to RasterMaps and left out here is a warning (-Wmissing-field-initializers; not so a member
// with a default initializer).
RasterMaps mirror_image(const RasterMaps& maps) {
  // A break between columns c and c + 1, t of the way from c, is between their mirror images, the
  // same distance from the other: in the mirror image's column cols - 2 - c, 1 - t of the way; the
  // last column has none.
  const Grid<float>& right = maps.break_right;
  Grid<float> break_right = Grid<float>::unfilled(right.cols, right.rows);
  for_bands(right.rows, [&](int, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      for (int c = 0; c + 1 < right.cols; ++c) break_right(right.cols - 2 - c, r) = 1 - right(c, r);
      if (right.cols > 0) break_right(right.cols - 1, r) = std::numeric_limits<float>::quiet_NaN();
    }
  });
  return RasterMaps{.grid = maps.grid,
                    .reference = maps.reference,
                    .kind = mirrored_copy(maps.kind),
                    .d_mm = mirrored_copy(maps.d_mm),
                    .h_mm = mirrored_copy(maps.h_mm),
                    .normal = {},
                    .break_right = std::move(break_right),
                    .break_below = mirrored_copy(maps.break_below),
                    .model_pixels = maps.model_pixels};
}

RasterPlan mirror_image(RasterPlan raster_plan) {
  raster_plan.face = columns_reversed(std::move(raster_plan.face));
  raster_plan.subsegment = columns_reversed(std::move(raster_plan.subsegment));
  // block_subsegment samples each W x W block at a centre counted from the left edge, which no
  // reversal of its columns mirrors exactly; nothing reads it after slicing, and it is left as it is.
  return raster_plan;
}

RasterPlan with_faces_in_scan_order(RasterPlan raster_plan) {
  const std::size_t n = raster_plan.faces.size();
  std::vector<std::int32_t> id(n, -1);
  id[kBackFace] = kBackFace, id[kFloorFace] = kFloorFace;
  std::int32_t next = kFloorFace + 1;
  for (const std::int32_t f : raster_plan.face.values)
    if (f >= 0 && id[static_cast<std::size_t>(f)] < 0) id[static_cast<std::size_t>(f)] = next++;
  for (std::int32_t& i : id)
    if (i < 0) i = next++;
  bool same = true;
  for (std::size_t f = 0; f < n; ++f) same = same && id[f] == static_cast<std::int32_t>(f);
  if (same) return raster_plan;
  std::vector<RasterFace> faces(n);
  for (std::size_t f = 0; f < n; ++f) faces[static_cast<std::size_t>(id[f])] = raster_plan.faces[f];
  raster_plan.faces = std::move(faces);
  for (std::int32_t& f : raster_plan.face.values)
    if (f >= 0) f = id[static_cast<std::size_t>(f)];
  return raster_plan;
}

SupportedPlan mirror_image(SupportedPlan supported, const Sheet& sheet) {
  const double width = sheet.width_mm;
  supported.raster_plan = mirror_image(std::move(supported.raster_plan));
  Plan& plan = supported.plan;
  for (PlanFace& face : plan.faces) face.inside = mirrored(face.inside, width);
  for (PlanPolyline& line : plan.lines)
    for (PlanPoint& p : line.points) p = mirrored(p, width);
  // Mirrored, a ring turns the other way: its points reversed keep outer boundaries
  // counter-clockwise and holes clockwise.
  for (PlanRegion& region : plan.regions) {
    region.inside = mirrored(region.inside, width);
    for (std::vector<PlanPoint>& ring : region.rings) {
      for (PlanPoint& p : ring) p = mirrored(p, width);
      std::ranges::reverse(ring);
    }
  }
  SupportReport& report = supported.report;
  for (CutOutFace& face : report.cut_out_faces) face.at = mirrored(face.at, width);
  for (JoinedFace& face : report.joined_faces) face.at = mirrored(face.at, width);
  for (NarrowStrip& strip : report.narrow) strip.at = mirrored(strip.at, width);
  return supported;
}

}  // namespace origamic
