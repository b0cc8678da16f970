// SPDX-License-Identifier: GPL-3.0-or-later
// Shading normals at the corners of a loaded triangle soup: computed over the faces around each
// vertex within a feature angle, or taken from the file and made unit length.
#include "mesh_normals.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <numeric>
#include <tuple>

namespace origamic {
namespace {

glm::dvec3 face_normal(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const glm::dvec3 n =
      glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
  const double length = glm::length(n);
  return length > 0 ? n / length : glm::dvec3(0.0);
}

// The cosine of the angle at each corner, from the three edges (p1 - p0 is -(p0 - p1) to the bit),
// clamped; 1 (no angle) where an edge has no length.
std::array<double, 3> corner_cosines(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  std::array<glm::dvec3, 3> edge;  // edge k runs from corner k to corner k + 1
  std::array<double, 3> length{};
  for (std::size_t k = 0; k < 3; ++k) {
    edge[k] = mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]];
    length[k] = glm::length(edge[k]);
  }
  std::array<double, 3> cosines{};
  for (std::size_t c = 0; c < 3; ++c) {
    const std::size_t back = (c + 2) % 3;  // the edge into corner c, reversed
    const double la = length[c], lb = length[back];
    cosines[c] = la == 0 || lb == 0 ? 1.0 : std::clamp(-glm::dot(edge[c], edge[back]) / (la * lb), -1.0, 1.0);
  }
  return cosines;
}

// Per vertex, the smallest index of a vertex at exactly its position.
std::vector<std::uint32_t> same_point_ids(const std::vector<glm::dvec3>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto key = [&](std::uint32_t v) {
    const glm::dvec3& p = positions[v];
    return std::tuple(p.x, p.y, p.z, v);
  };
  // The key is a total order (the index breaks ties): any sort gives the same order.
  tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::vector<std::uint32_t> id(positions.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    id[order[i]] = i > 0 && positions[order[i]] == positions[order[i - 1]] ? id[order[i - 1]] : order[i];
  return id;
}

}  // namespace

// Angle-weighted normals per corner over the faces around the corner's vertex whose normal is
// within the feature angle of the corner's own face.
UnfilledVector<glm::vec3> feature_corner_normals(const TriangleMesh& mesh, double feature_angle_deg) {
  // Corners meet at a point, not at a vertex index: a mesh cut along its patch seams (res_teapot:
  // 263 of its 792 vertices repeat another's position) is as smooth across them as within.
  const std::vector<std::uint32_t> point = same_point_ids(mesh.positions);
  const std::size_t n_vertices = mesh.positions.size();
  std::vector<std::uint32_t> first(n_vertices + 1, 0);
  for (const auto& t : mesh.triangles)
    for (auto v : t) ++first[point[v] + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::uint32_t> corners(first.back());
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c)
      corners[fill[point[mesh.triangles[f][static_cast<std::size_t>(c)]]]++] = static_cast<std::uint32_t>(3 * f + c);

  // Each triangle's values depend on nothing written in the same loop: both loops run on all cores,
  // and write every value into arrays left unfilled (res_dragon_full: 73 MB, which zeros would
  // have touched first, on one core).
  UnfilledVector<glm::dvec3> normals(mesh.triangles.size());
  UnfilledVector<double> angles(3 * mesh.triangles.size());
  tbb::parallel_for(std::size_t{0}, mesh.triangles.size(), [&](std::size_t f) {
    normals[f] = face_normal(mesh, mesh.triangles[f]);
    const std::array<double, 3> cosines = corner_cosines(mesh, mesh.triangles[f]);
    for (int c = 0; c < 3; ++c) angles[3 * f + c] = std::acos(cosines[static_cast<std::size_t>(c)]);
  });

  const double cos_feature = std::cos(feature_angle_deg * std::numbers::pi / 180);
  UnfilledVector<glm::vec3> result(3 * mesh.triangles.size());
  tbb::parallel_for(std::size_t{0}, mesh.triangles.size(), [&](std::size_t f) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = point[mesh.triangles[f][static_cast<std::size_t>(c)]];
      glm::dvec3 sum(0.0);
      for (std::uint32_t k = first[v]; k < first[v + 1]; ++k) {
        const std::size_t g = corners[k] / 3;
        if (glm::dot(normals[g], normals[f]) >= cos_feature) sum += angles[corners[k]] * normals[g];
      }
      const double length = glm::length(sum);
      result[3 * f + c] = glm::vec3(length > 0 ? sum / length : normals[f]);
    }
  });
  return result;
}

// File normals may be unnormalised or missing (zero); those corners take their face's normal.
void unit_or_face_normals(TriangleMesh& mesh) {
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::size_t c = 0; c < 3; ++c) {
      glm::vec3& n = mesh.corner_normals[3 * f + c];
      const float length = glm::length(n);
      n = std::isfinite(length) && length > 0 ? n / length : glm::vec3(face_normal(mesh, mesh.triangles[f]));
    }
  }
}

// A file's normals shade across its edges as its author chose: per-vertex normals on a low-poly
// building turn 45-90 degrees away from the walls and roofs they shade (arch_church's 22 vertices,
// arch_water_tower's 30), and across a flat face the normal then sweeps through the view direction,
// which shatters the segmentation (arch_church: 7,205 segments of 25 triangles). A corner normal
// farther than the feature angle from its face's plane takes the computed one, on the side of the
// face the triangle's file normals are on (an inverted file keeps its winding).
void sharpen_file_normals(TriangleMesh& mesh, double feature_angle_deg) {
  const double cos_feature = std::cos(feature_angle_deg * std::numbers::pi / 180);
  UnfilledVector<glm::vec3> computed;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const glm::dvec3 face = face_normal(mesh, mesh.triangles[f]);
    if (face == glm::dvec3(0.0)) continue;  // no area: no plane to be near
    double side = 0;
    bool far = false;
    for (std::size_t c = 0; c < 3; ++c) {
      const double along = glm::dot(glm::dvec3(mesh.corner_normals[3 * f + c]), face);
      side += along;
      far |= std::abs(along) < cos_feature;
    }
    if (!far) continue;
    if (computed.empty()) computed = feature_corner_normals(mesh, feature_angle_deg);
    for (std::size_t c = 0; c < 3; ++c) {
      glm::vec3& n = mesh.corner_normals[3 * f + c];
      if (std::abs(glm::dot(glm::dvec3(n), face)) < cos_feature)
        n = side < 0 ? -computed[3 * f + c] : computed[3 * f + c];
    }
  }
}

}  // namespace origamic
