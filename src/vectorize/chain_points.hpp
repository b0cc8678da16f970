// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: where a traced chain's points are drawn. On the pixel lattice, simplified; or, where the
// model's picture breaks across the chain's pixel edges (its silhouette, one surface in front of
// another, a crease: RasterMaps::break_right and break_below), on the model's edge itself, with the
// junctions and corners where such edges meet other lines moved to where they meet. No CGAL here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "boundary_chains.hpp"
#include "origamic/grid.hpp"

namespace origamic::chains {

/// A junction or fold end moved less than this onto the model's edge stays on its corner: the
/// rays' float rounding (about 3e-5 mm on the house) would leave a sliver beside it.
inline constexpr double kLeastMove_mm = 1e-3;

/// Runs of fewer pixel edges on the picture's breaks are not drawn on them (see simplified), nor
/// continued where the rays see no edge (breaks_and_levels). Drawing every break left prim_cylinder
/// 24 places narrower than W where the lattice left 9 (its 22.5-degree creases touched by slices'
/// ends); on the 37 models runs of 4, 8 and 16 leave 6,152, 6,129 and 6,130 (the lattice 6,060).
inline constexpr std::size_t kMinBreakRun = 8;

/// Where the model's picture breaks between neighbouring pixel centres (RasterMaps::break_right and
/// break_below): empty grids if not known.
struct PictureBreaks {
  const Grid<float>& right;
  const Grid<float>& below;
};

/// A point of a simplified chain: a lattice point, or an edge's midpoint moved across the edge onto
/// the model's break (plan mm).
struct ChainPoint {
  LatticePoint lattice;
  bool on_break = false;
  double X = 0, Y = 0;  // where on_break
  // A corner where a run on the model's edge meets a straight lattice run, moved onto the edge: on
  // the lattice run's line exactly (its X is the lattice's X(u), or its Y the lattice's Y(v)).
  int on_lattice_u = -1, on_lattice_v = -1;
};

/// Where the chain's straight start on the picture's break at its front (or back) end crosses the
/// plan line Y: a model edge meeting a fold there. Only within two pixels of that end's corner.
/// \pre the chain has at least 2 corners.
std::optional<double> leg_meets_line(const Chain& chain, bool front, double Y, const LatticeScale& lattice,
                                     const PictureBreaks& breaks);

/// Where a chain's end corners are drawn if their junctions moved (moved_junctions).
using MovedEnds = std::array<std::optional<std::array<double, 2>>, 2>;

struct DrawnChain {
  std::vector<ChainPoint> points;
  double off_edge_mm = 0;  // the farthest the drawing passes from the chain's points on the model's edge
};

/// How far a simplified chain may pass from its points.
struct DrawTolerance {
  double lattice_mm = 0;  // points on the lattice; <= 0: the chain's own corners
  double break_mm = 0;    // points moved onto the picture's breaks
};

/// Douglas-Peucker over the chain's edge midpoints between its two fixed end corners: a midpoint
/// whose pixel edge the picture breaks across, in a run of 8 or more such edges, is moved onto the
/// break and kept within `tolerance.break_mm` of the result, any other within
/// `tolerance.lattice_mm`. Where such a run meets a straight lattice run, the corner between them
/// moves to where their lines meet and is kept. Ends whose junctions moved are measured where they
/// moved to, and a midpoint beyond such an end (its last pixel edge ran past where the model edge
/// meets the other line) is dropped. A loop whose first pixel edge is on the picture's break starts
/// and ends on that edge's point: no junction holds its first corner. `tolerance.lattice_mm` <= 0
/// gives the chain's pixel contour, each straight run one segment.
/// \pre the chain has at least 2 corners.
DrawnChain simplified(const Chain& chain, const LatticeScale& lattice, const PictureBreaks& breaks,
                      DrawTolerance tolerance, const MovedEnds& moved_ends = {});

/// A junction moved off the lattice onto the model's edge: where a chain on the picture's break
/// meets another boundary's line (another such chain, or a straight run along the lattice, on which
/// it stays exactly: its coordinate across the run is the lattice's).
struct MovedJunction {
  LatticePoint corner;
  double X = 0, Y = 0;
  int u_on_lattice = -1, v_on_lattice = -1;  // X is the lattice's X(u) (Y its Y(v)) where >= 0
  std::int32_t on_fold_of = -1;              // Y is this chain's fold line, exactly, where >= 0
};

/// What a chain's ends allow its junctions: none moves if `pinned` (the chain keeps its raster
/// contour); an end that snaps onto the chain's fold line (at plan Y) moves only along that line.
struct ChainEnds {
  bool pinned = false;
  // A support's side ends here (W wide on the lattice): a leg on a level contour does not reach
  // past the contour's last pixel edges (junction_moves.cpp), which tilted the support.
  bool beside_support = false;
  std::array<std::optional<double>, 2> fold_Y = {};  // front, back
};

struct JunctionMoves {
  std::vector<MovedJunction> moved;
  std::vector<bool> collapsed;  // per chain: a short chain whose ends moved to one point: no line
};

/// Junctions moved less than a pixel: those that chains on breaks place on the model's edge (a level
/// contour's leg taken past the two pixel edges it keeps on the lattice beside a third face, except
/// where a support's side ends), and those that folds snapping there place on their line. Junctions joined by chains of
/// one pixel edge move as one, to one point, and those chains vanish. A straight run down a lattice column whose one
/// end moved across it takes its other end along the fold line that end lies on, as far. A junction of one corner that
/// no model edge passes, where the chains that snap onto their folds all snap onto one line, moves square onto that
/// line; a straight run along a lattice row from a junction moved onto a fold's line takes its other junction onto that
/// line too, square. Nothing moves where the picture's breaks are not known. `ends` has each chain's rule for its ends.
/// \pre ends.size() == chains.size().
JunctionMoves moved_junctions(const std::vector<Chain>& chains, const LatticeScale& lattice,
                              const PictureBreaks& breaks, const std::vector<ChainEnds>& ends);

}  // namespace origamic::chains
