// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh input: OBJ, STL (ASCII and binary), PLY and OFF through OpenMesh, each optionally gzipped.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "origamic/unfilled_vector.hpp"

namespace origamic {

/// A triangle soup with per-corner shading normals. Coordinates are in the file's units and axes
/// until placement maps them to OA space.
struct TriangleMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Unit shading normal at each triangle corner (3 per triangle, in triangle order), or empty.
  /// Its resize leaves new normals unwritten (UnfilledVector): write each.
  UnfilledVector<glm::vec3> corner_normals;
};

struct LoadOptions {
  // Where the file has no normals they are averaged over the faces around a corner, but only over
  // faces within this angle of the corner's face, so sharp edges stay sharp. 40 degrees keeps a
  // 16-gon cylinder (22.5 degrees) smooth and a box (90 degrees) sharp.
  double feature_angle_deg = 40.0;
};

/// What was read, for the report.
struct LoadedMesh {
  TriangleMesh mesh;
  std::string format;            // "obj", "stl", "ply" or "off"
  bool gzipped = false;
  bool file_normals = false;     // normals came from the file rather than being computed
  std::size_t faces_dropped = 0;  // faces with a corner repeated (no area): read past, counted here
};

/// Reads a mesh; polygons are triangulated, many-part, open and non-manifold meshes are kept whole.
/// \throws InputError (one line naming the file) if it is missing or unreadable, of an unknown
///         format, unparseable or truncated, has no faces, has a non-finite coordinate or has zero
///         extent.
LoadedMesh load_mesh(const std::filesystem::path& file, const LoadOptions& options = {});

/// The lower-case format name of a path ("stl" for "x.STL.gz"), or "" if not one we read.
std::string mesh_format_of(const std::filesystem::path& file);

}  // namespace origamic
