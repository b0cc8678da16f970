// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/raster.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

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

// A key step between neighbouring pixel centres larger than this many pixels may be a jump, and is
// bisected: a surface at 45 degrees to the rays steps 2 pixels' worth of h + d a pixel.
constexpr double kBreakJump_px = 4.0;
// Facings more than 20 degrees apart between neighbouring pixel centres may be a crease; finer
// facets (a 96-sided drum turns 3.75 degrees from facet to facet) are the model's curve.
constexpr double kCreaseCosine = 0.9397;

// The point (X, Y + d, d) of the 45-degree line through plan point (X, Y) on the plane of triangle
// abc, in double precision. Axis-parallel faces return their coordinate untouched, so a V face's d
// and an H face's h are exactly the mesh's.
Hit intersect_exactly(const std::array<glm::dvec3, 3>& abc, double X, double Y, double fallback_d) {
  const auto& [a, b, c] = abc;
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

struct Traced {
  HitKind kind = HitKind::Outside;
  Hit hit;
  glm::vec3 normal{0.0f};
  std::int32_t primitive = -1;
};

// The 45-degree rays of one scene: from plan point (X, Y) along (X, Y + start_d - t, start_d - t)
// to the model, or to the back plane (d = 0, reached at t = start_d when Y >= 0) or the floor (h = 0,
// at t = start_d + Y when Y < 0).
struct Tracer {
  const RayScene::Impl& scene;
  double start_d;  // rays start on this vertical plane, in front of the model and the floor's edge

  // Whether the ray through plan point (X, Y) may meet the model: it keeps x = X and h - d = Y, so
  // not outside the model's box in x and in h - d (widened by a micrometre, far more than the
  // float rounding of the rays and of Embree's vertices). Most of a sheet is back plane and floor.
  bool may_hit(double X, double Y) const {
    constexpr double kMargin_mm = 1e-3;
    return !scene.mesh.positions.empty() && X >= scene.lo.x - kMargin_mm && X <= scene.hi.x + kMargin_mm &&
           Y >= scene.lo.y - scene.hi.z - kMargin_mm && Y <= scene.hi.y - scene.lo.z + kMargin_mm;
  }

  // The unit normal of a triangle's plane, turned to face the viewer (+h, +d).
  glm::dvec3 facing(std::int32_t primitive) const {
    const auto& t = scene.mesh.triangles[static_cast<std::size_t>(primitive)];
    const glm::dvec3& p = scene.mesh.positions[t[0]];
    const glm::dvec3 n = glm::cross(scene.mesh.positions[t[1]] - p, scene.mesh.positions[t[2]] - p);
    const double length = glm::length(n);
    if (!(length > 0)) return glm::dvec3(0.0);
    return (n.y + n.z < 0 ? -n : n) / length;
  }

  Traced trace(double X, double Y, bool with_normal, bool coherent = false) const {
    const double t_plane = Y >= 0 ? start_d : start_d + Y;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // a row's rays, side by side
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
    if (may_hit(X, Y)) rtcIntersect1(scene.embree->handle(), &context, &ray);

    Traced traced;
    if (ray.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      traced.kind = HitKind::Model;
      traced.primitive = static_cast<std::int32_t>(ray.hit.primID);
      const auto& t = scene.mesh.triangles[ray.hit.primID];
      const std::array<glm::dvec3, 3> abc{scene.mesh.positions[t[0]], scene.mesh.positions[t[1]],
                                          scene.mesh.positions[t[2]]};
      traced.hit = intersect_exactly(abc, X, Y, start_d - ray.ray.tfar);
      if (!with_normal) return traced;
      const auto* n = &scene.mesh.corner_normals[3 * static_cast<std::size_t>(ray.hit.primID)];
      glm::vec3 normal = glm::normalize((1 - ray.hit.u - ray.hit.v) * n[0] + ray.hit.u * n[1] + ray.hit.v * n[2]);
      // Show the side facing the viewer, whatever the winding of an open or inverted mesh.
      if (normal.y + normal.z < 0) normal = -normal;
      if (!std::isfinite(normal.x)) normal = glm::vec3(0.0f, 0.70710678f, 0.70710678f);
      traced.normal = normal;
    } else if (Y >= 0) {
      traced = {HitKind::Back, {Y, 0.0}, {0.0f, 0.0f, 1.0f}, -1};
    } else {
      traced = {HitKind::Floor, {0.0, -Y}, {0.0f, 1.0f, 0.0f}, -1};
    }
    return traced;
  }
};

// The 45-degree key h + d: equal for points on one ray, larger nearer the viewer.
double key_of(const Traced& traced) { return traced.hit.h + traced.hit.d; }

// The last interval of a bisection from plan point a (fraction 0) to b (fraction 1).
struct Bisected {
  double lo = 0, hi = 1;
  Traced at_lo, at_hi;
};

// The way from plan point a to plan point b, and what the tracer found at each.
struct Way {
  glm::dvec2 a, b;
  const Traced& at_a;
  const Traced& at_b;
};

// Bisects the way, 10 times (to 1/1024 of it), on which side of a change a point lies.
template <typename OnASide>
Bisected bisect(const Tracer& tracer, const Way& way, OnASide on_a_side) {
  const auto& [a, b, at_a, at_b] = way;
  Bisected range{0, 1, at_a, at_b};
  for (int step = 0; step < 10; ++step) {
    const double mid = (range.lo + range.hi) / 2;
    const glm::dvec2 p = a + mid * (b - a);
    const Traced at_mid = tracer.trace(p.x, p.y, false);
    if (on_a_side(at_mid))
      range.lo = mid, range.at_lo = at_mid;
    else
      range.hi = mid, range.at_hi = at_mid;
  }
  return range;
}

// Where the picture breaks on the way from plan point a to b, as a fraction of it, or NaN: the
// model against the background; a jump in the key (one surface in front of another); or a crease,
// the facing turning sharply (a box's top edge). A jump or crease must stay whole as the bisection
// narrows it to 1/1024 of the way: a steep or curved but smooth surface spreads its change.
float break_between(const Tracer& tracer, const Way& way) {
  const auto& [a, b, at_a, at_b] = way;
  constexpr float none = std::numeric_limits<float>::quiet_NaN();
  const bool model_a = at_a.kind == HitKind::Model, model_b = at_b.kind == HitKind::Model;
  // A break on the pixel edge itself (an axis-parallel model edge on the lattice, as often as not)
  // leaves the first midpoint, 1/2, an end of the last interval: it is there, and stays symmetric.
  const auto middle = [](const Bisected& range) {
    return range.lo == 0.5 || range.hi == 0.5 ? 0.5f : static_cast<float>((range.lo + range.hi) / 2);
  };
  if (model_a != model_b)
    return middle(bisect(tracer, way, [&](const Traced& t) { return (t.kind == HitKind::Model) == model_a; }));
  if (!model_a) return none;
  const double jump = key_of(at_b) - key_of(at_a);
  if (std::abs(jump) > kBreakJump_px * glm::length(b - a)) {
    const Bisected range = bisect(tracer, way, [&](const Traced& t) {
      return t.kind == HitKind::Model && std::abs(key_of(t) - key_of(at_a)) < std::abs(key_of(t) - key_of(at_b));
    });
    if (std::abs(key_of(range.at_hi) - key_of(range.at_lo)) >= std::abs(jump) / 2) return middle(range);
  }
  const glm::dvec3 facing_a = tracer.facing(at_a.primitive), facing_b = tracer.facing(at_b.primitive);
  const double turn = glm::dot(facing_a, facing_b);
  if (!(turn < kCreaseCosine)) return none;
  const Bisected range = bisect(tracer, way, [&](const Traced& t) {
    if (t.kind != HitKind::Model) return false;
    const glm::dvec3 facing = tracer.facing(t.primitive);
    return glm::dot(facing, facing_a) > glm::dot(facing, facing_b);
  });
  if (range.at_lo.kind != HitKind::Model || range.at_hi.kind != HitKind::Model) return none;
  if (!(glm::dot(tracer.facing(range.at_lo.primitive), tracer.facing(range.at_hi.primitive)) <= (1 + turn) / 2))
    return none;
  return middle(range);
}

// The maps' breaks between neighbouring pixel centres on the sheet, in parallel over rows.
void trace_breaks(const Tracer& tracer, const Grid<std::int32_t>& primitive, RasterMaps& maps) {
  const PixelGrid& grid = maps.grid;
  constexpr float none = std::numeric_limits<float>::quiet_NaN();
  maps.break_right = Grid<float>::unfilled(grid.cols, grid.rows);  // every pixel written below
  maps.break_below = Grid<float>::unfilled(grid.cols, grid.rows);
  const double px_mm = 1 / grid.px_per_mm;
  tbb::parallel_for(tbb::blocked_range<int>(0, grid.rows), [&](const tbb::blocked_range<int>& range) {
    for (int row = range.begin(); row != range.end(); ++row)
      for (int col = 0; col < grid.cols; ++col) {
        if (maps.kind(col, row) == HitKind::Outside) {
          maps.break_right(col, row) = maps.break_below(col, row) = none;
          continue;
        }
        const glm::dvec2 a(grid.X(col), grid.Y(row));
        const Traced at_a{maps.kind(col, row), {maps.h_mm(col, row), maps.d_mm(col, row)}, {}, primitive(col, row)};
        for (const auto& [c, r, out] :
             {std::tuple{col + 1, row, &maps.break_right}, std::tuple{col, row + 1, &maps.break_below}}) {
          if (!maps.kind.contains(c, r) || maps.kind(c, r) == HitKind::Outside) {
            (*out)(col, row) = none;
            continue;
          }
          const Traced at_b{maps.kind(c, r), {maps.h_mm(c, r), maps.d_mm(c, r)}, {}, primitive(c, r)};
          (*out)(col, row) = break_between(tracer, {a, a + glm::dvec2(c - col, row - r) * px_mm, at_a, at_b});
        }
      }
  });
}

void check_options(const Sheet& sheet, const RasterOptions& options) {
  if (!(std::isfinite(options.px_per_mm) && options.px_per_mm > 0))
    throw InputError("RasterOptions::px_per_mm", "must be a positive, finite number");
  const double cols = sheet.width_mm * options.px_per_mm, rows = sheet.height_mm * options.px_per_mm;
  if (!(cols >= 1 && rows >= 2))
    throw InputError("RasterOptions::px_per_mm",
                     std::to_string(options.px_per_mm) + " gives less than one pixel across the sheet");
  const double pixels = cols * rows;
  constexpr double max_pixels = 64e6;  // the maps take about 37 bytes a pixel: 2.4 GB at most
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
  // Every pixel is written once below, on all cores.
  maps.kind = Grid<HitKind>::unfilled(cols, rows);
  maps.d_mm = Grid<double>::unfilled(cols, rows);
  maps.h_mm = Grid<double>::unfilled(cols, rows);
  maps.normal = Grid<glm::vec3>::unfilled(cols, rows);
  // The triangle each ray met (-1 where none), which the breaks between pixels read.
  Grid<std::int32_t> primitive = Grid<std::int32_t>::unfilled(cols, rows);

  const double half = sheet.half_height_mm();
  const bool empty = s.mesh.positions.empty();
  maps.reference.front_d_mm = std::max(half, empty ? 0.0 : s.hi.z);
  maps.reference.top_h_mm = std::max(half, empty ? 0.0 : s.hi.y);
  maps.reference.diag_mm = maps.reference.front_d_mm + maps.reference.top_h_mm;
  const DepthReference ref = maps.reference;
  // Rays start on the vertical plane d = start_d, in front of the model and of the floor's edge.
  const double start_d = ref.front_d_mm + 1.0;

  const Tracer tracer{s, start_d};
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    for (int row = range.begin(); row != range.end(); ++row) {
      const double Y = maps.grid.Y(row);
      const bool row_on_sheet = !(Y < sheet.min_Y() || Y > sheet.max_Y());
      for (int col = 0; col < cols; ++col) {
        const double X = maps.grid.X(col);
        if (!row_on_sheet || X > sheet.max_X()) {  // past the sheet's edge: the values unset
          maps.kind(col, row) = HitKind::Outside;
          maps.d_mm(col, row) = maps.h_mm(col, row) = std::numeric_limits<double>::quiet_NaN();
          maps.normal(col, row) = glm::vec3(0.0f);
          primitive(col, row) = -1;
          continue;
        }
        const Traced traced = tracer.trace(X, Y, true, true);
        const Hit& hit = traced.hit;
        maps.kind(col, row) = traced.kind;
        maps.h_mm(col, row) = hit.h;
        maps.d_mm(col, row) = hit.d;
        maps.normal(col, row) = traced.normal;
        primitive(col, row) = traced.primitive;
      }
    }
  });
  trace_breaks(tracer, primitive, maps);

  for (const HitKind k : maps.kind.values) maps.model_pixels += k == HitKind::Model;
  return maps;
}

// Made when a picture wants them: kept as maps, their 12 bytes a pixel were first touched on every
// design for nothing (fresh memory costs about 1.3 ms/MB here; the torus's peak 179 -> 162 MB).
NormalisedDepths normalised_depths(const RasterMaps& maps) {
  assert(maps.d_mm.size() == maps.kind.size() && maps.h_mm.size() == maps.kind.size());
  const int cols = maps.grid.cols, rows = maps.grid.rows;
  const DepthReference& ref = maps.reference;
  NormalisedDepths depths{Grid<float>(cols, rows, 1.0f), Grid<float>(cols, rows, 1.0f), Grid<float>(cols, rows, 1.0f)};
  for (std::size_t i = 0; i < maps.kind.size(); ++i) {
    if (maps.kind.values[i] == HitKind::Outside) continue;
    const double h = maps.h_mm.values[i], d = maps.d_mm.values[i];
    depths.D.values[i] = static_cast<float>((ref.diag_mm - (h + d)) / ref.diag_mm);
    depths.F.values[i] = static_cast<float>((ref.front_d_mm - d) / ref.front_d_mm);
    depths.T.values[i] = static_cast<float>((ref.top_h_mm - h) / ref.top_h_mm);
  }
  return depths;
}

}  // namespace origamic
