// SPDX-License-Identifier: GPL-3.0-or-later
// The 3D pop-up (seed §2.1, eq. 2.1-2.2, taken to any opening angle): the plan's faces folded into
// the card as it stands at an angle between closed and flat, as a triangle mesh for viewers and
// pictures.
//
// The mechanism. With e_x along the main fold, b the unit vector up the back half and f the unit
// vector out along the floor half, at the opening angle θ between b and f, a plan point (X, Y) of
//   a V face at depth d has h = Y + d,
//   an H face at height h has d = h - Y,
// and lands at  X e_x + h b + d f.
// At θ = 90 this is the OA point (x, h, d); at θ = 180 (b = -f) it is X e_x + Y b, the flat sheet.
// Within a V face d is fixed, so a plan step (ΔX, ΔY) moves the point by ΔX e_x + ΔY b; within an
// H face h is fixed and the step is ΔX e_x - ΔY f. As e_x is a unit vector orthogonal to the unit
// vectors b and f, both have length sqrt(ΔX² + ΔY²): every face moves rigidly, V faces parallel to
// the back half, H faces parallel to the floor half, at every angle. On the fold Y = h - d between
// V(d) and H(h) both rules give the same height and depth, so the faces stay joined along it.
//
// The world frame is OA space at 90 degrees and the floor half never moves: x along the main fold
// (right), y up, z towards the viewer (right-handed, y up as OBJ viewers expect), in mm:
//   e_x = (1, 0, 0),  f = (0, 0, 1),  b = (0, sin θ, cos θ).
// The floor half lies on y = 0 with z >= 0; the back half stands on the x axis (the main fold),
// upright at 90 degrees, lying on the floor half at 0 and flat behind it (z <= 0) at 180, where the
// plan point (X, Y) lands at (X, 0, -Y).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "origamic/oa.hpp"
#include "origamic/output.hpp"
#include "origamic/plan_regions.hpp"
#include "origamic/validity.hpp"

namespace origamic {

struct FoldOptions {
  double angle_deg = 90.0;    // opening angle between back and floor half: 0 closed, 90 standing, 180 flat
  double thickness_mm = 0.0;  // paper: 0 gives zero-thickness sheets, more a slab behind each face's printed side
};

/// The card's unit vectors in the world frame at an opening angle (exact at 0, 90 and 180 degrees).
struct CardFrame {
  glm::dvec3 e_x{1, 0, 0};    // along the main fold
  glm::dvec3 b{0, 1, 0};      // up the back half
  glm::dvec3 f{0, 0, 1};      // out along the floor half
  glm::dvec3 n_back{0, 0, 1};   // printed side of the back half and every V face: e_x × b
  glm::dvec3 n_floor{0, 1, 0};  // printed side of the floor half and every H face: f × e_x
};
CardFrame card_frame(double angle_deg);

/// Where plan point p of a face of the given orientation and depth (d of a V face, h of an H face)
/// lands on the printed side of the card opened to `frame`, in world mm.
glm::dvec3 fold_point(const CardFrame& frame, PlanPoint p, Orientation orientation, double depth_mm);

/// Which surface of the paper a triangle lies on.
enum class PaperSurface : std::uint8_t {
  Printed,  // the side the pop-up stands on (towards the viewer on the back half, up on the floor)
  Reverse,  // the other side, thickness_mm behind it (only when thickness_mm > 0)
  Edge,     // the cut edge between them (only when thickness_mm > 0)
};

/// What a renderer or a mesh file needs to know about a region.
struct FoldedRegion {
  Orientation orientation = Orientation::V;
  double depth_mm = 0;   // d of a V face, h of an H face
  FaceStatus status = FaceStatus::Valid;
};

/// The folded card: one triangulated patch per region, in world mm. Without thickness the patches
/// are one sheet: the two faces of a fold share its vertices; elsewhere (cuts) they share none.
struct FoldedPopup {
  Sheet sheet;
  FoldOptions options;
  std::vector<glm::dvec3> positions;
  std::vector<PlanPoint> plan_points;                    // per position: the plan point it comes from
  std::vector<std::int32_t> position_region;             // per position: the region that made it (a
                                                         // vertex on a fold serves the face across it too)
  std::vector<std::array<std::uint32_t, 3>> triangles;   // counter-clockwise seen from outside the paper
  std::vector<std::int32_t> triangle_region;             // per triangle: index into `regions`
  std::vector<PaperSurface> triangle_surface;            // per triangle
  std::vector<FoldedRegion> regions;                     // one per input region, in input order
  int empty_regions = 0;          // regions whose rings enclose no area (no triangles)
  int unplaced_regions = 0;       // regions left out: the folds give them no orientation and depth
  int split_vertices = 0;         // vertices copied where a region touches itself at a point
};

/// Folds the regions into the card opened to options.angle_deg. Regions not `placed` are left out
/// (they have no triangles; the count says how many). Each region's rings are
/// triangulated in the plan (a constrained Delaunay triangulation, inside by nesting depth: even-odd
/// over the rings, so holes may come in either direction) and every vertex is mapped by fold_point;
/// without thickness, a vertex on a fold is made once, by the first of its two faces.
/// Printed-side triangles keep the plan's counter-clockwise order, so their normals point to the
/// printed side (n_back for V, n_floor for H). With thickness_mm > 0 each region is also copied
/// thickness_mm behind its printed side (reversed) and closed by edge quads along its boundary. At a
/// fold (a horizontal edge the region shares with a placed region of the other orientation) the
/// reverse side is mitred: it ends where the two faces' reverse planes meet, so the two slabs meet
/// on the plane bisecting the fold without overlap or gap. The mitre is held at twice the thickness,
/// which is exact for folds opened 53 degrees or more (every fold between 53 and 127 degrees).
/// \throws InputError naming the option for an angle outside [0, 180] or a thickness outside
///         [0, 10] mm, and naming the region for a non-finite coordinate.
FoldedPopup fold_popup(const std::vector<PlanRegion>& regions, const Sheet& sheet, const FoldOptions& options);

enum class MeshFormat : std::uint8_t {
  Obj,   // Wavefront OBJ with a material library (one material per colour) beside it
  Ply,   // binary little-endian PLY with a colour per face
  Gltf,  // glTF 2.0 JSON with its buffer embedded, a material per colour, in metres (glTF's unit)
  Glb,   // the same glTF 2.0 asset as one binary file
};

/// An 8-bit sRGB colour.
struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// The colour a folded region gets in mesh files and pictures. Paper colours: V faces white, H faces
/// cream, the back plane and the floor (depth 0) a shade darker, edges of a slab grey-brown; faces
/// that do not stand (floating, dangling, invalid) pink when `mark_unsupported`.
Rgb8 paper_colour(const FoldedRegion& region, PaperSurface surface, bool mark_unsupported);

/// The paper colour of the popup's triangle t: its region's, on its surface.
Rgb8 triangle_colour(const FoldedPopup& popup, std::size_t t, bool mark_unsupported);

/// The mesh files of a folded pop-up, written by OpenMesh's IO, each triangle in its paper colour
/// (faces that do not stand marked): for Obj, `path` and the material library OpenMesh writes beside
/// it (same stem, extension ".mat", named by the OBJ's mtllib line); for Ply, `path` alone.
/// Positions are in world mm, in single precision (OpenMesh writes floats). Gltf and Glb are
/// written by tinygltf, `path` alone, in metres as glTF requires; the asset's extras name the
/// opening angle, the paper thickness and the sheet in mm.
/// \throws OutputError naming path if OpenMesh or tinygltf cannot write the mesh.
std::vector<OutputFile> folded_mesh_files(const FoldedPopup& popup, const std::filesystem::path& path,
                                          MeshFormat format);

}  // namespace origamic
