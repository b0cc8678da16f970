// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: where a face narrower than W across a chord ends in a tip (tip_of), found by walking
// across the chord vertex line by vertex line, for the tip repair (tip_repair.cpp).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "exact_kernel.hpp"
#include "plan_analysis_geometry.hpp"

namespace origamic::tips {

using exact::FT;

// A face's boundary edges in (u, v): u across a chord, v along it.
struct UvEdge {
  FT u0, v0, u1, v1;  // u0 < u1
  FT v_at(const FT& u) const { return analysis::crossing_v(u0, v0, u1, v1, u); }
};

// A tip of a face: where the cut across it goes (at u, from v_lo to v_hi) and a point inside it.
struct Tip {
  std::size_t region;
  bool along_Y;
  FT u, v_lo, v_hi;
  FT inside_u, inside_v;
};

// A face's boundary seen across chords along one axis: its edges in (u, v), and the u of its
// vertex lines, sorted, each once.
struct FaceLines {
  std::vector<UvEdge> edges;
  std::vector<FT> us;
};
/// The face's edges and vertex lines across chords along Y (along_Y) or along X.
FaceLines face_lines(const std::vector<analysis::Ring>& rings, bool along_Y);

/// Walks across the chord of a face narrower than W: one way the face must end within `reach`, the
/// other it must widen to `wide`; the tip is cut where it does, or on a vertex line of the face
/// within a hundredth of a millimetre of there where the face is still W wide.
std::optional<Tip> tip_of(const FaceLines& face, std::size_t region, bool along_Y, const analysis::Chord& chord,
                          const FT& W, const FT& wide, const FT& reach);

}  // namespace origamic::tips
