// SPDX-License-Identifier: GPL-3.0-or-later
// Supports (seed §4.4, second half): strips added to the raster plan until the exact plan has no
// floating, dangling or other invalid face. Each round proposes, for every invalid face, supports
// from its unconnected top and bottom edges to the first face behind/above or in front/below,
// chooses greedily in a seeded random order and widens them. The exact plan, rebuilt from scratch,
// judges pieces of paper: a face it finds in pieces becomes one face per piece.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

struct SupportOptions {
  bool enabled = true;
  std::uint32_t seed = 1;        // the order in which invalid faces choose (--seed)
  bool allow_dangling = false;   // leave dangling faces (windows, balconies) as they are
  // c(s) = length + corner + split (seed §4.4): a support that cuts through a third face costs this
  // much more, so it is chosen only when nothing else reaches.
  double split_cost_mm = 1000;
  // When supports run out, cut the faces they could not hold out of the sheet (holes, reported as
  // "removed") so that what is left stands; off, such faces stay in the plan, reported invalid.
  bool cut_out_unsupported = true;
  // Face orders tried, one after another from the seed's random sequence, until one makes the
  // plan stand with under 15% of the model cut out; the best of them is kept (fewest faces left
  // unheld, then least cut out).
  int orders = 8;
};

/// A face or support whose whole extent along the main fold is under W: the place to look.
struct NarrowStrip {
  std::int32_t face = 0;
  bool support = false;
  double width_mm = 0;  // its extent along X
  PlanPoint at;         // a pixel centre of it (in its middle column where it has one), in plan mm
};

struct SupportReport {
  int supports = 0;      // support strips added, before widening merged any
  int rounds = 0;        // rounds of supports chosen
  int exact_builds = 0;  // exact plans judged by: the slices' own, then one per pass of rounds
  int passes_undone = 0;  // passes of rounds undone because they left no fewer faces invalid
  // The share of the model's pixels in the faces cut out (pieces of the back plane or the floor
  // aside), counted as they are cut; never over a quarter.
  double cut_out_share = 0;
  int round_bound = 0;   // the loop's bound: one round per W-wide column of the sheet, plus one
  int orders = 0;        // face orders tried (SupportOptions::orders); the rest is of the one kept
  bool converged = false;
  std::string stop_reason;  // why supports alone did not make every face stand; empty when they did
  int cut_out = 0;          // faces cut out of the sheet as the last resort
  std::vector<NarrowStrip> narrow;  // faces and supports narrower than W, with their place
};

struct Supported {
  SliceResult slices;  // the raster plan with the supports painted in (RasterFace::support)
  Plan plan;           // the exact plan of it, validated from scratch
  SupportReport report;
};

/// Adds supports until every face of the exact plan is valid (or, with allow_dangling, valid or
/// dangling), or the bound is reached. Deterministic for a given seed.
Supported add_supports(const RasterMaps& maps, SliceResult slices, const Sheet& sheet, const PlanOptions& plan_options,
                       const SupportOptions& options);

/// Every face (holes aside) whose pixels span fewer than W (block_px) columns, in face order.
std::vector<NarrowStrip> narrow_strips(const SliceResult& slices, const PixelGrid& grid);

/// The verdict: no floating or invalid face, and no dangling one unless they are allowed.
bool plan_stands(const Validity& validity, bool allow_dangling);

}  // namespace origamic
