// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the corner normals of a loaded triangle soup (mesh_io.cpp reads the soup).
#pragma once

#include <glm/vec3.hpp>

#include "origamic/mesh_io.hpp"

namespace origamic {

/// Unit normals at each triangle corner (3 per triangle, in triangle order): the mean, weighted by
/// corner angle, of the normals of the faces around the corner's vertex that lie within
/// feature_angle_deg of the corner's own face, so sharp edges stay sharp. Where that mean is zero
/// the corner takes its face's normal.
UnfilledVector<glm::vec3> feature_corner_normals(const TriangleMesh& mesh, double feature_angle_deg);

/// Makes the file's corner normals in mesh.corner_normals unit length; a zero or non-finite one takes
/// its face's normal. \pre mesh.corner_normals holds 3 normals per triangle.
void unit_or_face_normals(TriangleMesh& mesh);

/// Replaces each unit file normal in mesh.corner_normals that lies farther than feature_angle_deg
/// from its face's plane normal (either side) by feature_corner_normals', turned to the side of the
/// face its triangle's file normals are on. \pre unit corner normals, 3 per triangle.
void sharpen_file_normals(TriangleMesh& mesh, double feature_angle_deg);

}  // namespace origamic
