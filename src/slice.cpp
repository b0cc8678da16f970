// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/slice.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include "origamic/error.hpp"
#include "bands.hpp"

namespace origamic {
namespace {

constexpr int kStep[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
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
  for (std::size_t s = 2; s < n; ++s)
    orientation[s] = max_d_span[s] > max_h_span[s] ? Orientation::H : Orientation::V;
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

struct Subsegment {
  std::int32_t segment = 0;
  double depth_mm = 0;
  Orientation orientation = Orientation::V;
};

// Where a surface runs steeper than 45 degrees across the slicing direction, its levels are strips
// narrower than W: each joins the neighbouring subsegment of its segment nearest in depth, pass after
// pass, until it is W wide or has no such neighbour. Levels thus merge into wider steps exactly where
// the surface is steep: the quantization adapts to it (seed Figure 4.6).
void merge_thin_subsegments(const Grid<std::int32_t>& segment, double min_side_px, std::vector<double>& pixels,
                            std::vector<Subsegment>& subsegments, Grid<std::int32_t>& subsegment) {
  // Each subsegment's pixels in row-major order, and whether it is thin: kept from pass to pass for
  // the subsegments no merge touched.
  std::vector<std::vector<std::pair<int, int>>> members(subsegments.size());
  for (int row = 0; row < subsegment.rows; ++row)
    for (int col = 0; col < subsegment.cols; ++col)
      if (const std::int32_t k = subsegment(col, row); k >= 0) members[static_cast<std::size_t>(k)].emplace_back(col, row);
  auto is_thin = [&](const std::vector<std::pair<int, int>>& pixels_of) {
    return !pixels_of.empty() && oriented_box_min_side_px(pixels_of) < min_side_px;
  };
  std::vector<std::uint8_t> thin(subsegments.size());
  for (std::size_t k = 0; k < subsegments.size(); ++k) thin[k] = is_thin(members[k]);
  // The grid keeps its first ids until the end; `current` maps them to the ids of this pass.
  std::vector<std::int32_t> current(subsegments.size());
  std::iota(current.begin(), current.end(), 0);
  auto id_at = [&](int col, int row) {
    const std::int32_t k = subsegment(col, row);
    return k < 0 ? k : current[static_cast<std::size_t>(k)];
  };
  for (;;) {
    const std::size_t n = subsegments.size();
    // Each thin subsegment's neighbour nearest in depth (ties: the lower id).
    // Pairs merge, the thinnest first, each subsegment in at most one pair per pass: a run of slivers
    // becomes steps about W wide, not one wide step.
    std::vector<std::int32_t> into(n);
    std::iota(into.begin(), into.end(), 0);
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < n; ++k)
      if (thin[k]) order.push_back(k);
    std::ranges::stable_sort(order, {}, [&](std::size_t k) { return pixels[k]; });
    std::vector<std::uint8_t> paired(n, 0);
    bool merged = false;
    for (const std::size_t k : order) {
      if (paired[k]) continue;
      auto gap = [&](std::int32_t x) {
        // Of another orientation, a neighbour is as far as can be: chosen only when no other is.
        const Subsegment& other = subsegments[static_cast<std::size_t>(x)];
        return other.orientation != subsegments[k].orientation ? std::numeric_limits<double>::max()
                                                               : std::abs(other.depth_mm - subsegments[k].depth_mm);
      };
      std::int32_t best = -1;
      for (const auto& [col, row] : members[k])
        for (const auto& [dc, dr] : kStep) {
          if (!subsegment.contains(col + dc, row + dr)) continue;
          const std::int32_t j = id_at(col + dc, row + dr);
          if (j < 0 || static_cast<std::size_t>(j) == k || paired[static_cast<std::size_t>(j)] ||
              segment(col + dc, row + dr) != subsegments[k].segment)
            continue;
          if (best < 0 || gap(j) < gap(best) || (gap(j) == gap(best) && j < best)) best = j;
        }
      if (best < 0) continue;
      into[k] = best, paired[k] = paired[static_cast<std::size_t>(best)] = 1, merged = true;
    }
    if (!merged) break;
    // A part of another orientation takes the plane of the subsegment it joins: its depth does not
    // count in the mean, its pixels do in the size.
    std::vector<double> sum(n, 0), count(n, 0), size(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto r = static_cast<std::size_t>(into[k]);
      size[r] += pixels[k];
      if (subsegments[k].orientation == subsegments[r].orientation) sum[r] += subsegments[k].depth_mm * pixels[k], count[r] += pixels[k];
    }
    std::vector<std::int32_t> renumber(n, -1);
    std::vector<Subsegment> next;
    std::vector<double> next_pixels;
    for (std::size_t k = 0; k < n; ++k)
      if (into[k] == static_cast<std::int32_t>(k) && count[k] > 0) {
        renumber[k] = static_cast<std::int32_t>(next.size());
        next.push_back({subsegments[k].segment, sum[k] / count[k], subsegments[k].orientation});
        next_pixels.push_back(size[k]);
      }
    for (auto& k : current)
      if (k >= 0) k = renumber[static_cast<std::size_t>(into[static_cast<std::size_t>(k)])];
    std::vector<std::vector<std::pair<int, int>>> next_members(next.size());
    std::vector<std::uint8_t> next_thin(next.size()), grown(next.size(), 0);
    for (std::size_t k = 0; k < n; ++k) {
      const std::int32_t r = renumber[static_cast<std::size_t>(into[k])];
      if (r < 0) continue;
      auto& to = next_members[static_cast<std::size_t>(r)];
      if (to.empty()) {
        to = std::move(members[k]);
        next_thin[static_cast<std::size_t>(r)] = thin[k];
      } else {
        // Row-major again, as a scan of the grid would list them: the box's sums come out the same.
        const auto middle = static_cast<std::ptrdiff_t>(to.size());
        to.insert(to.end(), members[k].begin(), members[k].end());
        std::ranges::inplace_merge(to, to.begin() + middle, {}, [](const std::pair<int, int>& p) { return std::pair{p.second, p.first}; });
        grown[static_cast<std::size_t>(r)] = 1;
      }
    }
    for (std::size_t r = 0; r < next.size(); ++r)
      if (grown[r]) next_thin[r] = is_thin(next_members[r]);
    subsegments = std::move(next);
    pixels = std::move(next_pixels);
    members = std::move(next_members);
    thin = std::move(next_thin);
  }
  for (auto& k : subsegment.values)
    if (k >= 0) k = current[static_cast<std::size_t>(k)];
}

// The depth quantization at full resolution: each segment's depth range is cut into the most levels
// at least W deep that fit, and each 4-connected run of pixels of one segment within one level is a
// subsegment at their mean depth. A slice's boundaries are then the model's iso-depth contours, and
// a V slice is at least W tall in the plan wherever it is not cut short by the segment's outline
// (Y = h - d changes by at least as much as d). Point sampling W x W blocks instead aliases: on a
// dome, neighbouring rows of blocks sample the same level or skip one, and slivers result.
std::vector<Subsegment> level_subsegments(const RasterMaps& maps, const Segmentation& seg,
                                          const std::vector<Orientation>& orientation, double W,
                                          Grid<std::int32_t>& subsegment) {
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
    if (flat < steep * tan_35) o = Orientation::V;
    else if (steep < flat * tan_35) o = Orientation::H;
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
      level.values[i] = static_cast<std::int32_t>(std::min(levels[k] - 1, std::floor((depth_at(i) - nearest[k]) / step[k])));
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
    for (std::size_t head = 0; head < run.size(); ++head) {
      const std::size_t i = run[head];
      offset_sum += depth_at(i) - base;
      const int col = static_cast<int>(i % static_cast<std::size_t>(cols)), row = static_cast<int>(i / static_cast<std::size_t>(cols));
      for (const auto& [dc, dr] : kStep) {
        if (!level.contains(col + dc, row + dr)) continue;
        const std::size_t j = level.index(col + dc, row + dr);
        if (subsegment.values[j] >= 0 || level.values[j] != l || part(j) != k) continue;
        subsegment.values[j] = id;
        run.push_back(j);
      }
    }
    subsegments.push_back({seg.segment.values[i0], base + offset_sum / static_cast<double>(run.size()),
                           part_of[i0] ? Orientation::H : Orientation::V});
    pixels.push_back(static_cast<double>(run.size()));
  }
  merge_thin_subsegments(seg.segment, W * maps.grid.px_per_mm, pixels, subsegments, subsegment);
  return subsegments;
}

// Pixels the slicing left without a face (removed thin faces, segments the sampling missed) take a
// neighbour's face, one ring at a time so no direction is favoured. First only faces sliced from the
// pixel's own segment may grow (a removed sliver of a dome joins the next ring of the dome, not the
// back plane behind it); then any face. The back plane fills only Y > 0 and the floor only Y < 0.
void fill_holes(const PixelGrid& grid, const Grid<std::int32_t>& segment, const std::vector<RasterFace>& faces,
                Grid<std::int32_t>& face) {
  Grid<std::uint8_t> queued(face.cols, face.rows, 0);
  std::vector<std::pair<int, int>> ring, next;
  std::vector<std::int32_t> labels;
  for (const bool same_segment_only : {true, false}) {
    auto label_of = [&](int col, int row) {
      for (const auto& step : kStep) {
        const int c = col + step[0], r = row + step[1];
        if (!face.contains(c, r) || face(c, r) < 0) continue;
        if (same_segment_only && faces[static_cast<std::size_t>(face(c, r))].segment != segment(col, row)) continue;
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
        for (const auto& step : kStep) {
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

ShapeError shape_error(const RasterMaps& maps, const Grid<std::int32_t>& face, const std::vector<RasterFace>& faces,
                       double W) {
  const Grid<float> error = shape_error_map(maps, face, faces);
  std::vector<float> errors;
  errors.reserve(maps.model_pixels);
  for (const float e : error.values)
    if (e >= 0) errors.push_back(e);
  ShapeError e;
  if (errors.empty()) return e;
  double sum = 0;
  for (const float v : errors) sum += v;
  e.mean_mm = sum / static_cast<double>(errors.size());
  const auto p95 = errors.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(errors.size() - 1));
  std::nth_element(errors.begin(), p95, errors.end());
  e.p95_mm = *p95;
  e.mean_W = e.mean_mm / W;
  e.p95_W = e.p95_mm / W;
  return e;
}

// A face sliced at its mean plane can reach past the card: an H(h) face behind the back plane where
// Y > h, a V(d) face below the floor where Y < -d (the part of a slope beyond its mean). That part
// becomes the back plane (the floor), so the face ends on its fold with it, at Y = h (Y = -d), as
// the paper does (seed §4.5).
void keep_within_card(const PixelGrid& grid, SliceResult& result) {
  for (int row = 0; row < result.face.rows; ++row)
    for (int col = 0; col < result.face.cols; ++col) {
      std::int32_t& f = result.face(col, row);
      if (f < 2) continue;
      const RasterFace& face = result.faces[static_cast<std::size_t>(f)];
      const double Y = grid.Y(row);
      if (face.orientation == Orientation::H && Y > face.depth_mm) f = kBackFace;
      else if (face.orientation == Orientation::V && Y < -face.depth_mm) f = kFloorFace;
    }
}

// Connected pieces of each full-resolution subsegment become faces; pieces whose oriented box has a
// side under W are removed and their holes filled from the neighbours (§4.3.3, last paragraph).
void build_faces(const RasterMaps& maps, const Segmentation& seg, const std::vector<Subsegment>& subsegments,
                 double W, SliceResult& result) {
  const int cols = maps.grid.cols, rows = maps.grid.rows;
  result.face = Grid<std::int32_t>(cols, rows, kNoFace);
  result.faces = {{Orientation::V, 0.0, kBackSegment, 0}, {Orientation::H, 0.0, kFloorSegment, 0}};
  for (std::size_t i = 0; i < result.face.size(); ++i) {
    const std::int32_t s = seg.segment.values[i];
    result.face.values[i] = s == kBackSegment ? kBackFace : s == kFloorSegment ? kFloorFace : s < 0 ? kNoFace : kUnassigned;
  }
  const double min_side_px = W * maps.grid.px_per_mm;
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
        for (const auto& step : kStep) {
          const int c = col + step[0], r = row + step[1];
          if (!visited.contains(c, r) || visited(c, r) || result.subsegment(c, r) != k) continue;
          visited(c, r) = 1;
          piece.emplace_back(c, r);
        }
      }
      if (oriented_box_min_side_px(piece) < min_side_px) {
        ++result.removed_thin;
        continue;
      }
      const auto id = static_cast<std::int32_t>(result.faces.size());
      const Subsegment& sub = subsegments[static_cast<std::size_t>(k)];
      result.faces.push_back({sub.orientation, sub.depth_mm,
                              sub.segment, 0});
      for (const auto& [col, row] : piece) result.face(col, row) = id;
    }
  fill_holes(maps.grid, seg.segment, result.faces, result.face);
  keep_within_card(maps.grid, result);
  merge_coplanar_faces(result);
  result.error = shape_error(maps, result.face, result.faces, W);
}

}  // namespace

void merge_coplanar_faces(SliceResult& result) {
  const std::size_t n = result.faces.size();
  std::vector<std::int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](std::int32_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  Grid<std::int32_t>& face = result.face;
  std::vector<std::int64_t> pixels(n, 0);
  bool merged = false;
  auto join = [&](std::int32_t f, std::int32_t g) {
    if (g < 2 || g == f) return;
    const RasterFace &a_face = result.faces[f], &b_face = result.faces[g];
    // Holes merge with each other whatever plane they came from, and never with paper.
    if (a_face.hole != b_face.hole) return;
    if (!a_face.hole && (a_face.orientation != b_face.orientation || a_face.depth_mm != b_face.depth_mm)) return;
    const std::int32_t a = root(f), b = root(g);
    if (a != b) parent[std::max(a, b)] = std::min(a, b), merged = true;
  };
  // Run by run along the rows, in bands in parallel: a run's pixels are counted at once, and a
  // stretch of one face below it is met once. Joining is the same in any order.
  std::array<std::vector<std::int64_t>, kBands> band_pixels;
  std::array<std::vector<std::pair<std::int32_t, std::int32_t>>, kBands> band_meets;
  for_bands(face.rows, [&](int band, int row_begin, int row_end) {
    std::vector<std::int64_t>& count = band_pixels[static_cast<std::size_t>(band)];
    std::vector<std::pair<std::int32_t, std::int32_t>>& meets = band_meets[static_cast<std::size_t>(band)];
    count.assign(n, 0);
    for (int row = row_begin; row < row_end; ++row) {
      const std::int32_t* here = &face.values[face.index(0, row)];
      const std::int32_t* below = row + 1 < face.rows ? here + face.cols : nullptr;
      for (int col = 0; col < face.cols;) {
        const std::int32_t f = here[col];
        int end = col + 1;
        while (end < face.cols && here[end] == f) ++end;
        if (f >= 0) count[static_cast<std::size_t>(f)] += end - col;
        if (f >= 2) {
          if (end < face.cols && here[end] >= 2) meets.emplace_back(f, here[end]);
          if (below)
            for (int c = col; c < end; ++c)
              if (below[c] != f && below[c] >= 2 && (c == col || below[c] != below[c - 1])) meets.emplace_back(f, below[c]);
        }
        col = end;
      }
    }
  });
  for (std::size_t band = 0; band < kBands; ++band) {
    for (std::size_t f = 0; f < n; ++f) pixels[f] += band_pixels[band][f];
    for (const auto& [f, g] : band_meets[band]) join(f, g);
  }
  const bool emptied = std::any_of(pixels.begin() + std::min<std::size_t>(2, n), pixels.end(), [](std::int64_t p) { return p == 0; });
  if (!merged && !emptied) {  // the ids stay as they are: no pass over the pixels to relabel them
    for (std::size_t f = 0; f < n; ++f) result.faces[f].pixels = pixels[f];
    return;
  }
  for (std::size_t f = 0; f < n; ++f)
    if (const auto r = static_cast<std::size_t>(root(static_cast<std::int32_t>(f))); r != f) pixels[r] += std::exchange(pixels[f], 0);
  std::vector<std::int32_t> new_id(n, -1);
  std::vector<RasterFace> faces;
  for (std::size_t f = 0; f < n; ++f)
    if (root(static_cast<std::int32_t>(f)) == static_cast<std::int32_t>(f) && (f < 2 || pixels[f] > 0)) {
      new_id[f] = static_cast<std::int32_t>(faces.size());
      faces.push_back(result.faces[f]);
      faces.back().pixels = pixels[f];
    }
  for (std::size_t f = 0; f < n; ++f) new_id[f] = new_id[static_cast<std::size_t>(root(static_cast<std::int32_t>(f)))];
  for_bands(face.rows, [&](int, int row_begin, int row_end) {
    const std::size_t cols = static_cast<std::size_t>(face.cols);
    for (std::size_t i = row_begin * cols; i < row_end * cols; ++i)
      if (std::int32_t& f = face.values[i]; f >= 0) f = new_id[static_cast<std::size_t>(f)];
  });
  result.faces = std::move(faces);
}

std::vector<FacePart> split_disconnected_faces(SliceResult& result, const std::vector<std::int32_t>& faces,
                                              std::int64_t min_part_px, int min_part_cols) {
  Grid<std::int32_t>& face = result.face;
  std::vector<std::uint8_t> wanted(result.faces.size(), 0);
  for (const std::int32_t f : faces)
    if (f >= 0 && !result.faces[static_cast<std::size_t>(f)].hole) wanted[static_cast<std::size_t>(f)] = 1;
  // The wanted faces as runs of pixels along the rows; runs of one face that overlap in
  // neighbouring rows are 4-connected. Union-find keeps the first run in row-major order as each
  // part's root, so the parts come out in the order of their first pixel.
  struct Run {
    int row, c0, c1;  // pixels [c0, c1) of the row
    std::int32_t face;
  };
  std::vector<Run> runs;
  std::vector<std::uint32_t> parent;
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::size_t previous_row = 0;  // where the runs of the row above begin
  for (int row = 0; row < face.rows; ++row) {
    const std::int32_t* line = &face.values[face.index(0, row)];
    const std::size_t this_row = runs.size();
    for (int c = 0; c < face.cols;) {
      const std::int32_t f = line[c];
      int end = c + 1;
      while (end < face.cols && line[end] == f) ++end;
      if (f >= 0 && wanted[static_cast<std::size_t>(f)]) {
        runs.push_back({row, c, end, f});
        parent.push_back(static_cast<std::uint32_t>(parent.size()));
      }
      c = end;
    }
    // Both rows' runs are sorted by column: one merge-like sweep finds the overlapping pairs.
    for (std::size_t a = previous_row, b = this_row; a < this_row && b < runs.size();) {
      if (runs[a].row == row - 1 && runs[a].face == runs[b].face && runs[a].c0 < runs[b].c1 && runs[b].c0 < runs[a].c1) {
        const std::uint32_t ra = root(static_cast<std::uint32_t>(a)), rb = root(static_cast<std::uint32_t>(b));
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
      (runs[a].c1 < runs[b].c1 ? a : b) += 1;
    }
    previous_row = this_row;
  }
  // part_runs[i]: the runs of part i, in row-major order.
  std::vector<std::int32_t> part_of_root(runs.size(), -1);
  std::vector<std::vector<std::uint32_t>> part_runs;
  std::vector<std::int32_t> part_face;
  std::vector<std::int64_t> part_size;
  for (std::uint32_t i = 0; i < runs.size(); ++i) {
    std::int32_t& part = part_of_root[root(i)];
    if (part < 0) {
      part = static_cast<std::int32_t>(part_runs.size());
      part_runs.emplace_back();
      part_face.push_back(runs[i].face);
      part_size.push_back(0);
    }
    part_runs[static_cast<std::size_t>(part)].push_back(i);
    part_size[static_cast<std::size_t>(part)] += runs[i].c1 - runs[i].c0;
  }
  const auto paint = [&](std::size_t part, std::int32_t id) {
    for (const std::uint32_t k : part_runs[part]) std::fill_n(&face.values[face.index(runs[k].c0, runs[k].row)], runs[k].c1 - runs[k].c0, id);
  };
  // The largest part of each face keeps its id (the first of equals, for determinism).
  std::vector<std::int32_t> keeper(result.faces.size(), -1);
  for (std::size_t i = 0; i < part_runs.size(); ++i) {
    std::int32_t& k = keeper[static_cast<std::size_t>(part_face[i])];
    if (k < 0 || part_size[i] > part_size[static_cast<std::size_t>(k)]) k = static_cast<std::int32_t>(i);
  }
  std::vector<FacePart> created;
  for (std::size_t i = 0; i < part_runs.size(); ++i) {
    const auto f = static_cast<std::size_t>(part_face[i]);
    const std::int64_t size = part_size[i];
    const bool kept = keeper[f] == static_cast<std::int32_t>(i);
    if (kept && (f < 2 || size >= min_part_px)) {
      result.faces[f].pixels = size;
      continue;
    }
    int lo = INT_MAX, hi = -1;
    for (const std::uint32_t k : part_runs[i]) lo = std::min(lo, runs[k].c0), hi = std::max(hi, runs[k].c1 - 1);
    if (size < min_part_px || (!kept && hi - lo + 1 < min_part_cols)) {
      // A crumb joins the face it shares the most pixel sides with.
      std::map<std::int32_t, int> sides;
      for (const std::uint32_t k : part_runs[i])
        for (int c = runs[k].c0; c < runs[k].c1; ++c)
          for (const auto& [dc, dr] : kStep)
            if (face.contains(c + dc, runs[k].row + dr)) {
              const std::int32_t g = face(c + dc, runs[k].row + dr);
              if (g >= 0 && g != static_cast<std::int32_t>(f) && !result.faces[static_cast<std::size_t>(g)].hole) ++sides[g];
            }
      if (!sides.empty()) {
        const std::int32_t into = std::ranges::max_element(sides, {}, [](const auto& s) { return s.second; })->first;
        paint(i, into);
        result.faces[static_cast<std::size_t>(into)].pixels += size;
        if (kept) result.faces[f].pixels = 0;
        continue;
      }
      if (kept) {
        result.faces[f].pixels = size;
        continue;
      }
    }
    const auto id = static_cast<std::int32_t>(result.faces.size());
    RasterFace piece = result.faces[f];
    piece.pixels = size;
    result.faces.push_back(piece);
    paint(i, id);
    created.push_back({id, static_cast<std::int32_t>(f)});
  }
  return created;
}

namespace {

// Where faces a (row r) and b (row r + 1 below it) should meet: their fold line Y = h - d lies
// between rows t and t + 1, Y = (rows_above_fold - t - 1) / px_per_mm. -1 when they meet on no fold
// within tolerance_mm of their boundary (and for a line above the sheet, which nothing can reach).
int fold_row(const SliceResult& result, const PixelGrid& grid, double tolerance_mm, std::int32_t a, std::int32_t b, int r) {
  if (a == b || a < 0 || b < 0) return -1;
  const RasterFace &fa = result.faces[static_cast<std::size_t>(a)], &fb = result.faces[static_cast<std::size_t>(b)];
  if (fa.orientation == fb.orientation || fa.hole || fb.hole) return -1;
  const double fold_Y = fa.orientation == Orientation::H ? fa.depth_mm - fb.depth_mm : fb.depth_mm - fa.depth_mm;
  const double edge_Y = grid.Y(r) - 0.5 / grid.px_per_mm;
  if (!(std::abs(edge_Y - fold_Y) <= tolerance_mm)) return -1;
  return static_cast<int>(std::lround(grid.rows_above_fold - 1 - fold_Y * grid.px_per_mm));
}

// One sweep of align_folds_to_lines over one column; returns how many pixels changed face.
std::int64_t align_column(SliceResult& result, const PixelGrid& grid, double tolerance_mm, int col) {
  std::int64_t moved = 0;
  Grid<std::int32_t>& face = result.face;
  auto count = [&](std::int32_t f, int delta) { result.faces[static_cast<std::size_t>(f)].pixels += delta; };
  for (int r = 0; r + 1 < face.rows; ++r) {
    const std::int32_t a = face(col, r), b = face(col, r + 1);  // a above, b below
    const int t = fold_row(result, grid, tolerance_mm, a, b, r);
    if (t == -1 || t == r) continue;
    if (t < r) {  // up: b takes rows t + 1 .. r if they are all a and a keeps row t
      bool free = t >= 0 && face(col, t) == a;
      for (int k = t + 1; free && k <= r; ++k) free = face(col, k) == a;
      if (!free) continue;
      for (int k = t + 1; k <= r; ++k) face(col, k) = b, count(a, -1), count(b, 1), ++moved;
    } else {  // down: a takes rows r + 1 .. t if they are all b and b keeps row t + 1
      bool free = t + 1 < face.rows && face(col, t + 1) == b;
      for (int k = r + 1; free && k <= t; ++k) free = face(col, k) == b;
      if (!free) continue;
      for (int k = r + 1; k <= t; ++k) face(col, k) = a, count(b, -1), count(a, 1), ++moved;
      r = t;  // continue below the moved boundary
    }
  }
  return moved;
}

// The first sweep of align_folds_to_lines; returns the columns in which pixels changed face.
// Columns are independent, so only those with a boundary off its line are walked: a row-major scan
// finds them far faster than walking every column down.
std::vector<int> align_sweep(SliceResult& result, const PixelGrid& grid, double tolerance_mm) {
  const Grid<std::int32_t>& face = result.face;
  std::vector<std::uint8_t> off_line(static_cast<std::size_t>(face.cols), 0);
  for (int r = 0; r + 1 < face.rows; ++r) {
    const std::int32_t* above = &face.values[face.index(0, r)];
    const std::int32_t* below = above + face.cols;
    bool last_off = false;  // fold_row of the previous column's pair: the same pair gives the same row
    for (int col = 0; col < face.cols; ++col) {
      if (above[col] == below[col]) continue;
      if (col == 0 || above[col] != above[col - 1] || below[col] != below[col - 1]) {
        const int t = fold_row(result, grid, tolerance_mm, above[col], below[col], r);
        last_off = t != -1 && t != r;
      }
      off_line[static_cast<std::size_t>(col)] |= last_off;
    }
  }
  std::vector<int> moved;
  for (int col = 0; col < face.cols; ++col)
    if (off_line[static_cast<std::size_t>(col)] && align_column(result, grid, tolerance_mm, col) > 0) moved.push_back(col);
  return moved;
}

}  // namespace

void align_folds_to_lines(SliceResult& result, const PixelGrid& grid, double tolerance_mm) {
  // A moved boundary can free another one in its column: sweep those columns again until nothing
  // moves, so that aligning an aligned plan changes nothing (build_plan aligns what it is given).
  // Columns are independent, so one in which nothing moved would not move on a later sweep.
  std::vector<int> moved = align_sweep(result, grid, tolerance_mm);
  for (int sweep = 1; sweep < 8 && !moved.empty(); ++sweep)
    std::erase_if(moved, [&](int col) { return align_column(result, grid, tolerance_mm, col) == 0; });
}

Grid<float> shape_error_map(const RasterMaps& maps, const Grid<std::int32_t>& face, const std::vector<RasterFace>& faces) {
  Grid<float> error(maps.grid.cols, maps.grid.rows, -1.0f);
  for (int row = 0; row < maps.grid.rows; ++row)
    for (int col = 0; col < maps.grid.cols; ++col) {
      if (maps.kind(col, row) != HitKind::Model) continue;
      const RasterFace& f = faces[static_cast<std::size_t>(face(col, row))];
      const double face_d = f.orientation == Orientation::V ? f.depth_mm : f.depth_mm - maps.grid.Y(row);
      error(col, row) = static_cast<float>(std::abs(face_d - maps.d_mm(col, row)));
    }
  return error;
}

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

SliceResult slice(const RasterMaps& maps, const Segmentation& seg, const SliceOptions& options) {
  const double W = options.min_strip_mm;
  if (!(std::isfinite(W) && W * maps.grid.px_per_mm >= 1))
    throw InputError("--min-strip: must be a finite width of at least one pixel (" +
                     std::to_string(1 / maps.grid.px_per_mm) + " mm at this resolution)");
  SliceResult result;
  result.min_strip_mm = W;
  result.block_px = static_cast<int>(std::ceil(W * maps.grid.px_per_mm - 1e-9));
  result.segment_orientation = choose_orientations(maps, seg);
  const Blocks blocks(maps.grid, result.block_px);
  const std::vector<Subsegment> subsegments =
      level_subsegments(maps, seg, result.segment_orientation, W, result.subsegment);
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
