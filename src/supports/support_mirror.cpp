// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_mirror.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "bands.hpp"

namespace origamic {
namespace {

// A grid's columns reversed in place, bands of rows in parallel, each value turned as it lands (a
// normal's x negated in the mirror image).
template <class T, class Turn = std::identity>
void reverse_columns(Grid<T>& grid, Turn turn = {}) {
  for_bands(grid.rows, [&](int, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      T* row = &grid.values[grid.index(0, r)];
      std::reverse(row, row + grid.cols);
      if constexpr (!std::is_same_v<Turn, std::identity>)
        for (int c = 0; c < grid.cols; ++c) row[c] = turn(row[c]);
    }
  });
}

template <class T>
Grid<T> columns_reversed(Grid<T> grid) {
  reverse_columns(grid);
  return grid;
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

// In place, not copied: the supports' choice in the mirror frame held the model's maps and their
// mirror image (25 bytes a pixel) at once; seedlike/torus's peak memory 142 -> 122 MB (with the
// normals dropped after slicing too, design.hpp: seedlike/sphere 158 -> 123 MB, arch_city_block
// 188 -> 132 MB), the same plans.
void mirror_in_place(RasterMaps& maps) {
  // Every member named: a grid added to RasterMaps and not mirrored here does not compile.
  auto& [grid, reference, kind, d_mm, h_mm, normal, break_right, break_below, model_pixels] = maps;
  reverse_columns(kind);
  reverse_columns(d_mm);
  reverse_columns(h_mm);
  reverse_columns(normal, [](glm::vec3 n) { return glm::vec3(-n.x, n.y, n.z); });
  reverse_columns(break_below);
  // A break between columns c and c + 1, t of the way from c, is between their mirror images, the
  // same distance from the other: in the mirror image's column cols - 2 - c, 1 - t of the way; the
  // last column has none. (t is a multiple of 1/2048, so 1 - t is exact and twice gives t back.)
  if (break_right.cols == 0) return;
  for_bands(break_right.rows, [&](int, int row_begin, int row_end) {
    for (int r = row_begin; r < row_end; ++r) {
      float* row = &break_right.values[break_right.index(0, r)];
      std::reverse(row, row + break_right.cols - 1);
      for (int c = 0; c + 1 < break_right.cols; ++c) row[c] = 1 - row[c];
      row[break_right.cols - 1] = std::numeric_limits<float>::quiet_NaN();
    }
  });
}

MirroredMaps::MirroredMaps(RasterMaps& maps) : maps_(maps) { mirror_in_place(maps_); }
MirroredMaps::~MirroredMaps() { mirror_in_place(maps_); }

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
  // Plan::fallbacks stay keyed in the frame the plan was drawn in (drawn_as builds again there).
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
  for (CutOutFace& face : report.spared_faces) face.at = mirrored(face.at, width);
  for (JoinedFace& face : report.joined_faces) face.at = mirrored(face.at, width);
  for (NarrowStrip& strip : report.narrow) strip.at = mirrored(strip.at, width);
  return supported;
}

}  // namespace origamic
