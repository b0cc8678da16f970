// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "four_neighbours.hpp"
#include "origamic/error.hpp"
#include "origamic/oa.hpp"
#include "raster_plan_edits.hpp"
#include "thin_subsegments.hpp"
#include "union_find.hpp"

namespace origamic {
namespace {

constexpr std::int32_t kUnassigned = -2;

// §4.3.1: per column of the image, the segment's vertical (h) and horizontal (d) spans; the larger
// of the two maxima over all columns decides. Ties go to V: a 45-degree slope stays vertical.
std::vector<Orientation> choose_orientations(const RasterMaps& maps, const Segmentation& seg) {
  const auto n = static_cast<std::size_t>(seg.count);
  std::vector<double> max_h_span(n, 0), max_d_span(n, 0);
  std::vector<double> lo_h(n), hi_h(n), lo_d(n), hi_d(n);
  std::vector<int> seen_in(n, -1);
  std::vector<std::int32_t> touched;
  for (int col = 0; col < maps.grid.cols; ++col) {
    touched.clear();
    for (int row = 0; row < maps.grid.rows; ++row) {
      const std::int32_t s = seg.segment(col, row);
      if (s < 2) continue;
      const double h = maps.h_mm(col, row), d = maps.d_mm(col, row);
      if (seen_in[s] != col) {
        seen_in[s] = col;
        touched.push_back(s);
        lo_h[s] = hi_h[s] = h;
        lo_d[s] = hi_d[s] = d;
      }
      lo_h[s] = std::min(lo_h[s], h), hi_h[s] = std::max(hi_h[s], h);
      lo_d[s] = std::min(lo_d[s], d), hi_d[s] = std::max(hi_d[s], d);
    }
    for (const std::int32_t s : touched) {
      max_h_span[s] = std::max(max_h_span[s], hi_h[s] - lo_h[s]);
      max_d_span[s] = std::max(max_d_span[s], hi_d[s] - lo_d[s]);
    }
  }
  std::vector<Orientation> orientation(n, Orientation::V);
  orientation[kFloorSegment] = Orientation::H;
  for (std::size_t s = 2; s < n; ++s) orientation[s] = max_d_span[s] > max_h_span[s] ? Orientation::H : Orientation::V;
  return orientation;
}

// The block lattice: W x W pixel blocks, one block row boundary on the main fold.
struct Blocks {
  int size = 1;
  int first_row = 0;  // image row of block row 0's top (may be negative)
  int cols = 0;
  int rows = 0;

  Blocks(const PixelGrid& grid, int block) : size(block) {
    first_row = grid.rows_above_fold % block - (grid.rows_above_fold % block ? block : 0);
    cols = (grid.cols + block - 1) / block;
    rows = (grid.rows - first_row + block - 1) / block;
  }
  int block_col(int col) const { return col / size; }
  int block_row(int row) const { return (row - first_row) / size; }
  int centre_col(int bc) const { return bc * size + size / 2; }
  int centre_row(int br) const { return first_row + br * size + size / 2; }
};

// The depth quantization at full resolution: each segment's depth range is cut into the most levels
// at least W deep that fit, and each 4-connected run of pixels of one segment within one level is a
// subsegment at their mean depth. A slice's boundaries are then the model's iso-depth contours, and
// a V slice is at least W tall in the plan wherever it is not cut short by the segment's outline
// (Y = h - d changes by at least as much as d). Point sampling W x W blocks instead aliases: on a
// dome, neighbouring rows of blocks sample the same level or skip one, and slivers result.
std::vector<Subsegment> level_subsegments(const RasterMaps& maps, const Segmentation& seg,
                                          const std::vector<Orientation>& orientation, const SliceOptions& options,
                                          Grid<std::int32_t>& subsegment) {
  const double W = options.min_strip_mm;
  // A curved segment is sliced where it is steep into V slices (levels of d) and where it is flat
  // into H slices (levels of h): a slice is then at least 2 W tall in the plan, room for the support
  // that joins it to the next. Within 10 degrees of 45 the segment's own orientation holds.
  const float tan_35 = 0.7002075f;
  const std::size_t n = 2 * orientation.size();
  std::vector<std::uint8_t> part_of(seg.segment.size(), 0);  // 2 * segment + (H ? 1 : 0)
  for (std::size_t i = 0; i < seg.segment.size(); ++i) {
    const std::int32_t s = seg.segment.values[i];
    if (s < 2) continue;
    const glm::vec3& normal = maps.normal.values[i];
    const float steep = std::abs(normal.z), flat = std::abs(normal.y);
    Orientation o = orientation[static_cast<std::size_t>(s)];
    if (flat < steep * tan_35)
      o = Orientation::V;
    else if (steep < flat * tan_35)
      o = Orientation::H;
    part_of[i] = o == Orientation::H;
  }
  auto part = [&](std::size_t i) { return 2 * static_cast<std::size_t>(seg.segment.values[i]) + part_of[i]; };
  auto depth_at = [&](std::size_t i) { return part_of[i] ? maps.h_mm.values[i] : maps.d_mm.values[i]; };
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity()), farthest(n, -nearest[0]);
  for (std::size_t i = 0; i < seg.segment.size(); ++i)
    if (seg.segment.values[i] >= 2) {
      nearest[part(i)] = std::min(nearest[part(i)], depth_at(i));
      farthest[part(i)] = std::max(farthest[part(i)], depth_at(i));
    }
  // The lowest terrace of a slope rising off the floor, at its pixels' mean height (about W / 2),
  // stood on a riser as tall as that, a strip between two folds (issue 23). An H part reaching the
  // floor with room for two levels has its levels begin at W / 2, the lowest kept W above the floor.
  // Over the 37 models at W = 2 / 3 / 5 mm: faces between two folds under W apart 557 / 304 / 200 ->
  // 527 / 288 / 191, all places under W 7,075 / 4,206 / 2,303 -> 7,043 / 4,138 / 2,300; mean p95
  // 1.976 / 1.799 / 1.879 -> 1.976 / 1.830 / 1.880 W (at 3 mm prim_pyramid's supports land otherwise,
  // 1.92 -> 2.86 W). Parts of one level keep their height: lifted, the castle keep's base plate took
  // its mean 0.17 -> 1.27 W. Tried for V parts at the back plane too (at 3 mm 4,165 places,
  // res_bunny's p95 1.50 -> 1.67 W): not done.
  std::vector<std::uint8_t> off_the_floor(n, 0);
  for (std::size_t k = 1; k < n; k += 2)  // the H parts
    if (nearest[k] < W / 2 && farthest[k] - W / 2 >= 2 * W) off_the_floor[k] = 1, nearest[k] = W / 2;
  // The most levels at least W deep that fit the part's depth range.
  std::vector<double> step(n, W), levels(n, 1);
  for (std::size_t k = 0; k < n; ++k)
    if (farthest[k] > nearest[k]) {
      levels[k] = std::max(1.0, std::floor((farthest[k] - nearest[k]) / W));
      step[k] = (farthest[k] - nearest[k]) / levels[k];
    }
  const int cols = seg.segment.cols;
  Grid<std::int32_t> level(cols, seg.segment.rows, -1);
  for (std::size_t i = 0; i < level.size(); ++i)
    if (seg.segment.values[i] >= 2) {
      const std::size_t k = part(i);
      level.values[i] =
          static_cast<std::int32_t>(std::clamp(std::floor((depth_at(i) - nearest[k]) / step[k]), 0.0, levels[k] - 1));
    }
  subsegment = Grid<std::int32_t>(cols, seg.segment.rows, -1);
  std::vector<Subsegment> subsegments;
  std::vector<double> pixels;
  std::vector<std::size_t> run;
  for (std::size_t i0 = 0; i0 < level.size(); ++i0) {
    if (level.values[i0] < 0 || subsegment.values[i0] >= 0) continue;
    const auto id = static_cast<std::int32_t>(subsegments.size());
    const std::size_t k = part(i0);
    const std::int32_t l = level.values[i0];
    run.assign(1, i0);
    subsegment.values[i0] = id;
    // Mean as base + mean offset, so equal depths give exactly that depth.
    const double base = depth_at(i0);
    double offset_sum = 0;
    bool nearer_level = false, farther_level = false;  // a pixel of the level before (after) touched
    for (std::size_t head = 0; head < run.size(); ++head) {
      const std::size_t i = run[head];
      offset_sum += depth_at(i) - base;
      const int col = static_cast<int>(i % static_cast<std::size_t>(cols)),
                row = static_cast<int>(i / static_cast<std::size_t>(cols));
      for (const auto& [dc, dr] : kFourNeighbours) {
        if (!level.contains(col + dc, row + dr)) continue;
        const std::size_t j = level.index(col + dc, row + dr);
        if (level.values[j] >= 0 && part(j) == k) {
          nearer_level = nearer_level || level.values[j] == l - 1;
          farther_level = farther_level || level.values[j] == l + 1;
        }
        if (subsegment.values[j] >= 0 || level.values[j] != l || part(j) != k) continue;
        subsegment.values[j] = id;
        run.push_back(j);
      }
    }
    // At its pixels' mean depth, unless that lies nearer than W to a level it touches: a support
    // folds a strip between the two as wide as their depths differ (issue 23), and on a curved
    // surface a level's pixels crowd to one side of it (on a sphere where the surface turns away).
    // Kept to the middle step - W of its level on that side, as the other is on its side, the two
    // lie W apart at least. Over the 37 models at W = 2 / 3 / 5 mm: faces between two folds under W
    // apart 913 / 505 / 272 -> 659 / 348 / 205; all places under W 7,846 / 4,734 / 2,429 -> 7,879 /
    // 4,730 / 2,440; mean p95 2.06 / 1.78 / 1.97 -> 2.05 / 1.79 / 1.90 W, all standing.
    double depth = base + offset_sum / static_cast<double>(run.size());
    const double centre = nearest[k] + (l + 0.5) * step[k], slack = (step[k] - W) / 2;
    if (nearer_level) depth = std::max(depth, centre - slack);
    if (farther_level) depth = std::min(depth, centre + slack);
    // Its riser is drawn in the file's coordinates (Y plus half the sheet's height): a hair over W,
    // so that no rounding there leaves it under W.
    if (l == 0 && off_the_floor[k]) depth = std::max(depth, W + 1e-6);
    subsegments.push_back({seg.segment.values[i0], depth, part_of[i0] ? Orientation::H : Orientation::V});
    pixels.push_back(static_cast<double>(run.size()));
  }
  return merge_thin_subsegments(seg.segment, W * maps.grid.px_per_mm, options.merge_thin_slices,
                                {std::move(subsegments), std::move(pixels)}, subsegment);
}

// Pixels the slicing left without a face (removed thin faces, segments the sampling missed) take a
// neighbour's face, one ring at a time so no direction is favoured. First only faces sliced from the
// pixel's own segment may grow (a removed sliver of a dome joins the next ring of the dome, not the
// back plane behind it); then any face of the model (a sliver at a silhouette, the back plane had
// taken the half of it nearer: over the 37 models at W = 3 mm the mean p95 1.80 -> 1.77 W, the
// lowest coverage 96.8 -> 98.8%, places narrower than W 3,890 -> 3,944); then any face. The back
// plane fills only Y > 0 and the floor only Y < 0.
void fill_holes(const PixelGrid& grid, const Grid<std::int32_t>& segment, const std::vector<RasterFace>& faces,
                Grid<std::int32_t>& face) {
  Grid<std::uint8_t> queued(face.cols, face.rows, 0);
  std::vector<std::pair<int, int>> ring, next;
  std::vector<std::int32_t> labels;
  enum class From { OwnSegment, ModelFaces, AnyFace };
  for (const From from : {From::OwnSegment, From::ModelFaces, From::AnyFace}) {
    auto label_of = [&](int col, int row) {
      for (const auto& step : kFourNeighbours) {
        const int c = col + step[0], r = row + step[1];
        if (!face.contains(c, r) || face(c, r) < 0) continue;
        if (from == From::OwnSegment && faces[static_cast<std::size_t>(face(c, r))].segment != segment(col, row))
          continue;
        if (from == From::ModelFaces && (face(c, r) == kBackFace || face(c, r) == kFloorFace)) continue;
        const std::int32_t label = face(c, r);
        if (label == kBackFace || label == kFloorFace) return grid.Y(row) > 0 ? kBackFace : kFloorFace;
        return label;
      }
      return kUnassigned;
    };
    ring.clear();
    for (int row = 0; row < face.rows; ++row)
      for (int col = 0; col < face.cols; ++col)
        if (face(col, row) == kUnassigned) ring.emplace_back(col, row), queued(col, row) = 1;
    // Rings are filled all at once, so no direction is favoured.
    while (!ring.empty()) {
      labels.resize(ring.size());
      for (std::size_t i = 0; i < ring.size(); ++i) labels[i] = label_of(ring[i].first, ring[i].second);
      next.clear();
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto [col, row] = ring[i];
        queued(col, row) = 0;
        if (labels[i] == kUnassigned) continue;
        face(col, row) = labels[i];
      }
      for (std::size_t i = 0; i < ring.size(); ++i) {
        if (labels[i] == kUnassigned) continue;
        for (const auto& step : kFourNeighbours) {
          const int c = ring[i].first + step[0], r = ring[i].second + step[1];
          if (!face.contains(c, r) || face(c, r) != kUnassigned || queued(c, r)) continue;
          queued(c, r) = 1;
          next.emplace_back(c, r);
        }
      }
      ring.swap(next);
    }
  }
  for (int row = 0; row < face.rows; ++row)
    for (int col = 0; col < face.cols; ++col)
      if (face(col, row) == kUnassigned) face(col, row) = grid.Y(row) > 0 ? kBackFace : kFloorFace;
}

// A face sliced at its mean plane can reach past the card: an H(h) face behind the back plane where
// Y > h, a V(d) face below the floor where Y < -d (the part of a slope beyond its mean). That part
// becomes the back plane (the floor), so the face ends on its fold with it, at Y = h (Y = -d), as
// the paper does (seed §4.5).
void keep_within_card(const PixelGrid& grid, RasterPlan& result) {
  for (int row = 0; row < result.face.rows; ++row)
    for (int col = 0; col < result.face.cols; ++col) {
      std::int32_t& f = result.face(col, row);
      if (f < 2) continue;
      const RasterFace& face = result.faces[static_cast<std::size_t>(f)];
      if (!on_card(face.orientation, face.depth_mm, grid.Y(row)))
        f = face.orientation == Orientation::H ? kBackFace : kFloorFace;
    }
}

// A piece of a subsegment too thin to be a face of its own, or several joined.
struct ThinPiece {
  std::vector<std::pair<int, int>> pixels;
  Subsegment plane;
  int pieces = 1;
};

// Thin pieces side by side, 4-connected: calls join(a, b) for each touching pair.
template <typename Join>
void for_touching_pieces(const std::vector<ThinPiece>& thin, int cols, int rows, Join join) {
  Grid<std::int32_t> owner(cols, rows, -1);
  for (std::size_t p = 0; p < thin.size(); ++p)
    for (const auto& [col, row] : thin[p].pixels) owner(col, row) = static_cast<std::int32_t>(p);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {
      const std::int32_t a = owner(col, row);
      if (a < 0) continue;
      for (const auto& [c, r] : {std::pair{col + 1, row}, std::pair{col, row + 1}})
        if (owner.contains(c, r) && owner(c, r) >= 0 && owner(c, r) != a) join(a, owner(c, r));
    }
}

// Thin pieces that touch and face one way, each within W / 2 of its neighbour's depth (half the
// depth between two levels of a slice, so no two levels of one surface chain), are one surface:
// the bars and panels of a lattice (arch_windmill's sails: each panel its own segment, all under
// W, 94 pieces over 4.1 mm of depth on one sail). The surface is sliced as a segment is, into the
// most levels at least W deep; each connected run of pieces within a level is one piece at their
// mean depth, weighted by area, in the segment of its largest piece.
std::vector<ThinPiece> join_coplanar_thin_pieces(std::vector<ThinPiece> thin, int cols, int rows, double W) {
  const auto at = [](std::int32_t p) { return static_cast<std::size_t>(p); };
  UnionFind<std::int32_t> surface(thin.size());
  for_touching_pieces(thin, cols, rows, [&](std::int32_t a, std::int32_t b) {
    const Subsegment &pa = thin[at(a)].plane, &pb = thin[at(b)].plane;
    if (pa.orientation == pb.orientation && std::abs(pa.depth_mm - pb.depth_mm) < W / 2) surface.join(a, b);
  });
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<double> nearest(thin.size(), kInfinity), farthest(thin.size(), -kInfinity);
  for (std::size_t p = 0; p < thin.size(); ++p) {
    const std::size_t s = at(surface.root(static_cast<std::int32_t>(p)));
    nearest[s] = std::min(nearest[s], thin[p].plane.depth_mm);
    farthest[s] = std::max(farthest[s], thin[p].plane.depth_mm);
  }
  std::vector<std::int32_t> level(thin.size());
  for (std::size_t p = 0; p < thin.size(); ++p) {
    const std::size_t s = at(surface.root(static_cast<std::int32_t>(p)));
    const double levels = std::max(1.0, std::floor((farthest[s] - nearest[s]) / W));
    const double step = (farthest[s] - nearest[s]) / levels;
    level[p] =
        step > 0
            ? static_cast<std::int32_t>(std::min(levels - 1, std::floor((thin[p].plane.depth_mm - nearest[s]) / step)))
            : 0;
  }
  UnionFind<std::int32_t> piece(thin.size());
  for_touching_pieces(thin, cols, rows, [&](std::int32_t a, std::int32_t b) {
    if (surface.root(a) == surface.root(b) && level[at(a)] == level[at(b)]) piece.join(a, b);
  });
  std::vector<std::vector<std::size_t>> members(thin.size());
  for (std::size_t p = 0; p < thin.size(); ++p) members[at(piece.root(static_cast<std::int32_t>(p)))].push_back(p);
  std::vector<ThinPiece> joined;
  for (const std::vector<std::size_t>& group : members) {
    if (group.empty()) continue;
    if (group.size() == 1) {
      joined.push_back(std::move(thin[group.front()]));
      continue;
    }
    double depth_sum = 0, area = 0;
    std::size_t largest = group.front();
    for (const std::size_t p : group) {
      const double n = static_cast<double>(thin[p].pixels.size());
      depth_sum += n * thin[p].plane.depth_mm, area += n;
      if (thin[p].pixels.size() > thin[largest].pixels.size()) largest = p;
    }
    ThinPiece one{{}, thin[largest].plane, static_cast<int>(group.size())};
    one.plane.depth_mm = depth_sum / area;
    for (const std::size_t p : group) one.pixels.insert(one.pixels.end(), thin[p].pixels.begin(), thin[p].pixels.end());
    joined.push_back(std::move(one));
  }
  return joined;
}

// Whether a piece stands clear in front of what lies behind it: two thirds or more of the placed
// pixels around it are the back plane's, the floor's, or the model's 2 W or more lower in h + d than
// the piece's pixel beside them (a V piece W in front of a V face). Else the piece is a detail among
// the model's faces, filled from them: kept, such pieces cost the supports more than they gave
// (arch_temple p95 2.8 -> 6.2 W, arch_water_tower 21 -> 42 W; a margin of 2 W keeps both as they were).
bool stands_clear(const ThinPiece& piece, const RasterPlan& plan, const RasterMaps& maps, double W) {
  const auto key = [&](int col, int row) { return maps.h_mm(col, row) + maps.d_mm(col, row); };
  std::int64_t around = 0, background = 0;
  for (const auto& [col, row] : piece.pixels)
    for (const auto& [dc, dr] : kFourNeighbours) {
      const int c = col + dc, r = row + dr;
      if (!plan.face.contains(c, r) || plan.face(c, r) < 0) continue;
      ++around;
      background += plan.face(c, r) == kBackFace || plan.face(c, r) == kFloorFace || key(c, r) <= key(col, row) - 2 * W;
    }
  return around > 0 && 3 * background >= 2 * around;
}

// A piece holding this share of the model's pixels is a part of it wherever it stands: arch_windmill's
// sails on a 150 x 150 mm card, less than W in front of the tower, hold 36% and 13% of the model;
// the largest pieces among arch_temple's and arch_water_tower's faces 0.9% and 1.0%.
constexpr double kPartShare = 0.05;

// Whether pixel (c, r) is the back plane's or the floor's and no face of the model but `self` meets
// it above (on the floor) or below (on the back plane), where the two may fold: those stay.
bool widenable(const Grid<std::int32_t>& face, int c, int r, std::int32_t self = kNoFace) {
  if (!face.contains(c, r)) return false;
  const auto model_at = [&](int cc, int rr) {
    return face.contains(cc, rr) && face(cc, rr) > kFloorFace && face(cc, rr) != self;
  };
  return (face(c, r) == kFloorFace && !model_at(c, r - 1)) || (face(c, r) == kBackFace && !model_at(c, r + 1));
}

// Widens each row's runs of `cells` along X to need_px over the pixels `free` allows and `taken`
// does not mark (both sides out by as much, or the free one by all), marking those it takes. The
// pixels taken, and whether every run is then at least min_px wide.
template <typename Free>
std::pair<std::vector<std::pair<int, int>>, bool> widen_runs(std::vector<std::pair<int, int>> cells, Free free,
                                                             Grid<std::uint8_t>& taken, int need_px, double min_px) {
  const auto open = [&](int c, int r) { return free(c, r) && !taken(c, r); };
  std::ranges::sort(cells, {}, [](const auto& p) { return std::pair{p.second, p.first}; });  // by row
  std::vector<std::pair<int, int>> added;
  bool wide = true;
  for (std::size_t i = 0; i < cells.size();) {
    const int r = cells[i].second;
    int c0 = cells[i].first, c1 = c0;  // the run from column c0 to c1
    std::size_t j = i + 1;
    while (j < cells.size() && cells[j].second == r && cells[j].first == c1 + 1) c1 = cells[j++].first;
    i = j;
    for (bool left = true; c1 - c0 + 1 < need_px; left = !left) {
      if (left && open(c0 - 1, r))
        taken(--c0, r) = 1, added.emplace_back(c0, r);
      else if (!left && open(c1 + 1, r))
        taken(++c1, r) = 1, added.emplace_back(c1, r);
      else if (!open(c0 - 1, r) && !open(c1 + 1, r))
        break;
    }
    wide &= c1 - c0 + 1 >= min_px;
  }
  return {std::move(added), wide};
}

// A thin piece that stands clear (a pole, a spire, a sail narrower than W) had gone from the card,
// its pixels filled from the back plane or the floor: the cutter needs W of paper. Instead its rows
// are widened along X over the back plane and the floor beside it (pixels of no model, which no
// other widened piece took: `taken`; not where a face of the model folds with them) to `need_px`,
// where every run then is W wide. No model pixel of it changes plane; a pole before a face of the
// model, which it could only widen over, stays thin and goes.
bool widen_over_background(ThinPiece& piece, const Grid<std::int32_t>& face, Grid<std::uint8_t>& taken, int need_px,
                           double min_side_px) {
  const auto background = [&](int c, int r) { return widenable(face, c, r); };
  auto [added, wide] = widen_runs(piece.pixels, background, taken, need_px, min_side_px);
  std::vector<std::pair<int, int>> all = piece.pixels;
  all.insert(all.end(), added.begin(), added.end());
  if (added.empty() || !wide || oriented_box_min_side_px(all) < min_side_px) {
    for (const auto& [c, r] : added) taken(c, r) = 0;
    return false;
  }
  piece.pixels = std::move(all);
  return true;
}

// Connected pieces of each full-resolution subsegment become faces; pieces whose oriented box has a
// side under W are removed and their holes filled from the neighbours (§4.3.3, last paragraph).
void build_faces(const RasterMaps& maps, const Segmentation& seg, const std::vector<Subsegment>& subsegments, double W,
                 RasterPlan& result) {
  const int cols = maps.grid.cols, rows = maps.grid.rows;
  result.face = Grid<std::int32_t>(cols, rows, kNoFace);
  result.faces = {{Orientation::V, 0.0, kBackSegment, 0}, {Orientation::H, 0.0, kFloorSegment, 0}};
  for (std::size_t i = 0; i < result.face.size(); ++i) {
    const std::int32_t s = seg.segment.values[i];
    result.face.values[i] = s == kBackSegment    ? kBackFace
                            : s == kFloorSegment ? kFloorFace
                            : s < 0              ? kNoFace
                                                 : kUnassigned;
  }
  const auto model_pixels = std::ranges::count(result.face.values, kUnassigned);
  const double min_side_px = W * maps.grid.px_per_mm;
  std::vector<ThinPiece> thin;
  Grid<std::uint8_t> visited(cols, rows, 0);
  std::vector<std::pair<int, int>> piece;
  for (int row0 = 0; row0 < rows; ++row0)
    for (int col0 = 0; col0 < cols; ++col0) {
      const std::int32_t k = result.subsegment(col0, row0);
      if (k < 0 || visited(col0, row0)) continue;
      piece.assign(1, {col0, row0});
      visited(col0, row0) = 1;
      for (std::size_t head = 0; head < piece.size(); ++head) {
        const auto [col, row] = piece[head];
        for (const auto& step : kFourNeighbours) {
          const int c = col + step[0], r = row + step[1];
          if (!visited.contains(c, r) || visited(c, r) || result.subsegment(c, r) != k) continue;
          visited(c, r) = 1;
          piece.emplace_back(c, r);
        }
      }
      const Subsegment& sub = subsegments[static_cast<std::size_t>(k)];
      if (oriented_box_min_side_px(piece) < min_side_px) {
        thin.push_back({std::move(piece), sub, 1});
        continue;
      }
      const auto id = static_cast<std::int32_t>(result.faces.size());
      result.faces.push_back({sub.orientation, sub.depth_mm, sub.segment, 0});
      for (const auto& [col, row] : piece) result.face(col, row) = id;
    }
  // Which joined pieces stand clear is decided on the faces placed before any of them, so that
  // neither decides for another (two levels of one sail).
  std::vector<ThinPiece> joined = join_coplanar_thin_pieces(std::move(thin), cols, rows, W);
  std::vector<std::uint8_t> kept(joined.size());
  Grid<std::uint8_t> widened(cols, rows, 0);
  // A run W and a pixel wide: the side that stays the model's edge may be drawn up to half a pixel in.
  const int need_px = static_cast<int>(std::ceil(min_side_px)) + 1;
  std::vector<std::uint8_t> widen(joined.size());
  for (std::size_t i = 0; i < joined.size(); ++i) {
    const bool part = static_cast<double>(joined[i].pixels.size()) >= kPartShare * static_cast<double>(model_pixels);
    const bool wide = oriented_box_min_side_px(joined[i].pixels) >= min_side_px;
    const bool clear = part || stands_clear(joined[i], result, maps, W);
    widen[i] = clear && !wide && widen_over_background(joined[i], result.face, widened, need_px, min_side_px);
    kept[i] = clear && (wide || widen[i]);
  }
  std::vector<std::int32_t> widened_faces;
  for (std::size_t i = 0; i < joined.size(); ++i) {
    if (!kept[i]) {
      result.removed_thin += joined[i].pieces;
      continue;
    }
    const auto id = static_cast<std::int32_t>(result.faces.size());
    result.faces.push_back({joined[i].plane.orientation, joined[i].plane.depth_mm, joined[i].plane.segment, 0});
    for (const auto& [col, row] : joined[i].pixels) result.face(col, row) = id;
    if (widen[i]) widened_faces.push_back(id), result.widened_thin += joined[i].pieces;
  }
  fill_holes(maps.grid, seg.segment, result.faces, result.face);
  // The holes a widened piece filled (a pole's top, too shallow to widen) are widened with it.
  if (!widened_faces.empty()) {
    std::vector<std::int32_t> slot(result.faces.size(), -1);  // each widened face's in widened_faces
    for (std::size_t k = 0; k < widened_faces.size(); ++k)
      slot[static_cast<std::size_t>(widened_faces[k])] = static_cast<std::int32_t>(k);
    std::vector<std::vector<std::pair<int, int>>> cells(widened_faces.size());
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        if (const std::int32_t f = result.face(c, r); f >= 0 && slot[static_cast<std::size_t>(f)] >= 0)
          cells[static_cast<std::size_t>(slot[static_cast<std::size_t>(f)])].emplace_back(c, r);
    for (std::size_t k = 0; k < widened_faces.size(); ++k) {
      const auto background = [&](int c, int r) { return widenable(result.face, c, r, widened_faces[k]); };
      for (const auto& [c, r] : widen_runs(cells[k], background, widened, need_px, min_side_px).first)
        result.face(c, r) = widened_faces[k];
    }
  }
  keep_within_card(maps.grid, result);
  result = merge_coplanar_faces(std::move(result));
  // Slices of one segment are W apart; faces of different segments nearer than a quarter of it in
  // depth are one plane of paper (the 0.2 mm between two facets of arch_one_wtc).
  result = merge_near_coplanar_faces(std::move(result), W / 4);
}

}  // namespace

double oriented_box_min_side_px(const std::vector<std::pair<int, int>>& pixels) {
  if (pixels.empty()) return 0;
  double mx = 0, my = 0;
  for (const auto& [x, y] : pixels) mx += x, my += y;
  const double n = static_cast<double>(pixels.size());
  mx /= n, my /= n;
  double sxx = 0, syy = 0, sxy = 0;
  for (const auto& [x, y] : pixels) {
    sxx += (x - mx) * (x - mx), syy += (y - my) * (y - my), sxy += (x - mx) * (y - my);
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);  // principal axis
  const double ux = std::cos(angle), uy = std::sin(angle);
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& [x, y] : pixels) {
    const double u = x * ux + y * uy, v = -x * uy + y * ux;
    lo_u = std::min(lo_u, u), hi_u = std::max(hi_u, u), lo_v = std::min(lo_v, v), hi_v = std::max(hi_v, v);
  }
  // Pixels are unit squares: a run of k pixels is k long.
  return std::min(hi_u - lo_u, hi_v - lo_v) + 1;
}

RasterPlan slice(const RasterMaps& maps, const Segmentation& seg, const SliceOptions& options) {
  const double W = options.min_strip_mm;
  if (!(std::isfinite(W) && W * maps.grid.px_per_mm >= 1))
    throw InputError("SliceOptions::min_strip_mm", "must be a finite width of at least one pixel (" +
                     std::to_string(1 / maps.grid.px_per_mm) + " mm at this resolution)");
  // A pop-up needs a few strips across each half of the card.
  const double widest = std::min(maps.grid.cols, maps.grid.rows_above_fold) / maps.grid.px_per_mm / 4;
  if (!(W <= widest)) {
    char text[128];
    std::snprintf(text, sizeof text,
                  "at most a quarter of the card's width and of each half's height (%.1f mm here)", widest);
    throw InputError("SliceOptions::min_strip_mm", text);
  }
  RasterPlan result;
  result.min_strip_mm = W;
  result.block_px = static_cast<int>(std::ceil(W * maps.grid.px_per_mm - 1e-9));
  result.segment_orientation = choose_orientations(maps, seg);
  const Blocks blocks(maps.grid, result.block_px);
  const std::vector<Subsegment> subsegments =
      level_subsegments(maps, seg, result.segment_orientation, options, result.subsegment);
  // SDS, for the maps: the subsegment at each block's centre.
  result.block_subsegment = Grid<std::int32_t>(blocks.cols, blocks.rows, -1);
  for (int br = 0; br < blocks.rows; ++br)
    for (int bc = 0; bc < blocks.cols; ++bc)
      if (result.subsegment.contains(blocks.centre_col(bc), blocks.centre_row(br)))
        result.block_subsegment(bc, br) = result.subsegment(blocks.centre_col(bc), blocks.centre_row(br));
  result.subsegments = static_cast<int>(subsegments.size());
  build_faces(maps, seg, subsegments, W, result);
  return result;
}

}  // namespace origamic
