// SPDX-License-Identifier: GPL-3.0-or-later
// The exact arrangement drawn from the raster plan's traced boundary chains: cuts simplified or
// drawn on the model's edges, folds snapped onto their lines, junctions moved where lines meet
// (§4.5). Include after defining CGAL_HAS_NO_THREADS (see exact_kernel.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "boundary_chains.hpp"
#include "chain_points.hpp"
#include "exact_plan_state.hpp"
#include "origamic/oa.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic::exact {

// The lattice's points (boundary_chains.hpp), exactly. Exact coordinates clamp to the sheet, whose
// edge the last pixels may overhang.
// They are made once per lattice line and shared by the points on it (fewer lazy numbers to make
// and free).
struct Lattice : chains::LatticeScale {
  std::vector<FT> X_of_u, Y_of_v;
  double half_mm;
  chains::PictureBreaks breaks;

  // `lines`: where chains cross pixel edges, the picture's breaks and the levels (level_contours.hpp).
  Lattice(const RasterMaps& maps, const Sheet& sheet, chains::PictureBreaks lines)
      : LatticeScale{maps.grid.rows_above_fold, 1 / maps.grid.px_per_mm},
        half_mm(sheet.half_height_mm()),
        breaks(lines) {
    const PixelGrid& grid = maps.grid;
    const FT two_ppm = FT(2) * FT(grid.px_per_mm), width(sheet.width_mm), half(sheet.half_height_mm());
    for (int u = 0; u <= 2 * grid.cols; ++u) X_of_u.push_back(CGAL::min(FT(u) / two_ppm, width));
    for (int v = 0; v <= 2 * grid.rows; ++v)
      Y_of_v.push_back(CGAL::max(CGAL::min(FT(2 * rows_above_fold - v) / two_ppm, half), -half));
  }

  Point exact(int u, int v) const { return {X_of_u[static_cast<std::size_t>(u)], Y_of_v[static_cast<std::size_t>(v)]}; }
  // A point off the lattice, from its doubles, but on a lattice line exactly where u (v) is >= 0.
  Point exact(double X, double Y, int u, int v) const {
    return {u >= 0 ? X_of_u[static_cast<std::size_t>(u)] : FT(X), v >= 0 ? Y_of_v[static_cast<std::size_t>(v)] : FT(Y)};
  }
};

// How much of the vectorization a chain keeps: a chain that crossed another is first left
// unsimplified, then also unsnapped (its pixel contour, which crosses nothing).
enum class Fallback : std::uint8_t { None, Unsimplified, PixelContour };

// What the arrangement is built of: the traced chains, the faces on their sides, the lattice, the
// sheet and the tolerances.
struct ArrangementInput {
  const std::vector<chains::Chain>& chains;
  const std::vector<RasterFace>& faces;
  const Lattice& lattice;
  const Sheet& sheet;
  double simplify_mm;
  double fold_tolerance;
};

// How far each chain fell back, how many still cross on their contour, and the chains drawn
// unsimplified, for the next plan of the run (ChainFallbacks).
struct ArrangementFallbacks {
  std::vector<Fallback> fallback;
  int unresolved = 0;
  ChainFallbacks passed_on;  // to the run's next plan
};

// Simplification or snapping that makes two boundaries cross would change the plan's topology:
// the chains involved fall back a step (unsimplified, then their pixel contour) until none does.
// The chains `known` start unsimplified.
ArrangementFallbacks arrangement_without_crossings(const ArrangementInput& in, const ChainFallbacks& known,
                                                   Built& built);

}  // namespace origamic::exact
