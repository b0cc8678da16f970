// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/raster.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "embree_scene.hpp"
#include "origamic/error.hpp"

namespace origamic {

struct RayScene::Impl {
  TriangleMesh mesh;
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
  std::unique_ptr<EmbreeScene> embree;
};

RayScene::RayScene(TriangleMesh oa_mesh) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.mesh = std::move(oa_mesh);
  s.lo = glm::dvec3(std::numeric_limits<double>::infinity());
  s.hi = -s.lo;
  for (const auto& p : s.mesh.positions) {
    s.lo = glm::min(s.lo, p);
    s.hi = glm::max(s.hi, p);
  }

  if (s.mesh.corner_normals.size() != 3 * s.mesh.triangles.size()) {
    // A mesh made in code may come without shading normals: use each face's own.
    s.mesh.corner_normals.clear();
    for (const auto& t : s.mesh.triangles) {
      const glm::dvec3& a = s.mesh.positions[t[0]];
      const glm::vec3 n(glm::normalize(glm::cross(s.mesh.positions[t[1]] - a, s.mesh.positions[t[2]] - a)));
      s.mesh.corner_normals.insert(s.mesh.corner_normals.end(), 3, n);
    }
  }

  s.embree = std::make_unique<EmbreeScene>(s.mesh.positions, s.mesh.triangles, RTC_BUILD_QUALITY_LOW);
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;
const TriangleMesh& RayScene::mesh() const { return impl_->mesh; }
glm::dvec3 RayScene::min_oa() const { return impl_->lo; }
glm::dvec3 RayScene::max_oa() const { return impl_->hi; }

PixelGrid PixelGrid::covering(const Sheet& sheet, double px_per_mm) {
  PixelGrid grid;
  grid.px_per_mm = px_per_mm;
  grid.cols = static_cast<int>(std::ceil(sheet.width_mm * px_per_mm - 1e-9));
  grid.rows_above_fold = static_cast<int>(std::ceil(sheet.half_height_mm() * px_per_mm - 1e-9));
  grid.rows = 2 * grid.rows_above_fold;
  return grid;
}

namespace {

struct Hit {
  double h = 0;
  double d = 0;
};

// The point (X, Y + d, d) of the 45-degree line through plan point (X, Y) on the plane of triangle
// abc, in double precision. Axis-parallel faces return their coordinate untouched, so a V face's d
// and an H face's h are exactly the mesh's.
Hit intersect_exactly(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double X, double Y,
                      double fallback_d) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  if (n.x == 0 && n.y == 0) return {Y + a.z, a.z};
  if (n.x == 0 && n.z == 0) return {a.y, a.y - Y};
  const double denominator = n.y + n.z;
  if (denominator == 0) return {Y + fallback_d, fallback_d};  // parallel to the ray: a grazing hit
  const double na = glm::dot(n, a);
  if (std::abs(n.y) >= std::abs(n.z)) {
    const double h = (na - n.x * X + n.z * Y) / denominator;
    return {h, h - Y};
  }
  const double d = (na - n.x * X - n.y * Y) / denominator;
  return {Y + d, d};
}

void check_options(const Sheet& sheet, const RasterOptions& options) {
  if (!(std::isfinite(options.px_per_mm) && options.px_per_mm > 0))
    throw InputError("RasterOptions::px_per_mm", "must be a positive, finite number");
  const double cols = sheet.width_mm * options.px_per_mm, rows = sheet.height_mm * options.px_per_mm;
  if (!(cols >= 1 && rows >= 2))
    throw InputError("RasterOptions::px_per_mm",
                     std::to_string(options.px_per_mm) + " gives less than one pixel across the sheet");
  const double pixels = cols * rows;
  constexpr double max_pixels = 64e6;  // the maps take about 45 bytes a pixel: 3 GB at most
  if (!(pixels <= max_pixels))
  {
    char text[160];
    std::snprintf(text, sizeof text, "%g gives %.3g Mpx on this sheet; at most 64 Mpx are allowed", options.px_per_mm,
                  pixels / 1e6);
    throw InputError("RasterOptions::px_per_mm", text);
  }
}

}  // namespace

RasterMaps raster(const RayScene& scene, const Sheet& sheet, const RasterOptions& options) {
  check_options(sheet, options);
  const RayScene::Impl& s = *scene.impl_;
  RasterMaps maps;
  maps.grid = PixelGrid::covering(sheet, options.px_per_mm);
  const int cols = maps.grid.cols, rows = maps.grid.rows;
  maps.kind = Grid<HitKind>(cols, rows, HitKind::Outside);
  maps.d_mm = Grid<double>(cols, rows, std::numeric_limits<double>::quiet_NaN());
  maps.h_mm = Grid<double>(cols, rows, std::numeric_limits<double>::quiet_NaN());
  maps.D = Grid<float>(cols, rows, 1.0f);
  maps.F = Grid<float>(cols, rows, 1.0f);
  maps.T = Grid<float>(cols, rows, 1.0f);
  maps.normal = Grid<glm::vec3>(cols, rows, glm::vec3(0.0f));
  maps.primitive = Grid<std::int32_t>(cols, rows, -1);

  const double half = sheet.half_height_mm();
  const bool empty = s.mesh.positions.empty();
  maps.reference.front_d_mm = std::max(half, empty ? 0.0 : s.hi.z);
  maps.reference.top_h_mm = std::max(half, empty ? 0.0 : s.hi.y);
  maps.reference.diag_mm = maps.reference.front_d_mm + maps.reference.top_h_mm;
  const DepthReference ref = maps.reference;
  // Rays start on the vertical plane d = start_d, in front of the model and of the floor's edge.
  const double start_d = ref.front_d_mm + 1.0;

  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int row = range.begin(); row != range.end(); ++row) {
      const double Y = maps.grid.Y(row);
      if (Y < sheet.min_Y() || Y > sheet.max_Y()) continue;
      for (int col = 0; col < cols; ++col) {
        const double X = maps.grid.X(col);
        if (X > sheet.max_X()) continue;
        // Along the ray (X, Y + start_d - t, start_d - t) the back plane d = 0 is reached at
        // t = start_d when Y >= 0, the floor h = 0 at t = start_d + Y when Y < 0.
        const double t_plane = Y >= 0 ? start_d : start_d + Y;
        RTCRayHit ray{};
        ray.ray.org_x = static_cast<float>(X);
        ray.ray.org_y = static_cast<float>(Y + start_d);
        ray.ray.org_z = static_cast<float>(start_d);
        ray.ray.dir_x = 0.0f;
        ray.ray.dir_y = -1.0f;
        ray.ray.dir_z = -1.0f;
        ray.ray.tnear = 0.0f;
        ray.ray.tfar = static_cast<float>(t_plane);
        ray.ray.mask = ~0u;
        ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        ray.hit.primID = RTC_INVALID_GEOMETRY_ID;
        if (!empty) rtcIntersect1(s.embree->handle(), &context, &ray);

        Hit hit;
        glm::vec3 normal;
        HitKind kind;
        std::int32_t primitive = -1;
        if (ray.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
          kind = HitKind::Model;
          primitive = static_cast<std::int32_t>(ray.hit.primID);
          const auto& t = s.mesh.triangles[ray.hit.primID];
          hit = intersect_exactly(s.mesh.positions[t[0]], s.mesh.positions[t[1]], s.mesh.positions[t[2]], X, Y,
                                  start_d - ray.ray.tfar);
          const auto* n = &s.mesh.corner_normals[3 * static_cast<std::size_t>(ray.hit.primID)];
          normal = glm::normalize((1 - ray.hit.u - ray.hit.v) * n[0] + ray.hit.u * n[1] + ray.hit.v * n[2]);
          // Show the side facing the viewer, whatever the winding of an open or inverted mesh.
          if (normal.y + normal.z < 0) normal = -normal;
          if (!std::isfinite(normal.x)) normal = glm::vec3(0.0f, 0.70710678f, 0.70710678f);
        } else if (Y >= 0) {
          kind = HitKind::Back;
          hit = {Y, 0.0};
          normal = {0.0f, 0.0f, 1.0f};
        } else {
          kind = HitKind::Floor;
          hit = {0.0, -Y};
          normal = {0.0f, 1.0f, 0.0f};
        }
        maps.kind(col, row) = kind;
        maps.h_mm(col, row) = hit.h;
        maps.d_mm(col, row) = hit.d;
        maps.D(col, row) = static_cast<float>((ref.diag_mm - (hit.h + hit.d)) / ref.diag_mm);
        maps.F(col, row) = static_cast<float>((ref.front_d_mm - hit.d) / ref.front_d_mm);
        maps.T(col, row) = static_cast<float>((ref.top_h_mm - hit.h) / ref.top_h_mm);
        maps.normal(col, row) = normal;
        maps.primitive(col, row) = primitive;
      }
    }
  });

  for (const HitKind k : maps.kind.values) maps.model_pixels += k == HitKind::Model;
  return maps;
}

}  // namespace origamic
