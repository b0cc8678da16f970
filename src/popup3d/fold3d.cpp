// SPDX-License-Identifier: GPL-3.0-or-later
// Folding regions into 3D: CGAL's constrained Delaunay triangulation (inexact constructions are
// enough: the triangles only draw the faces) and OpenMesh for the mesh (its files: fold_mesh_files.cpp).
#include "origamic/fold3d.hpp"

// OpenMesh's VectorT leaves its elements uninitialized by default, which GCC 12 reports wherever a
// point or colour property grows (OpenMesh/Core/Utils/Property.hh, push_back of T()); the values are set.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <string>

#include "number_text.hpp"
#include "om_mesh.hpp"
#include "origamic/error.hpp"
#include "origamic/plan.hpp"
#include "quiet_openmesh.hpp"

namespace origamic {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
struct FaceInfo {
  int nesting = -1;  // rings crossed from outside; odd is inside the region
  bool inside() const { return nesting % 2 == 1; }
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase =
    CGAL::Constrained_triangulation_face_base_2<Kernel, CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Rings that cross (a malformed region) are split at their crossing instead of failing.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

void check_options(const FoldOptions& options) {
  if (!(options.angle_deg >= 0 && options.angle_deg <= 180))
    throw InputError("FoldOptions::angle_deg", "the opening angle must be between 0 and 180 degrees, not " +
                     number_text(options.angle_deg));
  // Card is at most a millimetre or so; 10 mm is a slab, not paper.
  if (!(options.thickness_mm >= 0 && options.thickness_mm <= 10))
    throw InputError("FoldOptions::thickness_mm", "the paper thickness must be between 0 and 10 mm, not " +
                     number_text(options.thickness_mm));
}

// Marks every face of the triangulation with how many rings separate it from the outside: a flood
// from the infinite face that stops at constrained edges, then from each edge reached, one deeper.
void mark_nesting(Cdt& cdt) {
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
  std::vector<Cdt::Edge> border;
  std::vector<Cdt::Face_handle> stack;
  auto flood = [&](Cdt::Face_handle start, int level) {
    stack.assign(1, start);
    while (!stack.empty()) {
      const Cdt::Face_handle f = stack.back();
      stack.pop_back();
      if (f->info().nesting != -1) continue;
      f->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle next = f->neighbor(i);
        if (next->info().nesting != -1) continue;
        if (cdt.is_constrained({f, i})) border.emplace_back(f, i);
        else stack.push_back(next);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  for (std::size_t k = 0; k < border.size(); ++k) {  // grows while we walk it: breadth first by level
    const auto [f, i] = border[k];
    const Cdt::Face_handle next = f->neighbor(i);
    if (next->info().nesting == -1) flood(next, f->info().nesting + 1);
  }
}

// Builds the popup and, alongside, the OpenMesh mesh it will be written as: a triangle OpenMesh
// refuses (a region touching itself at a vertex makes it non-manifold there) gets its own copies of
// its vertices, so the popup and any file of it hold the same vertices and triangles.
class Builder {
 public:
  explicit Builder(FoldedPopup& popup) : popup_(popup) {}

  // The vertex at plan point `plan` of a fold between V(d) and H(h): made by the first of the two
  // faces to reach it, the same vertex for the other, so the mesh is joined along its folds.
  std::uint32_t fold_vertex(const glm::dvec3& position, PlanPoint plan, std::int32_t region, double d, double h) {
    const auto [it, fresh] = fold_vertices_.try_emplace({plan.X, plan.Y, d, h}, 0);
    if (fresh) it->second = add_vertex(position, plan, region);
    return it->second;
  }

  std::uint32_t add_vertex(const glm::dvec3& position, PlanPoint plan, std::int32_t region) {
    popup_.positions.push_back(position);
    popup_.plan_points.push_back(plan);
    popup_.position_region.push_back(region);
    mesh_.add_vertex(OmMesh::Point(position.x, position.y, position.z));
    return static_cast<std::uint32_t>(popup_.positions.size() - 1);
  }

  void add_triangle(std::array<std::uint32_t, 3> t, std::int32_t region, PaperSurface surface) {
    // A paper edge where the sheet's two sides meet (a mitre of zero at a fold's end) has no area:
    // it is left out, as a mesh checker would flag it (the capitol's pop-up had two). An area under
    // 1e-12 mm² counts as none: the files keep 9 digits, which make such a sliver exactly flat.
    const glm::dvec3 &a = popup_.positions[t[0]], &b = popup_.positions[t[1]], &c = popup_.positions[t[2]];
    if (glm::length(glm::cross(b - a, c - a)) < 2e-12) return;
    auto handles = [&] {
      return std::array{mesh_.vertex_handle(t[0]), mesh_.vertex_handle(t[1]), mesh_.vertex_handle(t[2])};
    };
    auto h = handles();
    if (!mesh_.add_face(h[0], h[1], h[2]).is_valid()) {
      for (std::uint32_t& v : t)
        v = add_vertex(glm::dvec3(popup_.positions[v]), PlanPoint(popup_.plan_points[v]), region);
      popup_.split_vertices += 3;
      h = handles();
      [[maybe_unused]] const bool added = mesh_.add_face(h[0], h[1], h[2]).is_valid();
      assert(added);
    }
    popup_.triangles.push_back(t);
    popup_.triangle_region.push_back(region);
    popup_.triangle_surface.push_back(surface);
  }

 private:
  FoldedPopup& popup_;
  std::map<std::array<double, 4>, std::uint32_t> fold_vertices_;  // (X, Y, d, h) -> vertex
  OmMesh mesh_;
  QuietOpenMesh quiet_;
};

void check_finite(const PlanRegion& region, std::size_t index) {
  for (const auto& ring : region.rings)
    for (const PlanPoint& p : ring)
      if (!std::isfinite(p.X) || !std::isfinite(p.Y))
        throw InputError("regions",
                         "region " + std::to_string(index) + " has a ring with a coordinate that is not finite");
}

// The fold edges of each region: a horizontal ring edge whose reverse is a ring edge of a placed
// region of the other orientation, on their fold line Y = h - d (the rings hold every vertex of the
// plan's arrangement, so the two faces of a fold share its edges exactly; elsewhere such an edge is
// a cut, and the faces do not meet there in 3D).
struct FoldEdge {
  double Y, X_low, X_high;
  bool region_above;     // the region lies on the +Y side of its fold
  Orientation other;     // the face across the fold
  double other_depth_mm;  // its depth (d of a V face, h of an H face)
};

std::vector<std::vector<FoldEdge>> fold_edges(const std::vector<PlanRegion>& regions) {
  using Key = std::array<double, 4>;
  std::map<Key, std::size_t> horizontal;  // directed ring edge -> region
  auto each_horizontal_edge = [&](auto&& visit) {
    for (std::size_t r = 0; r < regions.size(); ++r) {
      if (!regions[r].placed) continue;
      for (const auto& ring : regions[r].rings)
        for (std::size_t i = 0; i < ring.size(); ++i) {
          const PlanPoint a = ring[i], b = ring[(i + 1) % ring.size()];
          if (a.Y == b.Y && a.X != b.X) visit(r, a, b);
        }
    }
  };
  each_horizontal_edge([&](std::size_t r, PlanPoint a, PlanPoint b) { horizontal[{a.X, a.Y, b.X, b.Y}] = r; });
  std::vector<std::vector<FoldEdge>> folds(regions.size());
  each_horizontal_edge([&](std::size_t r, PlanPoint a, PlanPoint b) {
    const auto across = horizontal.find({b.X, b.Y, a.X, a.Y});
    if (across == horizontal.end() || regions[across->second].orientation == regions[r].orientation) return;
    const double line = fold_line_Y(regions[r].orientation, regions[r].depth_mm, regions[across->second].depth_mm);
    if (!(std::abs(a.Y - line) <= kFoldLineTolerance_mm)) return;
    // With the region on the left of its ring's edges, an edge running to +X has it above.
    folds[r].push_back({a.Y, std::min(a.X, b.X), std::max(a.X, b.X), b.X > a.X, regions[across->second].orientation,
                        regions[across->second].depth_mm});
  });
  return folds;
}

// The unit vector a step up the plan (+Y) moves a point of a face of this orientation (fold_point).
glm::dvec3 plan_up(const CardFrame& frame, Orientation orientation) {
  return orientation == Orientation::V ? frame.b : -frame.f;
}
glm::dvec3 printed_normal(const CardFrame& frame, Orientation orientation) {
  return orientation == Orientation::V ? frame.n_back : frame.n_floor;
}

// How far the reverse side of a region's slab reaches past (positive: short of) its printed edge at
// a fold, along the region away from the fold: where the two faces' reverse planes meet, so their
// slabs meet on the plane bisecting the fold. Nearly closed folds would need a mitre without bound;
// it is held at twice the thickness, exact for folds opened 53 degrees or more.
glm::dvec3 mitre(const CardFrame& frame, Orientation orientation, const FoldEdge& fold, double thickness_mm) {
  const double side = fold.region_above ? 1 : -1;
  const glm::dvec3 into = side * plan_up(frame, orientation);    // from the fold into the region
  const glm::dvec3 across = -side * plan_up(frame, fold.other);  // from the fold into the other face
  // Solve a·into - c·across = t·(n - n_other) in the plane across the main fold (y, z).
  const glm::dvec3 rhs = thickness_mm * (printed_normal(frame, orientation) - printed_normal(frame, fold.other));
  const double det = into.y * -across.z - into.z * -across.y;
  if (std::abs(det) < 1e-12) return {};  // flat: the faces are one sheet, nothing to mitre
  const double a = (rhs.y * -across.z - rhs.z * -across.y) / det;
  return std::clamp(a, -2 * thickness_mm, 2 * thickness_mm) * into;
}

// A region to fold, with what folding it reads.
struct RegionToFold {
  const PlanRegion& region;
  std::int32_t index = 0;              // among the popup's regions
  const std::vector<FoldEdge>& folds;  // the region's, from fold_edges
  const CardFrame& frame;
  double thickness_mm = 0;
};

void insert_rings(Cdt& cdt, const PlanRegion& region) {
  for (const auto& ring : region.rings) {
    std::vector<Kernel::Point_2> points;
    points.reserve(ring.size());
    for (const PlanPoint& p : ring) points.emplace_back(p.X, p.Y);
    cdt.insert_constraint(points.begin(), points.end(), true);
  }
}

// Zero-thickness paper is one sheet: a vertex on a fold is shared with the face across it. (Slabs
// meet on their mitre planes instead, each closed on its own.)
const FoldEdge* shared_fold(const RegionToFold& r, PlanPoint p) {
  if (r.thickness_mm > 0) return nullptr;
  for (const FoldEdge& fold : r.folds)
    if (fold.Y == p.Y && fold.X_low <= p.X && p.X <= fold.X_high) return &fold;
  return nullptr;
}

// The printed side of a region, over the popup's vertices.
struct PrintedSide {
  std::vector<std::uint32_t> vertices;  // in order of first use
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 2>> boundary;  // directed with the region on the left
};

// The triangles inside the region's rings, their vertices made as the triangles first use them.
PrintedSide printed_side(Cdt& cdt, const RegionToFold& r, Builder& builder) {
  mark_nesting(cdt);
  for (Cdt::Vertex_handle v : cdt.finite_vertex_handles()) v->info() = kUnused;
  PrintedSide side;
  auto vertex = [&](Cdt::Vertex_handle v) {
    if (v->info() == kUnused) {
      const PlanPoint p{v->point().x(), v->point().y()};
      const glm::dvec3 position = fold_point(r.frame, p, r.region.orientation, r.region.depth_mm);
      const FoldEdge* fold = shared_fold(r, p);
      const bool is_v = r.region.orientation == Orientation::V;
      v->info() = fold ? builder.fold_vertex(position, p, r.index, is_v ? r.region.depth_mm : fold->other_depth_mm,
                                             is_v ? fold->other_depth_mm : r.region.depth_mm)
                       : builder.add_vertex(position, p, r.index);
      side.vertices.push_back(v->info());
    }
    return v->info();
  };
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info().inside()) continue;
    side.triangles.push_back({vertex(f->vertex(0)), vertex(f->vertex(1)), vertex(f->vertex(2))});
    for (int i = 0; i < 3; ++i)
      if (!f->neighbor(i)->info().inside())
        side.boundary.push_back({f->vertex(Cdt::ccw(i))->info(), f->vertex(Cdt::cw(i))->info()});
  }
  return side;
}

// The slab: the reverse side thickness_mm behind the printed one, mitred at folds, and quads along
// the boundary.
void add_slab(const PrintedSide& printed, const RegionToFold& r, Builder& builder, const FoldedPopup& popup) {
  const glm::dvec3 offset = -r.thickness_mm * printed_normal(r.frame, r.region.orientation);
  std::vector<glm::dvec3> mitred(popup.positions.size());
  for (const auto& [a, b] : printed.boundary) {
    const PlanPoint p = popup.plan_points[a], q = popup.plan_points[b];
    if (p.Y != q.Y) continue;
    for (const FoldEdge& fold : r.folds)
      if (fold.Y == p.Y && fold.X_low <= std::min(p.X, q.X) && std::max(p.X, q.X) <= fold.X_high)
        mitred[a] = mitred[b] = mitre(r.frame, r.region.orientation, fold, r.thickness_mm);
  }
  std::vector<std::uint32_t> behind(popup.positions.size(), kUnused);
  for (const std::uint32_t v : printed.vertices)
    behind[v] = builder.add_vertex(popup.positions[v] + offset + mitred[v], popup.plan_points[v], r.index);
  for (const auto& t : printed.triangles)
    builder.add_triangle({behind[t[0]], behind[t[2]], behind[t[1]]}, r.index, PaperSurface::Reverse);
  for (const auto& [a, b] : printed.boundary) {
    builder.add_triangle({a, behind[a], behind[b]}, r.index, PaperSurface::Edge);
    builder.add_triangle({a, behind[b], b}, r.index, PaperSurface::Edge);
  }
}

void fold_region(const RegionToFold& r, Builder& builder, FoldedPopup& popup) {
  Cdt cdt;
  insert_rings(cdt, r.region);
  if (cdt.dimension() < 2) return;  // rings with no area between them: nothing to fold
  const PrintedSide printed = printed_side(cdt, r, builder);
  if (printed.triangles.empty()) {
    ++popup.empty_regions;
    return;
  }
  for (const auto& t : printed.triangles) builder.add_triangle(t, r.index, PaperSurface::Printed);
  if (r.thickness_mm > 0) add_slab(printed, r, builder, popup);
}

// sin and cos of an angle in degrees, exact at the quarter turns the tests and pictures use most.
std::pair<double, double> sin_cos_deg(double angle_deg) {
  if (angle_deg == 0) return {0.0, 1.0};
  if (angle_deg == 90) return {1.0, 0.0};
  if (angle_deg == 180) return {0.0, -1.0};
  const double radians = angle_deg * (std::acos(-1.0) / 180);
  return {std::sin(radians), std::cos(radians)};
}

}  // namespace

CardFrame card_frame(double angle_deg) {
  const auto [s, c] = sin_cos_deg(angle_deg);
  CardFrame frame;
  frame.b = {0, s, c};
  frame.n_back = glm::cross(frame.e_x, frame.b);
  frame.n_floor = glm::cross(frame.f, frame.e_x);
  return frame;
}

glm::dvec3 fold_point(const CardFrame& frame, PlanPoint p, Orientation orientation, double depth_mm) {
  const double h = orientation == Orientation::V ? p.Y + depth_mm : depth_mm;
  const double d = orientation == Orientation::V ? depth_mm : depth_mm - p.Y;
  return p.X * frame.e_x + h * frame.b + d * frame.f;
}

FoldedPopup fold_popup(const std::vector<PlanRegion>& regions, const Sheet& sheet, const FoldOptions& options) {
  check_options(options);
  for (std::size_t i = 0; i < regions.size(); ++i) check_finite(regions[i], i);
  FoldedPopup popup;
  popup.sheet = sheet;
  popup.options = options;
  const CardFrame frame = card_frame(options.angle_deg);
  const std::vector<std::vector<FoldEdge>> folds = fold_edges(regions);
  Builder builder(popup);
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const PlanRegion& region = regions[i];
    popup.regions.push_back({region.orientation, region.depth_mm, region.status});
    if (region.status == FaceStatus::Removed) continue;  // cut out of the sheet: a hole, as the DXF has it
    if (!region.placed) {
      ++popup.unplaced_regions;
      continue;
    }
    fold_region({region, static_cast<std::int32_t>(i), folds[i], frame, options.thickness_mm}, builder, popup);
  }
  return popup;
}

Rgb8 triangle_colour(const FoldedPopup& popup, std::size_t t, bool mark_unsupported) {
  return paper_colour(popup.regions[static_cast<std::size_t>(popup.triangle_region[t])], popup.triangle_surface[t],
                      mark_unsupported);
}

Rgb8 paper_colour(const FoldedRegion& region, PaperSurface surface, bool mark_unsupported) {
  if (surface == PaperSurface::Edge) return {150, 138, 120};
  const bool v = region.orientation == Orientation::V;
  const bool stands = region.status == FaceStatus::Valid || region.status == FaceStatus::Indirect;
  if (mark_unsupported && !stands) return v ? Rgb8{246, 178, 178} : Rgb8{236, 160, 160};
  if (region.depth_mm == 0) return v ? Rgb8{226, 230, 236} : Rgb8{214, 205, 186};  // the card
  return v ? Rgb8{250, 248, 242} : Rgb8{240, 230, 208};
}

}  // namespace origamic
