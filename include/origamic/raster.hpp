// SPDX-License-Identifier: GPL-3.0-or-later
// Raster extraction (seed §4.1): the placed model, the back plane and the floor seen along the
// 45-degree direction, one orthographic ray per plan pixel centre, traced with Embree.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>

#include "origamic/grid.hpp"
#include "origamic/mesh_io.hpp"
#include "origamic/oa.hpp"

namespace origamic {

/// The plan's pixel lattice. Pixels are squares of 1/px_per_mm mm; row 0 is at the top (largest Y)
/// and the main fold Y = 0 is a row boundary; pixel centres past the sheet's edge are outside it.
struct PixelGrid {
  int cols = 0;
  int rows = 0;
  double px_per_mm = 4.0;
  int rows_above_fold = 0;  // rows whose centres have Y > 0

  double X(int col) const { return (col + 0.5) / px_per_mm; }
  double Y(int row) const { return (rows_above_fold - row - 0.5) / px_per_mm; }

  /// The lattice covering a sheet at a resolution.
  static PixelGrid covering(const Sheet& sheet, double px_per_mm);
};

enum class HitKind : std::uint8_t {
  Back = 0,     // the back plane, d = 0 (Y >= 0)
  Floor = 1,    // the floor, h = 0 (Y < 0)
  Model = 2,    // the model
  Outside = 3,  // the pixel centre is beyond the sheet's edge
};

/// The reference planes of the normalised depths (§4.1): a vertical plane in front of everything
/// and a horizontal plane above everything, both at least half a sheet away.
struct DepthReference {
  double front_d_mm = 0;  // F = (front_d - d) / front_d
  double top_h_mm = 0;    // T = (top_h - h) / top_h
  double diag_mm = 0;     // D = (diag - (h + d)) / diag: the 45-degree depth
};

/// Maps with direct pixel correspondence in plan space (§4.1). On Outside pixels values are unset.
struct RasterMaps {
  PixelGrid grid;
  DepthReference reference;
  Grid<HitKind> kind;
  Grid<double> d_mm;                // depth in front of the back plane
  Grid<double> h_mm;                // height above the floor; h - d = Y of the pixel centre
  Grid<glm::vec3> normal;           // unit shading normal, OA axes; design() drops it after slicing
                                    // unless DesignOptions::keep_normals
  // Where the model's picture breaks between two neighbouring pixel centres (its silhouette against
  // the back plane or floor, one surface passing in front of another, or a sharp crease of its
  // surface): the fraction of the way from the first centre to the second, to 1/1024, found by
  // bisection with rays between them; NaN where it does not break. Empty if not traced (maps made
  // by hand).
  Grid<float> break_right;  // between (col, row) and (col + 1, row)
  Grid<float> break_below;  // between (col, row) and (col, row + 1)
  std::size_t model_pixels = 0;
};

/// The normalised depths of §4.1, each 0 nearest the viewer and 1 furthest.
struct NormalisedDepths {
  Grid<float> D;  // 45-degree depth
  Grid<float> F;  // front depth: constant on V faces
  Grid<float> T;  // top depth: constant on H faces
};
/// The maps' normalised depths, from their d, h and reference planes (1 on Outside pixels): for the
/// pictures of --dump-maps. \pre kind, d_mm and h_mm are one size.
NormalisedDepths normalised_depths(const RasterMaps& maps);

struct RasterOptions {
  double px_per_mm = 4.0;  // plan resolution; 4 gives about 1 Mpx on an A4 sheet
};

/// An Embree scene of a mesh in OA space, built once and queried by raster() and later renders.
class RayScene {
 public:
  /// Builds the BVH. \pre mesh is in OA mm, finite.
  explicit RayScene(TriangleMesh oa_mesh);
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;

  const TriangleMesh& mesh() const;
  glm::dvec3 min_oa() const;
  glm::dvec3 max_oa() const;

  struct Impl;

 private:
  friend RasterMaps raster(const RayScene&, const Sheet&, const RasterOptions&);
  std::unique_ptr<Impl> impl_;
};

/// Traces one 45-degree ray per pixel centre, in parallel over rows; the output does not depend on
/// the thread count. d and h of model pixels are recomputed in double precision on the triangle
/// Embree hit, so an axis-parallel face yields its exact depth or height.
/// \throws InputError if px_per_mm is not positive and finite or the grid would be absurdly large.
RasterMaps raster(const RayScene& scene, const Sheet& sheet, const RasterOptions& options);

}  // namespace origamic
