// SPDX-License-Identifier: GPL-3.0-or-later
// The coordinate conventions every stage relies on (seed §2.1, eq. 2.1-2.2).
//
// OA space, in mm, of the card opened at 90 degrees:
//   x  along the main fold, from the sheet's left edge;
//   h  height above the floor plane (h >= 0 is above the floor);
//   d  depth in front of the back plane (d >= 0 is in front of it, towards the viewer).
// (x, h, d) is right-handed: x right, h up, d towards the viewer. A glm::dvec3 holding an OA point
// stores (x, h, d) in (.x, .y, .z).
//
// Plan space, in mm, of the flat sheet:
//   X = x,  Y = h - d.
// The main fold is Y = 0, the back plane is Y >= 0 and the floor Y <= 0. Every point of the 90-degree
// pop-up on the 45-degree line {(X, Y + t, t) : t >= 0} lands on the same plan point (X, Y).
//
// Faces are V (parallel to the back plane, constant d) or H (parallel to the floor, constant h);
// the fold between V(d) and H(h) lies on Y = h - d.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>

namespace origamic {

/// The flat card: width along the main fold, height across it; the main fold halves the height.
struct Sheet {
  double width_mm = 210.0;   // along the main fold (X)
  double height_mm = 297.0;  // across the main fold (Y), back plane and floor half each

  double half_height_mm() const { return height_mm / 2; }
  double min_X() const { return 0.0; }
  double max_X() const { return width_mm; }
  double min_Y() const { return -half_height_mm(); }
  double max_Y() const { return half_height_mm(); }
};

/// The two kinds of face.
enum class Orientation : std::uint8_t {
  V,  // parallel to the back plane, at constant depth d
  H,  // parallel to the floor, at constant height h
};

/// A point of the plan, in mm.
struct PlanPoint {
  double X = 0;
  double Y = 0;
  bool operator==(const PlanPoint&) const = default;
};

/// The plan point of an OA point (x, h, d): (x, h - d).
inline PlanPoint plan_of(const glm::dvec3& oa) { return {oa.x, oa.y - oa.z}; }

/// The fold line Y = h - d between a V face and an H face, given either first: face a of orientation
/// a_is and depth depth_a (d of a V face, h of an H face), face b of the other orientation and
/// depth_b. Doubles give the IEEE difference (one rounding); exact numbers give it exactly.
template <typename Depth>
Depth fold_line_Y(Orientation a_is, const Depth& depth_a, const Depth& depth_b) {
  return a_is == Orientation::H ? depth_a - depth_b : depth_b - depth_a;
}

/// The 45-degree key h + d of a face's plane at plan height Y: a V face at depth d holds h = Y + d
/// there, an H face at height h holds d = h - Y (depth_mm is d of a V face, h of an H face).
inline double key_of_plane(Orientation orientation, double depth_mm, double Y) {
  return orientation == Orientation::V ? Y + 2 * depth_mm : 2 * depth_mm - Y;
}

/// The key the 45-degree view sees at plan height Y of a face in this plane: the plane's, or
/// through a hole (a face cut out) the plane the card would be there: the back plane above the main
/// fold, the floor below, |Y| either way.
inline double shown_key(Orientation orientation, double depth_mm, bool hole, double Y) {
  return hole ? std::abs(Y) : key_of_plane(orientation, depth_mm, Y);
}

/// Whether a face's plane is on the card at plan height Y: a V face at depth d above the floor's
/// fold with it (Y >= -d), an H face at height h before the back plane's (Y <= h).
inline bool on_card(Orientation orientation, double depth_mm, double Y) {
  return orientation == Orientation::V ? Y >= -depth_mm : Y <= depth_mm;
}

}  // namespace origamic
