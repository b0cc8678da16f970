// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/fold3d.hpp"

#include <gtest/gtest.h>

// OpenMesh's colour property trips GCC 12's -Wmaybe-uninitialized (see src/fold3d.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "helpers.hpp"
#include "union_find.hpp"
#include "origamic/error.hpp"
#include "origamic/output.hpp"
#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace origamic {
namespace {

// The box of the hand-made plan: off any round number, taller than deep.
constexpr double kX0 = 61.3, kX1 = 148.9, kH = 63.7, kD = 41.9;
const std::vector<double> kAngles = {0, 30, 90, 137, 180};

std::vector<PlanRegion> box_regions() { return test::box_popup_regions(Sheet{}, kX0, kX1, kH, kD); }

double plan_distance(PlanPoint p, PlanPoint q) { return std::hypot(p.X - q.X, p.Y - q.Y); }

void expect_near3(const glm::dvec3& a, const glm::dvec3& b, double tolerance, const std::string& what) {
  EXPECT_LE(glm::length(a - b), tolerance) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x
                                           << ", " << b.y << ", " << b.z << ")";
}

TEST(Fold3d, FlatAt180EveryVertexIsItsPlanPoint) {
  for (const double thickness : {0.0, 0.3}) {
    const FoldedPopup popup = fold_popup(box_regions(), Sheet{}, {.angle_deg = 180, .thickness_mm = thickness});
    ASSERT_FALSE(popup.positions.empty());
    for (std::size_t i = 0; i < popup.positions.size(); ++i) {
      const PlanPoint p = popup.plan_points[i];
      const glm::dvec3 flat(p.X, 0, -p.Y);  // the flat frame: the sheet on y = 0, plan Y along -z
      const glm::dvec3 q = popup.positions[i];
      if (thickness == 0) {
        expect_near3(q, flat, 1e-9, "vertex " + std::to_string(i));
      } else {  // printed side on y = 0, reverse side a thickness below
        EXPECT_NEAR(q.x, flat.x, 1e-9);
        EXPECT_NEAR(q.z, flat.z, 1e-9);
        EXPECT_TRUE(std::abs(q.y) <= 1e-9 || std::abs(q.y + thickness) <= 1e-9) << q.y;
      }
    }
  }
}

TEST(Fold3d, At90VFacesKeepTheirDepthAndHFacesTheirHeight) {
  const std::vector<PlanRegion> regions = box_regions();
  const FoldedPopup popup = fold_popup(regions, Sheet{}, {});
  std::set<std::int32_t> seen;
  for (std::size_t t = 0; t < popup.triangles.size(); ++t)
    for (const std::uint32_t i : popup.triangles[t]) {  // each vertex as each face that uses it places it
      const PlanRegion& r = regions[static_cast<std::size_t>(popup.triangle_region[t])];
      const glm::dvec3 q = popup.positions[i];
      const PlanPoint p = popup.plan_points[i];
      EXPECT_EQ(q.x, p.X);
      if (r.orientation == Orientation::V) {  // parallel to the back plane, at its depth
        EXPECT_NEAR(q.z, r.depth_mm, 1e-9);
        EXPECT_NEAR(q.y, p.Y + r.depth_mm, 1e-9);
      } else {  // parallel to the floor, at its height
        EXPECT_NEAR(q.y, r.depth_mm, 1e-9);
        EXPECT_NEAR(q.z, r.depth_mm - p.Y, 1e-9);
      }
      EXPECT_GE(q.y, -1e-9) << "nothing below the floor";
      EXPECT_GE(q.z, -1e-9) << "nothing behind the back plane";
      seen.insert(popup.triangle_region[t]);
    }
  EXPECT_EQ(seen.size(), regions.size());
  // The box itself: front and top span exactly the box.
  for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
    if (popup.triangle_region[t] < 2) continue;
    for (const std::uint32_t i : popup.triangles[t]) {
      const glm::dvec3 q = popup.positions[i];
      EXPECT_TRUE(q.x == kX0 || q.x == kX1);
      EXPECT_TRUE(std::abs(q.y) < 1e-9 || std::abs(q.y - kH) < 1e-9);
      EXPECT_TRUE(std::abs(q.z) < 1e-9 || std::abs(q.z - kD) < 1e-9);
    }
  }
}

TEST(Fold3d, EveryEdgeKeepsItsPlanLengthAtEveryAngle) {
  for (const double thickness : {0.0, 0.5})
    for (const double angle : kAngles) {
      const FoldedPopup popup = fold_popup(box_regions(), Sheet{}, {.angle_deg = angle, .thickness_mm = thickness});
      // The reverse side of thick paper is mitred at folds (shorter inside a bend, longer outside),
      // as real card's is; it keeps its plan lengths only where the card lies flat.
      auto kept = [&](PaperSurface s) {
        return s == PaperSurface::Printed || (s == PaperSurface::Reverse && angle == 180);
      };
      int edges = 0;
      for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
        if (!kept(popup.triangle_surface[t])) continue;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t a = popup.triangles[t][k], b = popup.triangles[t][(k + 1) % 3];
          const double plan = plan_distance(popup.plan_points[a], popup.plan_points[b]);
          const double folded = glm::length(popup.positions[a] - popup.positions[b]);
          ASSERT_GT(plan, 0);
          EXPECT_NEAR(folded / plan, 1.0, 1e-9) << "angle " << angle << ", triangle " << t;
          ++edges;
        }
      }
      EXPECT_EQ(edges, 3 * static_cast<int>(std::ranges::count_if(popup.triangle_surface, kept)));
      EXPECT_GT(edges, 0);
    }
}

// Zero-thickness card is one sheet: the two faces of each fold share its vertices (the mesh is
// joined along it, as the paper is), and faces share no vertex anywhere else.
TEST(Fold3d, FacesShareTheVerticesOfTheirFoldsAndNoOthers) {
  const std::vector<PlanRegion> regions = box_regions();
  for (const double angle : kAngles) {
    const FoldedPopup popup = fold_popup(regions, Sheet{}, {.angle_deg = angle});
    std::vector<std::set<std::int32_t>> users(popup.positions.size());
    for (std::size_t t = 0; t < popup.triangles.size(); ++t)
      for (const std::uint32_t i : popup.triangles[t]) users[i].insert(popup.triangle_region[t]);
    int shared = 0;
    for (std::size_t i = 0; i < users.size(); ++i) {
      if (users[i].size() < 2) continue;
      ASSERT_EQ(users[i].size(), 2u) << "a fold's end joins two faces";
      const PlanRegion& a = regions[static_cast<std::size_t>(*users[i].begin())];
      const PlanRegion& b = regions[static_cast<std::size_t>(*users[i].rbegin())];
      ASSERT_NE(a.orientation, b.orientation);
      const PlanRegion& v = a.orientation == Orientation::V ? a : b;
      const PlanRegion& h = a.orientation == Orientation::H ? a : b;
      const PlanPoint p = popup.plan_points[i];
      ASSERT_EQ(p.Y, h.depth_mm - v.depth_mm) << "the box plan's faces meet on folds only there";
      const CardFrame frame = card_frame(angle);
      expect_near3(popup.positions[i], fold_point(frame, p, Orientation::V, v.depth_mm), 1e-9, "as the V face has it");
      expect_near3(popup.positions[i], fold_point(frame, p, Orientation::H, h.depth_mm), 1e-9, "as the H face has it");
      ++shared;
    }
    // Main fold (0, a, b, W), floor-front, front-top and top-back fold ends (2 each).
    EXPECT_EQ(shared, 10) << "angle " << angle;
    // No fold point made twice: vertices at one plan point belong to faces that meet there on no fold.
    for (std::size_t i = 0; i < users.size(); ++i)
      for (std::size_t j = i + 1; j < users.size(); ++j) {
        const PlanPoint p = popup.plan_points[i], q = popup.plan_points[j];
        if (p.X != q.X || p.Y != q.Y) continue;
        for (const std::int32_t ri : users[i])
          for (const std::int32_t rj : users[j]) {
            const PlanRegion &a = regions[static_cast<std::size_t>(ri)], &b = regions[static_cast<std::size_t>(rj)];
            if (a.orientation == b.orientation) continue;
            const PlanRegion& v = a.orientation == Orientation::V ? a : b;
            EXPECT_NE(p.Y, (a.orientation == Orientation::H ? a : b).depth_mm - v.depth_mm)
                << "a fold point at (" << p.X << ", " << p.Y << ") made twice";
          }
      }
    // So the card is one piece: every triangle reaches every other through shared vertices.
    UnionFind<std::uint32_t> sets(popup.positions.size());
    for (const auto& t : popup.triangles) sets.join(t[0], t[1]), sets.join(t[0], t[2]);
    std::set<std::uint32_t> pieces;
    for (const auto& t : popup.triangles) pieces.insert(sets.root(t[0]));
    EXPECT_EQ(pieces.size(), 1u) << "angle " << angle;
  }
  // Slabs of thick card meet on their mitre planes, each closed on its own.
  const FoldedPopup thick = fold_popup(regions, Sheet{}, {.thickness_mm = 0.5});
  std::vector<std::set<std::int32_t>> users(thick.positions.size());
  for (std::size_t t = 0; t < thick.triangles.size(); ++t)
    for (const std::uint32_t i : thick.triangles[t]) users[i].insert(thick.triangle_region[t]);
  EXPECT_TRUE(std::ranges::all_of(users, [](const auto& u) { return u.size() <= 1; }));
  // Across a cut the faces part: plan point (x0, 0) lies on the front's side (a cut) and on the
  // floor's cut-out; at 90 degrees the front holds it at (x0, d, d), the floor at (x0, 0, 0).
  const CardFrame frame = card_frame(90);
  const glm::dvec3 on_front = fold_point(frame, {kX0, 0}, Orientation::V, kD);
  const glm::dvec3 on_floor = fold_point(frame, {kX0, 0}, Orientation::H, 0);
  EXPECT_NEAR(glm::length(on_front - on_floor), std::hypot(kD, kD), 1e-9);
}

TEST(Fold3d, PrintedSidesFaceTheViewerAndTheSky) {
  for (const double angle : kAngles) {
    const CardFrame frame = card_frame(angle);
    EXPECT_NEAR(glm::dot(frame.b, frame.f), std::cos(angle * std::acos(-1.0) / 180), 1e-15);
    const FoldedPopup popup = fold_popup(box_regions(), Sheet{}, {.angle_deg = angle, .thickness_mm = 0.2});
    for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
      const auto& tri = popup.triangles[t];
      const glm::dvec3 n = glm::normalize(glm::cross(popup.positions[tri[1]] - popup.positions[tri[0]],
                                                     popup.positions[tri[2]] - popup.positions[tri[0]]));
      const bool v = popup.regions[static_cast<std::size_t>(popup.triangle_region[t])].orientation == Orientation::V;
      const glm::dvec3 printed = v ? frame.n_back : frame.n_floor;
      switch (popup.triangle_surface[t]) {
        case PaperSurface::Printed: expect_near3(n, printed, 1e-9, "printed normal"); break;
        case PaperSurface::Reverse: expect_near3(n, -printed, 1e-9, "reverse normal"); break;
        case PaperSurface::Edge: {
          // Along a cut the edge stands square to the paper; along a fold it is the mitre, which
          // still runs along the fold, square to the main fold's direction.
          const bool along_fold = popup.plan_points[tri[0]].Y == popup.plan_points[tri[1]].Y &&
                                  popup.plan_points[tri[1]].Y == popup.plan_points[tri[2]].Y;
          EXPECT_NEAR(glm::dot(n, along_fold ? frame.e_x : printed), 0, 1e-9);
          break;
        }
      }
    }
  }
  EXPECT_EQ(card_frame(90).n_back, glm::dvec3(0, 0, 1));
  EXPECT_EQ(card_frame(90).n_floor, glm::dvec3(0, 1, 0));
}

TEST(Fold3d, TrianglesCoverEachRegionLessItsHoles) {
  // The back plane with a window as a clockwise hole, beside the box.
  std::vector<PlanRegion> regions = box_regions();
  const std::vector<PlanPoint> window = {{20, 100}, {20, 120}, {45, 120}, {45, 100}};
  regions[0].rings.push_back(window);
  const FoldedPopup popup = fold_popup(regions, Sheet{}, {.angle_deg = 63});
  std::vector<double> area(regions.size(), 0.0);
  for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
    const auto& tri = popup.triangles[t];
    const double twice = test::twice_signed_area(
        {popup.plan_points[tri[0]], popup.plan_points[tri[1]], popup.plan_points[tri[2]]});
    EXPECT_GT(twice, 0) << "plan triangles are counter-clockwise";
    area[static_cast<std::size_t>(popup.triangle_region[t])] += twice / 2;
    // No triangle inside the window: its centroid is outside.
    const double cx = (popup.plan_points[tri[0]].X + popup.plan_points[tri[1]].X + popup.plan_points[tri[2]].X) / 3;
    const double cy = (popup.plan_points[tri[0]].Y + popup.plan_points[tri[1]].Y + popup.plan_points[tri[2]].Y) / 3;
    EXPECT_FALSE(cx > 20 && cx < 45 && cy > 100 && cy < 120);
  }
  for (std::size_t r = 0; r < regions.size(); ++r) {
    double expected = 0;
    for (const auto& ring : regions[r].rings) expected += test::twice_signed_area(ring) / 2;
    EXPECT_NEAR(area[r], expected, 1e-9 * expected) << "region " << r;
  }
  EXPECT_NEAR(area[0], 210 * 148.5 - (kX1 - kX0) * kH - 25 * 20, 1e-9);
  EXPECT_EQ(popup.empty_regions, 0);
}

TEST(Fold3d, ThickPaperMakesClosedSlabsMitredAtTheFolds) {
  const double t = 0.4;
  const std::vector<PlanRegion> regions = box_regions();
  for (const double angle : {30.0, 60.0, 90.0, 120.0, 150.0}) {
    const FoldedPopup popup = fold_popup(regions, Sheet{}, {.angle_deg = angle, .thickness_mm = t});
    std::vector<double> volume(regions.size(), 0.0);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t i = 0; i < popup.triangles.size(); ++i) {
      const auto& tri = popup.triangles[i];
      const glm::dvec3 &a = popup.positions[tri[0]], &b = popup.positions[tri[1]], &c = popup.positions[tri[2]];
      volume[static_cast<std::size_t>(popup.triangle_region[i])] += glm::dot(a, glm::cross(b, c)) / 6;
      for (int k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
    }
    // Closed and consistently wound: every directed edge once, and its reverse once.
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    if (angle == 90) {
      // Square folds: a valley's reverse sides (outside the bend) reach on by t, a mountain's stop t
      // short, each slab gaining or losing a t-by-t half square along the fold. The back plane and
      // the floor meet the box and each other in valleys; the front meets the top in a mountain
      // and the floor in a valley, the top the back plane in a valley.
      const double box = kX1 - kX0, rest = 210 - box, corner = t * t / 2;
      const std::vector<double> folds = {corner * (rest + box), corner * (rest + box), corner * (box - box),
                                         corner * (box - box)};
      for (std::size_t r = 0; r < regions.size(); ++r)
        EXPECT_NEAR(volume[r], t * test::twice_signed_area(regions[r].rings[0]) / 2 + folds[r], 1e-6) << "region " << r;
    }
    if (angle < 53 || angle > 127) continue;
    // The two slabs of a fold meet on the same mitre: the front's and the top's points on their fold
    // line (printed and reverse) are the same points, and so are the back plane's and the top's.
    for (const auto& [a, b, Y] : {std::tuple{2, 3, kH - kD}, std::tuple{0, 3, kH}}) {
      auto on_fold = [&](int region) {
        std::vector<glm::dvec3> points;
        for (std::size_t v = 0; v < popup.positions.size(); ++v)
          if (popup.position_region[v] == region && popup.plan_points[v].Y == Y) points.push_back(popup.positions[v]);
        return points;
      };
      const std::vector<glm::dvec3> first = on_fold(a), second = on_fold(b);
      ASSERT_EQ(first.size(), 4u) << "angle " << angle << ": two printed and two reverse ends";
      for (const glm::dvec3& p : first) {
        double nearest = std::numeric_limits<double>::max();
        for (const glm::dvec3& q : second) nearest = std::min(nearest, glm::length(p - q));
        EXPECT_LT(nearest, 1e-9) << "angle " << angle << ", regions " << a << " and " << b;
      }
    }
  }
}

// A horizontal edge between a V face and an H face off their fold line Y = h - d is a cut: the faces
// do not meet there in 3D, and thick card gets no mitre on it. Each slab is then exactly its area
// times the thickness (a mitred fold would add or take a t-by-t half square along the edge).
TEST(Fold3d, AnEdgeOffTheFoldLineIsACutAndGetsNoMitre) {
  const double t = 0.4, W = Sheet{}.width_mm, half = Sheet{}.half_height_mm(), cut_Y = kH + 5;
  std::vector<PlanRegion> regions(2);
  regions[0].orientation = Orientation::V;  // the back plane, notched down to the cut
  regions[0].rings = {{{0, 0}, {kX0, 0}, {kX0, cut_Y}, {kX1, cut_Y}, {kX1, 0}, {W, 0}, {W, half}, {0, half}}};
  regions[1].orientation = Orientation::H;  // at height kH: its fold line with the back plane is Y = kH
  regions[1].depth_mm = kH;
  regions[1].rings = {{{kX0, cut_Y - 10}, {kX1, cut_Y - 10}, {kX1, cut_Y}, {kX0, cut_Y}}};
  for (PlanRegion& r : regions) r.placed = true;
  const FoldedPopup popup = fold_popup(regions, Sheet{}, {.angle_deg = 90, .thickness_mm = t});
  std::vector<double> volume(regions.size(), 0.0);
  for (std::size_t i = 0; i < popup.triangles.size(); ++i) {
    const auto& tri = popup.triangles[i];
    const glm::dvec3 &a = popup.positions[tri[0]], &b = popup.positions[tri[1]], &c = popup.positions[tri[2]];
    volume[static_cast<std::size_t>(popup.triangle_region[i])] += glm::dot(a, glm::cross(b, c)) / 6;
  }
  for (std::size_t r = 0; r < regions.size(); ++r)
    EXPECT_NEAR(volume[r], t * test::twice_signed_area(regions[r].rings[0]) / 2, 1e-6) << "region " << r;
}

TEST(Fold3d, RegionsTheFoldsDoNotPlaceAreLeftOut) {
  std::vector<PlanRegion> regions = box_regions();
  regions[3].placed = false;  // the top, as a plan read from its lines might leave it
  const FoldedPopup popup = fold_popup(regions, Sheet{}, {});
  EXPECT_EQ(popup.unplaced_regions, 1);
  EXPECT_EQ(popup.regions.size(), 4u);
  EXPECT_EQ(std::ranges::count(popup.triangle_region, 3), 0);
  EXPECT_EQ(std::ranges::count(popup.position_region, 3), 0);
  EXPECT_GT(std::ranges::count(popup.triangle_region, 2), 0);
}

TEST(Fold3d, OptionsAndCoordinatesOutOfRangeAreRejected) {
  auto message = [](const std::vector<PlanRegion>& regions, const FoldOptions& options) {
    try {
      fold_popup(regions, Sheet{}, options);
    } catch (const InputError& e) {
      return e.field;
    }
    return std::string();
  };
  for (const double angle : {-1.0, 180.5, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_EQ(message(box_regions(), {.angle_deg = angle}), "FoldOptions::angle_deg") << angle;
  for (const double thickness : {-0.1, 11.0, std::numeric_limits<double>::infinity()})
    EXPECT_EQ(message(box_regions(), {.thickness_mm = thickness}), "FoldOptions::thickness_mm") << thickness;
  std::vector<PlanRegion> regions = box_regions();
  regions[2].rings[0][1].Y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(regions, {}), "regions");
  try {
    fold_popup(regions, Sheet{}, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem.find("region 2 "), std::string::npos) << e.what();
  }
}

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec3uc;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

// The box folded at an angle, as thin paper and as 0.4 mm card.
std::vector<FoldedPopup> folded_boxes(double angle_deg) {
  std::vector<FoldedPopup> popups;
  for (const double thickness : {0.0, 0.4})
    popups.push_back(fold_popup(box_regions(), Sheet{}, {.angle_deg = angle_deg, .thickness_mm = thickness}));
  return popups;
}

TEST(Fold3d, MeshFilesReadBackWithTheSameVerticesFacesAndColours) {
  const test::TempDir dir;
  for (const FoldedPopup& popup : folded_boxes(90)) {
    std::set<std::array<int, 3>> colours;
    for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
      const Rgb8 c = triangle_colour(popup, t, true);  // as the files colour it
      colours.insert({c.r, c.g, c.b});
    }
    const std::vector<OutputFile> obj = folded_mesh_files(popup, dir / "box.obj", MeshFormat::Obj);
    ASSERT_EQ(obj.size(), 2u);
    EXPECT_EQ(obj[1].path, dir / "box.mtl");
    const std::vector<OutputFile> ply = folded_mesh_files(popup, dir / "box.ply", MeshFormat::Ply);
    ASSERT_EQ(ply.size(), 1u);
    write_files({obj[0], obj[1], ply[0]});

    // OpenMesh reads both back.
    for (const char* name : {"box.obj", "box.ply"}) {
      OmMesh mesh;
      mesh.request_face_colors();
      OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceColor;
      ASSERT_TRUE(OpenMesh::IO::read_mesh(mesh, (dir / name).string(), options)) << name;
      EXPECT_EQ(mesh.n_vertices(), popup.positions.size()) << name;
      EXPECT_EQ(mesh.n_faces(), popup.triangles.size()) << name;
      EXPECT_TRUE(options.check(OpenMesh::IO::Options::FaceColor)) << name;
      std::set<std::array<int, 3>> read;
      for (const auto f : mesh.faces()) read.insert({mesh.color(f)[0], mesh.color(f)[1], mesh.color(f)[2]});
      if (std::string(name) == "box.ply") {
        EXPECT_EQ(read, colours);  // the OBJ's are Kd fractions, read back rounded
      }
      EXPECT_EQ(read.size(), colours.size()) << name;
    }

    // And by hand: OBJ lines and materials, the PLY header and its exact binary size.
    std::istringstream lines(test::read_bytes(dir / "box.obj"));
    std::size_t v = 0, f = 0;
    std::set<std::string> used;
    std::string mtllib;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("v ", 0) == 0) ++v;
      if (line.rfind("f ", 0) == 0) ++f;
      if (line.rfind("usemtl ", 0) == 0) used.insert(line.substr(7));
      if (line.rfind("mtllib ", 0) == 0) mtllib = line.substr(7);
    }
    EXPECT_EQ(v, popup.positions.size());
    EXPECT_EQ(f, popup.triangles.size());
    EXPECT_EQ(mtllib, "box.mtl");
    EXPECT_EQ(used.size(), colours.size());
    const std::string materials = test::read_bytes(dir / "box.mtl");
    for (const std::string& m : used) EXPECT_NE(materials.find("newmtl " + m + "\n"), std::string::npos) << m;

    const std::string bytes = test::read_bytes(dir / "box.ply");
    const std::size_t header_end = bytes.find("end_header\n");
    ASSERT_NE(header_end, std::string::npos);
    const std::string header = bytes.substr(0, header_end);
    EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
    EXPECT_NE(header.find("element vertex " + std::to_string(popup.positions.size()) + "\n"), std::string::npos);
    EXPECT_NE(header.find("element face " + std::to_string(popup.triangles.size()) + "\n"), std::string::npos);
    // Three floats a vertex; a count byte, three int indices and three colour bytes a face.
    EXPECT_EQ(bytes.size(), header_end + 11 + 12 * popup.positions.size() + 16 * popup.triangles.size());
  }
}

// glTF read back by tests/read_gltf.py, the container and accessors parsed by the standard library.
TEST(Fold3d, GltfAndGlbReadBackWithTheSameVerticesTrianglesAndColoursInMetres) {
  const test::TempDir dir;
  for (const FoldedPopup& popup : folded_boxes(63)) {
    const double thickness = popup.options.thickness_mm;
    // Every triangle with its colour; the file groups them by colour, so compare as multisets.
    std::multiset<std::array<int, 6>> expected;
    for (std::size_t t = 0; t < popup.triangles.size(); ++t) {
      const Rgb8 c = triangle_colour(popup, t, true);  // as the files colour it
      const auto& v = popup.triangles[t];
      expected.insert({static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), c.r, c.g, c.b});
    }
    for (const auto& [name, format] :
         {std::pair{"box.gltf", MeshFormat::Gltf}, std::pair{"box.glb", MeshFormat::Glb}}) {
      const std::vector<OutputFile> files = folded_mesh_files(popup, dir / name, format);
      ASSERT_EQ(files.size(), 1u) << name;
      write_files(files);
      const test::CommandResult r = test::shell("/usr/bin/python3 " + std::string(ORIGAMIC_TESTS_DIR) +
                                                "/read_gltf.py " + test::quoted(dir / name));
      ASSERT_EQ(r.status, 0) << name << ": " << r.output;
      const nlohmann::json read = nlohmann::json::parse(r.output);
      EXPECT_EQ(read["version"], "2.0");
      EXPECT_DOUBLE_EQ(read["extras"]["opening_angle_deg"].get<double>(), 63.0) << name;
      EXPECT_DOUBLE_EQ(read["extras"]["paper_thickness_mm"].get<double>(), thickness) << name;
      EXPECT_DOUBLE_EQ(read["extras"]["sheet_width_mm"].get<double>(), 210.0) << name;

      const auto& positions = read["positions"];
      ASSERT_EQ(positions.size(), popup.positions.size()) << name;
      std::array<double, 3> low{1e9, 1e9, 1e9}, high{-1e9, -1e9, -1e9};
      for (std::size_t i = 0; i < positions.size(); ++i)
        for (int k = 0; k < 3; ++k) {
          const double metres = positions[i][static_cast<std::size_t>(k)].get<double>();
          EXPECT_EQ(metres, static_cast<double>(static_cast<float>(popup.positions[i][k] / 1000))) << name << " " << i;
          low[static_cast<std::size_t>(k)] = std::min(low[static_cast<std::size_t>(k)], metres);
          high[static_cast<std::size_t>(k)] = std::max(high[static_cast<std::size_t>(k)], metres);
        }
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(read["min"][k].get<double>(), low[k]) << name;
        EXPECT_EQ(read["max"][k].get<double>(), high[k]) << name;
      }

      // Linear colour factors back to 8-bit sRGB.
      auto srgb = [](double linear) {
        const double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
        return static_cast<int>(std::lround(255 * c));
      };
      std::multiset<std::array<int, 6>> triangles;
      ASSERT_EQ(read["triangles"].size(), popup.triangles.size()) << name;
      for (std::size_t t = 0; t < read["triangles"].size(); ++t) {
        const auto& m = read["materials"][read["triangle_material"][t].get<std::size_t>()];
        const auto& v = read["triangles"][t];
        triangles.insert({v[0].get<int>(), v[1].get<int>(), v[2].get<int>(), srgb(m["rgba"][0].get<double>()),
                          srgb(m["rgba"][1].get<double>()), srgb(m["rgba"][2].get<double>())});
      }
      EXPECT_EQ(triangles, expected) << name;
      for (const auto& m : read["materials"]) {
        EXPECT_EQ(m["double_sided"].get<bool>(), thickness == 0) << name << ": a sheet is seen from both sides";
        EXPECT_EQ(m["metallic"].get<double>(), 0.0) << name;
      }
    }
  }
}

// The plan of a box designed from its mesh, through the exact core's regions.
Plan designed_box_plan() {
  const RayScene scene(test::box({kX0, 0, 0}, {kX1, kH, kD}));
  const Sheet sheet;
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const RasterPlan raster_plan = slice(maps, segment(maps, SegmentOptions{}), SliceOptions{});
  return build_plan(maps, raster_plan, sheet, PlanOptions{});
}

// A popup with nothing placed still makes valid glTF: an empty node, and no empty buffer.
TEST(Fold3d, AnEmptyPopupIsValidGltf) {
  const test::TempDir dir;
  std::vector<PlanRegion> regions = box_regions();
  for (PlanRegion& r : regions) r.placed = false;
  const FoldedPopup popup = fold_popup(regions, Sheet{}, {});
  ASSERT_TRUE(popup.positions.empty());
  for (const auto& [name, format] :
       {std::pair{"empty.gltf", MeshFormat::Gltf}, std::pair{"empty.glb", MeshFormat::Glb}}) {
    write_files(folded_mesh_files(popup, dir / name, format));
    const test::CommandResult r = test::shell("/usr/bin/python3 " + std::string(ORIGAMIC_TESTS_DIR) + "/read_gltf.py " +
                                              test::quoted(dir / name));
    ASSERT_EQ(r.status, 0) << name << ": " << r.output;
    EXPECT_TRUE(nlohmann::json::parse(r.output)["positions"].empty()) << name;
  }
}

TEST(Fold3d, ADesignedBoxFoldsIntoTheBoxAndFlatIntoItsPlan) {
  const Plan plan = designed_box_plan();
  ASSERT_EQ(plan.regions.size(), 4u);
  const FoldedPopup standing = fold_popup(plan.regions, plan.sheet, {});
  int on_box = 0;
  for (std::size_t i = 0; i < standing.positions.size(); ++i) {
    const PlanRegion& r = plan.regions[static_cast<std::size_t>(standing.position_region[i])];
    if (r.depth_mm == 0) continue;  // the card
    const glm::dvec3 q = standing.positions[i];
    // On the box's front (z = d) or top (y = h), within its x range to a pixel.
    const bool front = q.z == kD && q.y >= -1e-9 && q.y <= kH + 1e-9;
    const bool top = q.y == kH && q.z >= -1e-9 && q.z <= kD + 1e-9;
    EXPECT_TRUE(front || top) << "(" << q.x << ", " << q.y << ", " << q.z << ")";
    EXPECT_GE(q.x, kX0 - 0.25);
    EXPECT_LE(q.x, kX1 + 0.25);
    ++on_box;
  }
  EXPECT_GE(on_box, 8);
  const FoldedPopup flat = fold_popup(plan.regions, plan.sheet, {.angle_deg = 180});
  for (std::size_t i = 0; i < flat.positions.size(); ++i)
    expect_near3(flat.positions[i], {flat.plan_points[i].X, 0, -flat.plan_points[i].Y}, 1e-9, "flat");
}

}  // namespace
}  // namespace origamic
