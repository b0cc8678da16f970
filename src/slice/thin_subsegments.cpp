// SPDX-License-Identifier: GPL-3.0-or-later
// Slicing's levels merged where they are thinner than W (thin_subsegments.hpp).
#include "thin_subsegments.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <tuple>

#include "disc_width.hpp"
#include "four_neighbours.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

// The subsegments as merge_thin_subsegments works on them, pass after pass.
struct SubsegmentSet {
  std::vector<Subsegment> subsegments;
  std::vector<double> pixels;
  // Each one's pixels in row-major order, and whether it is thin: kept from pass to pass for the
  // subsegments no merge touched.
  std::vector<std::vector<std::pair<int, int>>> members;
  std::vector<std::uint8_t> thin;
};

// Whether a subsegment is too thin to be a face (merge_thin_subsegments).
enum Thin : std::uint8_t { kWide, kThinBox, kThinDisc };  // kThinDisc: its box W wide, no disc W across

struct Thinness {
  double min_side_px;
  bool by_widest_disc;

  std::uint8_t operator()(const std::vector<std::pair<int, int>>& pixels_of) const {
    if (pixels_of.empty()) return kWide;
    if (oriented_box_min_side_px(pixels_of) < min_side_px) return kThinBox;
    return by_widest_disc && !holds_square_px(pixels_of, static_cast<int>(std::ceil(min_side_px))) &&
                   widest_disc_px(pixels_of) < min_side_px
               ? kThinDisc
               : kWide;
  }
};

// Each thin subsegment's neighbour nearest in depth (ties: the larger, then the lower id: two levels
// kept W apart from it are as near, and ids follow the scan, which a mirror image reverses), into[k],
// or k itself.
// Pairs merge, the thinnest first, each subsegment in at most one pair per pass: a run of slivers
// becomes steps about W wide, not one wide step. `id_at` names the subsegment at a pixel.
template <typename IdAt>
std::vector<std::int32_t> thin_pairs(const SubsegmentSet& set, const Grid<std::int32_t>& segment, IdAt id_at) {
  const std::vector<Subsegment>& subsegments = set.subsegments;
  const std::size_t n = subsegments.size();
  std::vector<std::int32_t> into(n);
  std::iota(into.begin(), into.end(), 0);
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < n; ++k)
    if (set.thin[k]) order.push_back(k);
  std::ranges::stable_sort(order, {}, [&](std::size_t k) { return set.pixels[k]; });
  std::vector<std::uint8_t> paired(n, 0);
  for (const std::size_t k : order) {
    if (paired[k]) continue;
    auto gap = [&](std::int32_t x) {
      // Of another orientation, a neighbour is as far as can be: chosen only when no other is.
      const Subsegment& other = subsegments[static_cast<std::size_t>(x)];
      return other.orientation != subsegments[k].orientation ? std::numeric_limits<double>::max()
                                                             : std::abs(other.depth_mm - subsegments[k].depth_mm);
    };
    std::int32_t best = -1;
    for (const auto& [col, row] : set.members[k])
      for (const auto& [dc, dr] : kFourNeighbours) {
        if (!segment.contains(col + dc, row + dr)) continue;
        const std::int32_t j = id_at(col + dc, row + dr);
        if (j < 0 || static_cast<std::size_t>(j) == k || paired[static_cast<std::size_t>(j)] ||
            segment(col + dc, row + dr) != subsegments[k].segment)
          continue;
        // A crescent taking the other orientation's plane stood off its surface as a fin where the
        // surface turns away (seedlike/sphere, prim_cone): it joins a level of its own or stays.
        if (set.thin[k] == kThinDisc &&
            subsegments[static_cast<std::size_t>(j)].orientation != subsegments[k].orientation)
          continue;
        if (best < 0 || std::tuple(gap(j), -set.pixels[static_cast<std::size_t>(j)], j) <
                            std::tuple(gap(best), -set.pixels[static_cast<std::size_t>(best)], best))
          best = j;
      }
    if (best < 0) continue;
    into[k] = best, paired[k] = paired[static_cast<std::size_t>(best)] = 1;
  }
  return into;
}

// Merges each subsegment k into into[k]; returns the new id of each old one (-1: none). A part of
// another orientation takes the plane of the subsegment it joins: its depth does not count in the
// mean, its pixels do in the size.
std::vector<std::int32_t> merge_pairs(SubsegmentSet& set, const std::vector<std::int32_t>& into,
                                      const Thinness& is_thin) {
  const std::size_t n = set.subsegments.size();
  std::vector<double> sum(n, 0), count(n, 0), size(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto r = static_cast<std::size_t>(into[k]);
    size[r] += set.pixels[k];
    if (set.subsegments[k].orientation == set.subsegments[r].orientation)
      sum[r] += set.subsegments[k].depth_mm * set.pixels[k], count[r] += set.pixels[k];
  }
  std::vector<std::int32_t> renumber(n, -1);
  SubsegmentSet next;
  for (std::size_t k = 0; k < n; ++k)
    if (into[k] == static_cast<std::int32_t>(k) && count[k] > 0) {
      renumber[k] = static_cast<std::int32_t>(next.subsegments.size());
      next.subsegments.push_back({set.subsegments[k].segment, sum[k] / count[k], set.subsegments[k].orientation});
      next.pixels.push_back(size[k]);
    }
  next.members.resize(next.subsegments.size());
  next.thin.resize(next.subsegments.size());
  std::vector<std::uint8_t> grown(next.subsegments.size(), 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t r = renumber[static_cast<std::size_t>(into[k])];
    if (r < 0) continue;
    auto& to = next.members[static_cast<std::size_t>(r)];
    if (to.empty()) {
      to = std::move(set.members[k]);
      next.thin[static_cast<std::size_t>(r)] = set.thin[k];
    } else {
      // Row-major again, as a scan of the grid would list them: the box's sums come out the same.
      const auto middle = static_cast<std::ptrdiff_t>(to.size());
      to.insert(to.end(), set.members[k].begin(), set.members[k].end());
      std::ranges::inplace_merge(to, to.begin() + middle, {}, [](const std::pair<int, int>& p) {
        return std::pair{p.second, p.first};
      });
      grown[static_cast<std::size_t>(r)] = 1;
    }
  }
  for (std::size_t r = 0; r < next.subsegments.size(); ++r)
    if (grown[r]) next.thin[r] = is_thin(next.members[r]);
  std::vector<std::int32_t> new_id(n, -1);
  for (std::size_t k = 0; k < n; ++k) new_id[k] = renumber[static_cast<std::size_t>(into[k])];
  set = std::move(next);
  return new_id;
}

}  // namespace

std::vector<Subsegment> merge_thin_subsegments(const Grid<std::int32_t>& segment, double min_side_px,
                                               bool by_widest_disc, SizedSubsegments sized,
                                               Grid<std::int32_t>& subsegment) {
  const Thinness is_thin{min_side_px, by_widest_disc};
  SubsegmentSet set{std::move(sized.subsegments), std::move(sized.pixels), {}, {}};
  set.members.assign(set.subsegments.size(), {});
  for (int row = 0; row < subsegment.rows; ++row)
    for (int col = 0; col < subsegment.cols; ++col)
      if (const std::int32_t k = subsegment(col, row); k >= 0)
        set.members[static_cast<std::size_t>(k)].emplace_back(col, row);
  set.thin.resize(set.subsegments.size());
  for (std::size_t k = 0; k < set.subsegments.size(); ++k) set.thin[k] = is_thin(set.members[k]);
  // The grid keeps its first ids until the end; `current` maps them to the ids of this pass.
  std::vector<std::int32_t> current(set.subsegments.size());
  std::iota(current.begin(), current.end(), 0);
  auto id_at = [&](int col, int row) {
    const std::int32_t k = subsegment(col, row);
    return k < 0 ? k : current[static_cast<std::size_t>(k)];
  };
  for (;;) {
    const std::vector<std::int32_t> into = thin_pairs(set, segment, id_at);
    bool merged = false;
    for (std::size_t k = 0; k < into.size(); ++k) merged = merged || into[k] != static_cast<std::int32_t>(k);
    if (!merged) break;
    const std::vector<std::int32_t> new_id = merge_pairs(set, into, is_thin);
    for (auto& k : current)
      if (k >= 0) k = new_id[static_cast<std::size_t>(k)];
  }
  for (auto& k : subsegment.values)
    if (k >= 0) k = current[static_cast<std::size_t>(k)];
  return std::move(set.subsegments);
}

}  // namespace origamic
