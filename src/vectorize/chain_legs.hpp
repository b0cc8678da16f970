// SPDX-License-Identifier: GPL-3.0-or-later
// Internal to the vectorize stage: a traced chain's straight start at one of its ends (its leg), which
// the drawing of chains (chain_points.cpp) and the moves of their junctions (junction_moves.cpp)
// both read. No CGAL here.
#pragma once

#include <cstdint>
#include <optional>

#include "boundary_chains.hpp"
#include "chain_points.hpp"

namespace origamic::chains {

// Two legs meet in a junction only if they cross at 15 degrees or more: nearly parallel legs (one
// edge of the model on both sides of the main fold) place it poorly.
inline constexpr double kLegMinSine = 0.25;

// A junction moves at most this far: the model's edge passes within half a pixel of every
// refined point, and the junction's corner within a pixel's diagonal of the edges' meeting point.
inline constexpr double kJunctionMove_px = 1.0;

// A chain's straight start from one of its ends.
struct Leg {
  double X, Y;    // a point of the line
  double dx, dy;  // its unit direction
  bool on_break;  // the line is the model's edge; otherwise a lattice line through `through`
  LatticePoint through;
  std::int32_t fold_chain = -1;  // the line is this chain's fold line (it snaps onto it there)
};

// The chain's leg at its front (or back): its first edges along one lattice line, or else their
// points on the picture's break, if they lie on one line (a model edge).
// Past up to `lattice_edges` edges at the end off the break (a level contour stays on the pixel edges
// within a pixel of a third face), the leg is the run on the break after them.
std::optional<Leg> leg_of(const Chain& chain, bool front, const LatticeScale& lattice, const PictureBreaks& breaks,
                          std::size_t lattice_edges = 0);

// Whether two lattice points are one; whether a chain closes on itself (no junctions); whether it
// is a single pixel edge (its junctions one place on the model's edge).
bool same(LatticePoint a, LatticePoint b);
bool is_loop(const Chain& chain);
inline bool is_short(const Chain& chain) { return chain.corners.size() < 3; }

}  // namespace origamic::chains
