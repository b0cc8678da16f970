// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/placement.hpp"

#include <cmath>
#include <glm/common.hpp>
#include <limits>
#include <numbers>
#include <sstream>

#include "number_text.hpp"
#include "origamic/error.hpp"

namespace origamic {
namespace {

// Columns of glm matrices: m[col][row]. The axis swap takes model axes to OA (x, h, d).
glm::dmat3 axis_swap(UpAxis up) {
  if (up == UpAxis::Y) return glm::dmat3(1.0);
  // OA (x, h, d) = model (x, z, -y): model y goes to -d, model z to h.
  return glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
}

// Right-handed rotation about the up (h) axis: counter-clockwise seen from above.
glm::dmat3 rotation_about_up(double degrees) {
  const double a = degrees * std::numbers::pi / 180;
  const double c = std::cos(a), s = std::sin(a);
  return glm::dmat3(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));
}

struct Extents {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  double lo_Y = std::numeric_limits<double>::infinity();  // of h - d
  double hi_Y = -std::numeric_limits<double>::infinity();
};

Extents extents(const TriangleMesh& mesh, const glm::dmat3& linear, const glm::dvec3& translation) {
  Extents e;
  for (const auto& p : mesh.positions) {
    const glm::dvec3 q = linear * p + translation;
    e.lo = glm::min(e.lo, q);
    e.hi = glm::max(e.hi, q);
    e.lo_Y = std::min(e.lo_Y, q.y - q.z);
    e.hi_Y = std::max(e.hi_Y, q.y - q.z);
  }
  return e;
}

void check_options(const Sheet& sheet, const PlacementOptions& options) {
  if (!(std::isfinite(sheet.width_mm) && std::isfinite(sheet.height_mm) && sheet.width_mm > 0 &&
        sheet.height_mm > 0))
    throw InputError("Sheet", "the sheet must have a positive, finite width and height");
  // Beyond any cutter's bed or printer's page (a wide plotter takes 1.6 m).
  if (sheet.width_mm > 5000 || sheet.height_mm > 5000)
    throw InputError("Sheet", "a side longer than 5000 mm is no card");
  if (!(std::abs(options.rotate_deg) <= 360))
    throw InputError("PlacementOptions::rotate_deg", "must be an angle from -360 to 360 degrees");
  if (options.scale && !(std::isfinite(*options.scale) && *options.scale > 0))
    throw InputError("PlacementOptions::scale", "must be a positive, finite number");
  if (options.offset_mm && !(std::isfinite(options.offset_mm->x) && std::isfinite(options.offset_mm->y) &&
                             std::isfinite(options.offset_mm->z)))
    throw InputError("PlacementOptions::offset_mm", "must be three finite numbers X,H,D in mm");
  if (!(std::isfinite(options.margin_mm) && options.margin_mm >= 0))
    throw InputError("PlacementOptions::margin_mm", "must be a non-negative, finite length in mm");
  if (!options.scale && !options.offset_mm &&
      (2 * options.margin_mm >= sheet.width_mm || options.margin_mm >= sheet.half_height_mm()))
    throw InputError("PlacementOptions::margin_mm", "leaves no room on the sheet for the model");
}

// The largest scale at which extents e (unscaled, resting at h = d = 0) fit inside the margins, with
// the model's height and depth each within half the sheet less the margin.
double fit_scale(const Extents& e, const Sheet& sheet, double margin_mm) {
  const double rest_Y = e.lo.y - e.lo.z;  // h - d of the bounding box corner that goes to the fold
  const double room_X = sheet.width_mm - 2 * margin_mm;
  const double room_half = sheet.half_height_mm() - margin_mm;
  double scale = std::numeric_limits<double>::infinity();
  if (e.hi.x > e.lo.x) scale = std::min(scale, room_X / (e.hi.x - e.lo.x));
  if (e.hi_Y > rest_Y) scale = std::min(scale, room_half / (e.hi_Y - rest_Y));
  if (e.lo_Y < rest_Y) scale = std::min(scale, room_half / (rest_Y - e.lo_Y));
  // Room for supports: a support from height h reaches the back plane at plan Y = h, one from depth
  // d reaches the floor at Y = -d. Models whose highest point stands forward (a ridge, a dome) or
  // whose frontmost point is raised would otherwise fit their projection but leave no room.
  if (e.hi.y > e.lo.y) scale = std::min(scale, room_half / (e.hi.y - e.lo.y));
  if (e.hi.z > e.lo.z) scale = std::min(scale, room_half / (e.hi.z - e.lo.z));
  if (!std::isfinite(scale))
    throw InputError("PlacementOptions::scale", "the model's 45-degree projection has zero extent: give a scale");
  return scale;
}

// A length in a message, to a tenth of a millimetre; one no card could hold (1e9 mm is 1,000 km;
// a model scaled by 1e300 gave 300 digits before the point) in powers of ten.
std::string mm(double v) {
  if (!(std::abs(v) < 1e9)) return number_text(v);
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v;
  return s.str();
}

}  // namespace

Placement place(const TriangleMesh& mesh, const Sheet& sheet, const PlacementOptions& options) {
  check_options(sheet, options);
  const glm::dmat3 rotation = rotation_about_up(options.rotate_deg) * axis_swap(options.up);
  const Extents unscaled = extents(mesh, rotation, glm::dvec3(0.0));

  Placement placement;
  placement.scale = options.scale ? *options.scale : fit_scale(unscaled, sheet, options.margin_mm);
  placement.linear = placement.scale * rotation;
  if (options.offset_mm) {
    placement.translation = *options.offset_mm;
  } else {
    const double s = placement.scale;
    placement.translation = {sheet.width_mm / 2 - s * (unscaled.lo.x + unscaled.hi.x) / 2,
                             -s * unscaled.lo.y, -s * unscaled.lo.z};
  }

  const Extents placed = extents(mesh, placement.linear, placement.translation);
  placement.min_oa = placed.lo;
  placement.max_oa = placed.hi;
  placement.min_plan = {placed.lo.x, placed.lo_Y};
  placement.max_plan = {placed.hi.x, placed.hi_Y};

  // Auto-fit lands exactly on the margin up to rounding (1e-9 mm is far below a pixel).
  constexpr double slack = 1e-9;
  const bool inside = placed.lo.x >= sheet.min_X() - slack && placed.hi.x <= sheet.max_X() + slack &&
                      placed.lo_Y >= sheet.min_Y() - slack && placed.hi_Y <= sheet.max_Y() + slack;
  if (!inside) {
    const std::string option = options.offset_mm && options.scale
                                   ? "PlacementOptions::scale/PlacementOptions::offset_mm"
                               : options.offset_mm ? "PlacementOptions::offset_mm"
                               : options.scale     ? "PlacementOptions::scale"
                                                   : "Sheet/PlacementOptions::margin_mm";
    throw InputError(option, "the model's 45-degree projection (X " + mm(placed.lo.x) + " to " +
                     mm(placed.hi.x) + ", Y " + mm(placed.lo_Y) + " to " + mm(placed.hi_Y) +
                     " mm) leaves the " + mm(sheet.width_mm) + " x " + mm(sheet.height_mm) +
                     " mm sheet (X 0 to " + mm(sheet.max_X()) + ", Y " + mm(sheet.min_Y()) + " to " +
                     mm(sheet.max_Y()) + ")");
  }
  if (placed.lo.y < -slack || placed.lo.z < -slack)
    throw InputError(options.offset_mm ? "PlacementOptions::offset_mm" : "PlacementOptions::scale",
                     "the model reaches below the floor (min h " + mm(placed.lo.y) +
                     " mm) or behind the back plane (min d " + mm(placed.lo.z) + " mm); both must be >= 0");
  return placement;
}

TriangleMesh apply(const Placement& placement, TriangleMesh mesh) {
  const glm::dmat3 rotation = placement.linear / placement.scale;
  for (auto& p : mesh.positions) p = placement.to_oa(p);
  for (auto& n : mesh.corner_normals) n = glm::vec3(rotation * glm::dvec3(n));
  return mesh;
}

}  // namespace origamic
