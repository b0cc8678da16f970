// SPDX-License-Identifier: GPL-3.0-or-later
// Placement: the user's model put into OA space against the back plane and the floor (seed ch. 4,
// "positioning and orientating it with respect to the back and floor planes").
#pragma once

#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "origamic/mesh_io.hpp"
#include "origamic/oa.hpp"

namespace origamic {

enum class UpAxis {
  Y,  // Y up, viewer at +Z (OpenGL, OBJ, PLY): OA (x, h, d) = model (x, y, z)
  Z,  // Z up, viewer at -Y (STL, CAD):          OA (x, h, d) = model (x, z, -y)
};

struct PlacementOptions {
  UpAxis up = UpAxis::Y;                 // which model axis points up
  double rotate_deg = 0.0;               // about the up axis, counter-clockwise seen from above
  std::optional<double> scale;           // mm per model unit; auto-fit to the sheet when empty
  std::optional<glm::dvec3> offset_mm;   // OA (x, h, d) of the model's origin; auto when empty
  double margin_mm = 10.0;               // auto-fit keeps the 45-degree projection this far inside
};

/// The affine map from model coordinates to OA mm: oa = linear * model + translation,
/// where linear = scale * (axis swap and rotation about the up axis).
struct Placement {
  glm::dmat3 linear{1.0};
  glm::dvec3 translation{0.0};
  double scale = 1.0;            // mm per model unit
  glm::dvec3 min_oa{0.0};        // bounding box of the placed model, OA (x, h, d) mm
  glm::dvec3 max_oa{0.0};
  PlanPoint min_plan;            // bounding box of its 45-degree projection on the plan
  PlanPoint max_plan;

  glm::dvec3 to_oa(const glm::dvec3& model) const { return linear * model + translation; }
};

/// Chooses the placement. Auto-fit (no scale, no offset): the largest uniform scale at which the
/// model's 45-degree projection lies inside the sheet less the margin, standing on the floor
/// (min h = 0), touching the back plane (min d = 0), centred along the fold. An explicit scale keeps
/// the automatic position; an explicit offset places the model's origin there.
/// \pre mesh has at least one position, all finite.
/// \throws InputError naming the option if the options are absurd (non-finite, non-positive scale,
///         negative margin, a margin that leaves no room) or the projection leaves the sheet.
Placement place(const TriangleMesh& mesh, const Sheet& sheet, const PlacementOptions& options);

/// The mesh moved into OA space: positions mapped, normals rotated.
TriangleMesh apply(const Placement& placement, TriangleMesh mesh);

}  // namespace origamic
