// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/slice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "disc_width.hpp"
#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/likeness.hpp"
#include "origamic/placement.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

struct Planned {
  RasterMaps maps;
  Segmentation segmentation;
  RasterPlan raster_plan;
};

Planned plan_of_oa_mesh(TriangleMesh oa_mesh, double W = 3.0, bool merge_thin_slices = false) {
  Planned p;
  const RayScene scene(std::move(oa_mesh));
  p.maps = raster(scene, Sheet{}, RasterOptions{});
  p.segmentation = segment(p.maps, SegmentOptions{});
  p.raster_plan =
      slice(p.maps, p.segmentation, SliceOptions{.min_strip_mm = W, .merge_thin_slices = merge_thin_slices});
  return p;
}

TEST(Slice, BoxBecomesOneVFaceAndOneHFaceAtItsDepthAndHeight) {
  const double depth = 37.3, height = 61.7;
  const Planned p = plan_of_oa_mesh(test::box({40.2, 0, 0}, {151.9, height, depth}));
  ASSERT_EQ(p.raster_plan.faces.size(), 4u);  // back, floor, front, top
  int v = 0, h = 0;
  for (std::size_t i = 2; i < p.raster_plan.faces.size(); ++i) {
    const RasterFace& f = p.raster_plan.faces[i];
    if (f.orientation == Orientation::V) {
      ++v;
      EXPECT_NEAR(f.depth_mm, depth, 1e-6);
    } else {
      ++h;
      EXPECT_NEAR(f.depth_mm, height, 1e-6);
    }
  }
  EXPECT_EQ(v, 1);
  EXPECT_EQ(h, 1);
  const Likeness l = likeness(p.maps, card_view(p.maps.grid, p.raster_plan.face, p.raster_plan.faces), 3.0);
  EXPECT_NEAR(l.p95_mm, 0.0, 1e-6);
  EXPECT_NEAR(l.mean_mm, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(l.coverage, 1.0);
}

// Faces' widths along X and Y, in pixels: (max col - min col + 1), (max row - min row + 1).
std::map<std::int32_t, std::pair<int, int>> face_extents(const Grid<std::int32_t>& face) {
  std::map<std::int32_t, std::array<int, 4>> box;
  for (int row = 0; row < face.rows; ++row)
    for (int col = 0; col < face.cols; ++col) {
      auto [it, fresh] = box.try_emplace(face(col, row), std::array<int, 4>{col, col, row, row});
      auto& b = it->second;
      b = {std::min(b[0], col), std::max(b[1], col), std::min(b[2], row), std::max(b[3], row)};
    }
  std::map<std::int32_t, std::pair<int, int>> extents;
  for (const auto& [id, b] : box) extents[id] = {b[1] - b[0] + 1, b[3] - b[2] + 1};
  return extents;
}

TEST(Slice, HalfCylinderBecomesVerticalSlicesNoNarrowerThanW) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  DesignOptions options;
  options.placement.up = UpAxis::Z;
  options.supports.enabled = false;  // the slices as sliced
  const DesignResult r = design(test::models_dir() / "seedlike/half_cylinder.stl", options);
  const double W = options.slice.min_strip_mm, W_px = W * r.maps.grid.px_per_mm;
  const auto extents = face_extents(r.raster_plan.face);
  // Curved-side faces: V, each of one constant depth, at least W wide; d falls from the centre out.
  std::vector<std::pair<double, double>> centre_and_depth;
  const double mid_X = (r.placement.min_oa.x + r.placement.max_oa.x) / 2;
  for (std::size_t i = 2; i < r.raster_plan.faces.size(); ++i) {
    const RasterFace& f = r.raster_plan.faces[i];
    if (f.orientation == Orientation::H) continue;  // the flat top
    const auto [w_px, h_px] = extents.at(static_cast<std::int32_t>(i));
    EXPECT_GE(w_px, W_px - 1) << "face " << i;
    double sum_X = 0;
    std::int64_t n = 0;
    for (int row = 0; row < r.raster_plan.face.rows; ++row)
      for (int col = 0; col < r.raster_plan.face.cols; ++col)
        if (r.raster_plan.face(col, row) == static_cast<std::int32_t>(i)) sum_X += r.maps.grid.X(col), ++n;
    centre_and_depth.emplace_back(std::abs(sum_X / static_cast<double>(n) - mid_X), f.depth_mm);
  }
  ASSERT_GE(centre_and_depth.size(), 8u);
  std::ranges::sort(centre_and_depth);
  for (std::size_t i = 1; i < centre_and_depth.size(); ++i)
    EXPECT_LE(centre_and_depth[i].second, centre_and_depth[i - 1].second + W / 2)
        << "depth must fall away from the centre";
  EXPECT_GT(centre_and_depth.front().second, centre_and_depth.back().second + 2 * W);
  // The pop-up stays within W of the model in depth: 2 W in h + d along the 45-degree ray.
  EXPECT_LE(r.sliced_likeness.p95_mm, 2 * W);
}

TEST(Slice, FaceCountFallsAsWGrowsAndNoFaceIsNarrowerThanW) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  for (const char* model : {"seedlike/half_cylinder.stl", "seedlike/wedge.stl", "seedlike/quarter_sphere.stl"}) {
    SCOPED_TRACE(model);
    std::size_t previous = SIZE_MAX;
    for (const double W : {2.0, 4.0, 8.0}) {
      DesignOptions options;
      options.placement.up = UpAxis::Z;
      options.slice.min_strip_mm = W;
      options.supports.enabled = false;
      options.keep_normals = true;  // read below
      const DesignResult r = design(test::models_dir() / model, options);
      EXPECT_LT(r.raster_plan.faces.size(), previous) << "W = " << W;
      previous = r.raster_plan.faces.size();
      // V where the model is steeper than 55 degrees, H where it is flatter than 35: nearly every
      // such pixel (slivers under W join a neighbour whatever its orientation).
      std::int64_t decisive = 0, agreeing = 0;
      for (int row = 0; row < r.raster_plan.face.rows; ++row)
        for (int col = 0; col < r.raster_plan.face.cols; ++col) {
          const std::int32_t f = r.raster_plan.face(col, row);
          if (f < 2 || r.maps.kind(col, row) != HitKind::Model) continue;
          const glm::vec3 n = r.maps.normal(col, row);
          const float steep = std::abs(n.z), flat = std::abs(n.y), tan_35 = 0.7002f;
          if (flat >= steep * tan_35 && steep >= flat * tan_35) continue;
          ++decisive;
          agreeing += r.raster_plan.faces[static_cast<std::size_t>(f)].orientation ==
                      (flat < steep * tan_35 ? Orientation::V : Orientation::H);
        }
      EXPECT_GE(agreeing, decisive * 98 / 100) << "W = " << W;
      std::map<std::int32_t, std::vector<std::pair<int, int>>> pixels_of;
      for (int row = 0; row < r.raster_plan.face.rows; ++row)
        for (int col = 0; col < r.raster_plan.face.cols; ++col)
          if (r.raster_plan.face(col, row) >= 2) pixels_of[r.raster_plan.face(col, row)].emplace_back(col, row);
      for (const auto& [id, pixels] : pixels_of)
        EXPECT_GE(oriented_box_min_side_px(pixels), W * r.maps.grid.px_per_mm - 1) << "face " << id << " W " << W;
    }
  }
}

TEST(Slice, ARoofRisingToTheBackPlaneEndsOnItsFoldThereNotBehindIt) {
  // A ramp 35 mm high at the back plane, 60 mm deep on the floor: a 30-degree roof, sliced into H
  // terraces at their mean heights. The top terrace's back reaches Y = 35 in the plan, above its
  // mean height: that part would lie behind the back plane. It is the back plane's.
  TriangleMesh ramp;
  ramp.positions = {{40, 0, 0}, {40, 0, 60}, {40, 35, 0}, {150, 0, 0}, {150, 0, 60}, {150, 35, 0}};
  ramp.triangles = {{0, 1, 2}, {3, 5, 4}, {1, 4, 5}, {1, 5, 2}, {0, 3, 4}, {0, 4, 1}, {0, 2, 5}, {0, 5, 3}};
  const Planned p = plan_of_oa_mesh(ramp);
  const PixelGrid& grid = p.maps.grid;
  int terraces = 0;
  double top = 0;
  for (std::size_t f = 2; f < p.raster_plan.faces.size(); ++f)
    if (p.raster_plan.faces[f].orientation == Orientation::H)
      ++terraces, top = std::max(top, p.raster_plan.faces[f].depth_mm);
  EXPECT_GE(terraces, 10) << "one terrace per W of the 35 mm rise";
  EXPECT_LT(top, 35.0);
  int top_rows_below_back_plane = 0;
  for (int row = 0; row + 1 < grid.rows; ++row)
    for (int col = 0; col < grid.cols; ++col) {
      const std::int32_t f = p.raster_plan.face(col, row);
      ASSERT_GE(f, 0);
      const RasterFace& face = p.raster_plan.faces[static_cast<std::size_t>(f)];
      if (f >= 2 && face.orientation == Orientation::H) {
        EXPECT_LE(grid.Y(row), face.depth_mm) << col << ", " << row;
      }
      if (f >= 2 && face.orientation == Orientation::V) {
        EXPECT_GE(grid.Y(row), -face.depth_mm) << col << ", " << row;
      }
      // The top terrace meets the back plane on its fold line Y = h, to the pixel.
      if (f == kBackFace && grid.X(col) > 45 && grid.X(col) < 145 && p.raster_plan.face(col, row + 1) >= 2 &&
          p.raster_plan.faces[static_cast<std::size_t>(p.raster_plan.face(col, row + 1))].depth_mm == top) {
        EXPECT_NEAR(grid.Y(row) - 0.5 / grid.px_per_mm, top, 1 / grid.px_per_mm);
        ++top_rows_below_back_plane;
      }
    }
  EXPECT_GT(top_rows_below_back_plane, static_cast<int>(90 * grid.px_per_mm)) << "folded to the back plane all along";
}

TEST(Slice, TheLowestTerraceOfARampStandsAtLeastWAboveTheFloor) {
  // The ramp above: its lowest terrace is held on the floor by a riser as tall as the terrace is
  // high, a strip between two folds. Its levels begin W / 2 up, the lowest kept W above the floor.
  TriangleMesh ramp;
  ramp.positions = {{40, 0, 0}, {40, 0, 60}, {40, 35, 0}, {150, 0, 0}, {150, 0, 60}, {150, 35, 0}};
  ramp.triangles = {{0, 1, 2}, {3, 5, 4}, {1, 4, 5}, {1, 5, 2}, {0, 3, 4}, {0, 4, 1}, {0, 2, 5}, {0, 5, 3}};
  for (const double W : {2.0, 3.0, 5.0}) {
    SCOPED_TRACE(W);
    const Planned p = plan_of_oa_mesh(ramp, W);
    double lowest = 35;
    int terraces = 0;
    for (std::size_t f = 2; f < p.raster_plan.faces.size(); ++f)
      if (const RasterFace& face = p.raster_plan.faces[f]; face.orientation == Orientation::H && face.pixels > 0)
        ++terraces, lowest = std::min(lowest, face.depth_mm);
    EXPECT_GE(terraces, 35 / W - 2);
    EXPECT_GE(lowest, W);
    EXPECT_LT(lowest, 2 * W);
  }
}

TEST(Slice, ThinPoleIsRemovedAndItsHoleFilled) {
  // A box with a 1 mm pole standing in front of it; W = 3 mm. Beside the pole where it stands
  // before the box lie the box's pixels, no background to widen it over: it goes.
  const TriangleMesh house = test::box({60, 0, 0}, {150, 50, 30});
  const TriangleMesh pole = test::box({100, 0, 50}, {101, 80, 51});
  const Planned p = plan_of_oa_mesh(test::merged(house, pole));
  for (int row = 0; row < p.maps.grid.rows; ++row)
    for (int col = 0; col < p.maps.grid.cols; ++col) {
      const std::int32_t f = p.raster_plan.face(col, row);
      ASSERT_GE(f, 0);
      // No face stands at the pole's depth (50 .. 51 mm) or on its top (80 mm).
      const RasterFace& face = p.raster_plan.faces[static_cast<std::size_t>(f)];
      EXPECT_LT(face.depth_mm, face.orientation == Orientation::V ? 49.0 : 79.0);
    }
  EXPECT_GE(p.raster_plan.removed_thin, 1);
  EXPECT_EQ(p.raster_plan.widened_thin, 0);
  EXPECT_EQ(p.raster_plan.faces.size(), 4u);  // back, floor, and the house's front and top
}

// A pole 1 mm square and 80 mm tall standing on the floor 50 mm before the back plane, alone: W =
// 3 mm wide it can be cut, so it is kept, each row of its front widened along X over the back plane
// and the floor beside it to W and a pixel (13 pixels at 4 px/mm). Its model pixels all lie in its
// face, which takes no pixel of the model beyond them; its top, a square 1 mm across, goes.
TEST(Slice, AThinPoleStandingClearIsWidenedToWOverTheBackPlaneAndTheFloor) {
  const Planned p = plan_of_oa_mesh(test::box({100, 0, 50}, {101, 80, 51}));
  const PixelGrid& grid = p.maps.grid;
  std::int32_t pole = -1;
  for (std::size_t f = kFloorFace + 1; f < p.raster_plan.faces.size(); ++f)
    if (p.raster_plan.faces[f].orientation == Orientation::V && p.raster_plan.faces[f].pixels > 0)
      pole = static_cast<std::int32_t>(f);
  ASSERT_GE(pole, 0);
  EXPECT_NEAR(p.raster_plan.faces[static_cast<std::size_t>(pole)].depth_mm, 51, 0.5);
  EXPECT_GE(p.raster_plan.removed_thin, 1);  // the top
  EXPECT_EQ(p.raster_plan.widened_thin, 1);
  int rows = 0;
  for (int r = 0; r < grid.rows; ++r) {
    int first = -1, last = -1, runs = 0;
    for (int c = 0; c < grid.cols; ++c) {
      const bool in = p.raster_plan.face(c, r) == pole;
      if (in && (c == 0 || p.raster_plan.face(c - 1, r) != pole)) ++runs, first = c;
      if (in) last = c;
      // Model pixels in the pole's rows are the pole's; the face's others are the back plane's or
      // the floor's pixels, no model's.
      if (p.maps.kind(c, r) == HitKind::Model && p.raster_plan.face(c, r) != pole) {
        const RasterFace& other = p.raster_plan.faces[static_cast<std::size_t>(p.raster_plan.face(c, r))];
        EXPECT_NE(other.orientation, Orientation::V) << c << ", " << r;  // only the pole's top, filled
      }
    }
    if (runs == 0) continue;
    ++rows;
    EXPECT_EQ(runs, 1) << r;
    EXPECT_EQ(last - first + 1, static_cast<int>(std::ceil(3 * grid.px_per_mm)) + 1) << r;
    EXPECT_LE(grid.X(first), 100);
    EXPECT_GE(grid.X(last), 101);
  }
  EXPECT_GE(rows, 79 * grid.px_per_mm);  // the front, 80 mm tall, less a pixel's rounding at each end
}

// A plate 1.5 mm wide against the left side of a box, its front 10 mm behind the box's: too thin to
// be a face, its pixels are filled from the faces of the model beside them, not from the back plane
// and the floor behind (which had taken the half of each row nearer them: a card showing the
// background where the model is; over the 37 models at W = 3 mm the mean p95 1.80 -> 1.77 W, the
// lowest coverage 96.8 -> 98.8%).
TEST(Slice, AThinPieceBesideTheModelIsFilledFromItsFaces) {
  const TriangleMesh house = test::box({60, 0, 0}, {150, 50, 30});
  const TriangleMesh plate = test::box({58.5, 0, 0}, {60, 50, 20});
  const Planned p = plan_of_oa_mesh(test::merged(house, plate));
  EXPECT_GE(p.raster_plan.removed_thin, 1);
  // The plate's front, X 58.5 to 60, Y = h - 20 from -20 to 30 (a pixel in from each side).
  int background = 0, model = 0;
  for (int row = 0; row < p.maps.grid.rows; ++row)
    for (int col = 0; col < p.maps.grid.cols; ++col)
      if (const double X = p.maps.grid.X(col), Y = p.maps.grid.Y(row);
          58.75 <= X && X <= 59.75 && -19.75 <= Y && Y <= 29.75)
        ++(p.raster_plan.face(col, row) == kBackFace || p.raster_plan.face(col, row) == kFloorFace ? background
                                                                                                   : model);
  EXPECT_GT(model, 4 * 190);
  EXPECT_EQ(background, 0);
}

// A low-poly model's file normals, one per vertex and averaged over the faces around it, turn 55
// degrees from every face of a box; the loader gives each face its own, and the box slices as it
// does with no normals in its file: one front, one top.
TEST(Slice, ABoxWithNormalsAveragedAtItsCornersSlicesAsTheBoxWithout) {
  const test::TempDir dir;
  test::write_text(dir / "plain.obj", test::box_obj({80, 50, 40}, false));
  test::write_text(dir / "normals.obj", test::box_obj({80, 50, 40}, true));
  DesignOptions options;
  options.supports.enabled = false;
  const DesignResult plain = design(dir / "plain.obj", options), with_normals = design(dir / "normals.obj", options);
  EXPECT_EQ(plain.segmentation.count, 4);  // back, floor, front, top
  EXPECT_EQ(with_normals.segmentation.count, plain.segmentation.count);
  ASSERT_EQ(with_normals.raster_plan.faces.size(), 4u);
  EXPECT_EQ(with_normals.raster_plan.face.values, plain.raster_plan.face.values);
}

// A plate of `count` slats 2 mm wide side by side from X = 60 mm, hanging from h 50 to 80 mm (a
// lattice sail), each from depth 15 mm to its front, `front` and `front` + 1 mm in turn: each front
// is a segment of its own and thinner than W = 3.
TriangleMesh slatted_plate(double front = 20.5, int count = 20) {
  TriangleMesh plate;
  for (int j = 0; j < count; ++j)
    plate = test::merged(plate, test::box({60.0 + 2 * j, 50, 15}, {62.0 + 2 * j, 80, j % 2 ? front + 1 : front}));
  return plate;
}

// Faces of the plan at the pixels whose centres lie in the plan box [X0, X1] x [Y0, Y1].
std::set<std::int32_t> faces_in(const Planned& p, double X0, double X1, double Y0, double Y1) {
  std::set<std::int32_t> faces;
  for (int row = 0; row < p.maps.grid.rows; ++row)
    for (int col = 0; col < p.maps.grid.cols; ++col)
      if (const double X = p.maps.grid.X(col), Y = p.maps.grid.Y(row); X0 <= X && X <= X1 && Y0 <= Y && Y <= Y1)
        faces.insert(p.raster_plan.face(col, row));
  return faces;
}

TEST(Slice, ThinPiecesInOnePlaneBeforeTheBackPlaneAreOneFace) {
  const Planned p = plan_of_oa_mesh(slatted_plate());
  ASSERT_GE(p.segmentation.count, 2 + 20);
  // The fronts, Y = h - d from 50 - 20.5 to 80 - 21.5 (a pixel in from each side): one V face at
  // their mean depth, 21 mm.
  const std::set<std::int32_t> front = faces_in(p, 61, 99, 30, 58);
  ASSERT_EQ(front.size(), 1u);
  const RasterFace& face = p.raster_plan.faces[static_cast<std::size_t>(*front.begin())];
  EXPECT_EQ(face.orientation, Orientation::V);
  EXPECT_NEAR(face.depth_mm, 21.0, 0.05);
  // The slats' tops, 2 mm wide each: one H face at 80 mm, from Y = 80 - 20.5 up to 80 - 15.
  const std::set<std::int32_t> top = faces_in(p, 61, 99, 60, 64.5);
  ASSERT_EQ(top.size(), 1u);
  EXPECT_EQ(p.raster_plan.faces[static_cast<std::size_t>(*top.begin())].orientation, Orientation::H);
  EXPECT_DOUBLE_EQ(p.raster_plan.faces[static_cast<std::size_t>(*top.begin())].depth_mm, 80.0);
}

// Four slats against a wall, their fronts 2.5 and 3.5 mm proud of it (in h + d, 5 and 7 mm: under
// 2 W beside half of them): among the model's faces they are a detail (2% of it), filled from the
// faces around, and the thin pieces count as removed one by one.
TEST(Slice, ThinPiecesInOnePlaneJustProudOfAModelFaceAreFilledFromIt) {
  const TriangleMesh wall = test::box({30, 0, 0}, {130, 100, 15});
  const Planned p = plan_of_oa_mesh(test::merged(wall, slatted_plate(17.5, 4)));
  for (const std::int32_t f : faces_in(p, 61, 67, 30, 58)) {
    ASSERT_GE(f, 0);
    const RasterFace& face = p.raster_plan.faces[static_cast<std::size_t>(f)];
    // The wall's front, or the slats' tops grown down over them.
    EXPECT_TRUE(face.orientation == Orientation::V ? face.depth_mm == 15.0 : face.depth_mm == 80.0)
        << (face.orientation == Orientation::V ? "V " : "H ") << face.depth_mm;
  }
  EXPECT_EQ(p.raster_plan.removed_thin, 4);  // the four fronts, joined and filled
}

// The one face the slats' fronts become, at their mean depth (not filled from the wall at 15 mm).
void expect_slats_one_face(const Planned& p, double X1, double depth_mm) {
  const std::set<std::int32_t> front = faces_in(p, 61, X1, 34, 58);
  ASSERT_EQ(front.size(), 1u);
  const RasterFace& face = p.raster_plan.faces[static_cast<std::size_t>(*front.begin())];
  EXPECT_EQ(face.orientation, Orientation::V);
  EXPECT_NEAR(face.depth_mm, depth_mm, 0.05);
}

// The same four slats half a millimetre farther out, 3 and 4 mm proud (6 and 8 mm in h + d, 2 W and
// more), stand in front of the wall as a sail of arch_windmill before its tower (at W = 5 mm three
// of its four sails had been filled from the tower: p95 9.7 W, a quarter of the model lost): one
// face at their mean depth, as before the back plane.
TEST(Slice, ThinPiecesInOnePlaneStandingWBeforeAModelFaceAreOneFace) {
  const TriangleMesh wall = test::box({30, 0, 0}, {130, 100, 15});
  expect_slats_one_face(plan_of_oa_mesh(test::merged(wall, slatted_plate(18.0, 4))), 67, 18.5);
}

// Twenty slats 1.5 and 2.5 mm proud of the wall are 10% of the model: a part of it, not a detail
// (the windmill's sails on a 150 x 150 mm card, under W in front of the tower: p95 7.6 -> 1.3 W).
TEST(Slice, ThinPiecesInOnePlaneHoldingAShareOfTheModelAreOneFace) {
  const TriangleMesh wall = test::box({30, 0, 0}, {130, 100, 15});
  expect_slats_one_face(plan_of_oa_mesh(test::merged(wall, slatted_plate(16.5))), 99, 17.0);
}

// Two slices of one curved surface that touch lie W apart or more: the face a support folds between
// them is then no strip narrower than W (issue 23). A slice at its pixels' mean depth alone came
// nearer: on a sphere the pixels of a level crowd to its near side where the surface turns away.
TEST(Slice, TouchingSlicesOfASphereLieAtLeastWApart) {
  for (const double W : {3.0, 5.0}) {
    SCOPED_TRACE(W);
    const Planned p = plan_of_oa_mesh(test::sphere({105, 50, 50}, 44, 96, 48), W);
    const Grid<std::int32_t>& face = p.raster_plan.face;
    const std::vector<RasterFace>& faces = p.raster_plan.faces;
    std::set<std::pair<std::int32_t, std::int32_t>> touching;
    for (int row = 0; row + 1 < face.rows; ++row)
      for (int col = 0; col + 1 < face.cols; ++col)
        for (const std::int32_t g : {face(col + 1, row), face(col, row + 1)}) {
          const std::int32_t f = face(col, row);
          if (f >= 2 && g >= 2 && f != g) touching.emplace(std::min(f, g), std::max(f, g));
        }
    int same_orientation = 0;
    for (const auto& [f, g] : touching) {
      const RasterFace &a = faces[static_cast<std::size_t>(f)], &b = faces[static_cast<std::size_t>(g)];
      if (a.hole || b.hole || a.orientation != b.orientation) continue;
      ++same_orientation;
      EXPECT_GE(std::abs(a.depth_mm - b.depth_mm), W - 1e-9) << "faces " << f << " and " << g;  // to rounding
    }
    EXPECT_GE(same_orientation, 10);
  }
}

// Where a sphere turns sideways its levels crowd into crescents narrower than W, though their
// boxes are wide; merged, none is left but where no neighbour of its segment takes it.
TEST(Slice, ThinSlicesMergedLeaveNoCrescentNarrowerThanW) {
  const TriangleMesh sphere = test::sphere({105, 50, 50}, 44, 96, 48);
  const auto thin_faces = [](const Planned& p) {
    std::vector<std::vector<std::pair<int, int>>> pixels(p.raster_plan.faces.size());
    for (int row = 0; row < p.raster_plan.face.rows; ++row)
      for (int col = 0; col < p.raster_plan.face.cols; ++col)
        if (const std::int32_t f = p.raster_plan.face(col, row); f >= 2)
          pixels[static_cast<std::size_t>(f)].emplace_back(col, row);
    int thin = 0, boxed = 0;  // narrower than W everywhere; of them, with no side of their box under W
    const double W_px = p.raster_plan.min_strip_mm * p.maps.grid.px_per_mm;
    for (const auto& of_face : pixels)
      if (!of_face.empty() && widest_disc_px(of_face) < W_px)
        ++thin, boxed += oriented_box_min_side_px(of_face) >= W_px;
    return std::pair{thin, boxed};
  };
  EXPECT_GE(thin_faces(plan_of_oa_mesh(sphere)).second, 4);  // crescents
  EXPECT_EQ(thin_faces(plan_of_oa_mesh(sphere, 3.0, true)).first, 0);
}

TEST(Slice, SameInputGivesByteIdenticalFaceMaps) {
  const TriangleMesh shape = test::sphere({105, 40, 40}, 38, 96, 48);
  const Planned a = plan_of_oa_mesh(shape), b = plan_of_oa_mesh(shape);
  EXPECT_EQ(a.raster_plan.face.values, b.raster_plan.face.values);
  EXPECT_EQ(a.segmentation.segment.values, b.segmentation.segment.values);
  ASSERT_EQ(a.raster_plan.faces.size(), b.raster_plan.faces.size());
  for (std::size_t i = 0; i < a.raster_plan.faces.size(); ++i)
    EXPECT_EQ(a.raster_plan.faces[i].depth_mm, b.raster_plan.faces[i].depth_mm);
}

TEST(Slice, OrientedBoxOfADiagonalLineIsOnePixelThin) {
  std::vector<std::pair<int, int>> line;
  for (int i = 0; i < 50; ++i) line.emplace_back(i, i);
  EXPECT_LT(oriented_box_min_side_px(line), 2.5);
  std::vector<std::pair<int, int>> square;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) square.emplace_back(i, j);
  EXPECT_NEAR(oriented_box_min_side_px(square), 12.0, 1e-9);
}

}  // namespace
}  // namespace origamic

namespace origamic {
namespace {

// A face cut in three by a column of another face: the largest part keeps its id, the other
// becomes a face of its own with the same plane, and a crumb joins the face it touches most.
TEST(Slice, FacesInPartsBecomeOneFacePerPartAndCrumbsJoinANeighbour) {
  RasterPlan s;
  s.face = Grid<std::int32_t>(12, 6, kBackFace);
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::H, 7.5}, {Orientation::V, 3}};
  for (int r = 1; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) s.face(c, r) = 2;   // 20 px
    for (int c = 6; c < 9; ++c) s.face(c, r) = 2;   // 12 px
    s.face(5, r) = s.face(9, r) = 3;
  }
  s.face(10, 2) = 2;  // a crumb, touching face 3 on one side and the back plane on three
  SplitFaces split = split_disconnected_faces(std::move(s), {2}, 2, 0);
  s = std::move(split.raster_plan);
  const std::vector<FacePart>& parts = split.parts;
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].face, 4);
  EXPECT_EQ(parts[0].from, 2);
  ASSERT_EQ(s.faces.size(), 5u);
  EXPECT_EQ(s.faces[4].orientation, Orientation::H);
  EXPECT_EQ(s.faces[4].depth_mm, 7.5);
  EXPECT_EQ(s.faces[2].pixels, 20);
  EXPECT_EQ(s.faces[4].pixels, 12);
  EXPECT_EQ(s.face(7, 3), 4);
  EXPECT_EQ(s.face(0, 1), 2);
  EXPECT_EQ(s.face(10, 2), kBackFace);
}

// Parts are 4-connected: a U whose arms meet only in its bottom row is one part, a square touching
// it at a corner only is another, and the largest part keeps the id whatever order it is met in.
TEST(Slice, AFaceIsInPartsOnlyWhereNoPathOfSidesJoinsThem) {
  RasterPlan s;
  s.face = Grid<std::int32_t>(10, 7, kBackFace);
  s.faces = {{Orientation::V, 0}, {Orientation::H, 0}, {Orientation::V, 4}};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) s.face(c, r) = 2;               // the square: 4 px, met first in row-major order
  for (int r = 2; r < 7; ++r) s.face(2, r) = s.face(6, r) = 2;  // the U's arms, 5 px each
  for (int c = 3; c < 6; ++c) s.face(c, 6) = 2;                 // its bottom: 3 px
  SplitFaces split = split_disconnected_faces(std::move(s), {2}, 1, 0);
  s = std::move(split.raster_plan);
  const std::vector<FacePart>& parts = split.parts;
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].from, 2);
  EXPECT_EQ(s.faces[2].pixels, 13) << "the U keeps the id";
  EXPECT_EQ(s.faces[static_cast<std::size_t>(parts[0].face)].pixels, 4);
  EXPECT_EQ(s.face(0, 0), parts[0].face);
  EXPECT_EQ(s.face(1, 1), parts[0].face);
  EXPECT_EQ(s.face(2, 2), 2);
  EXPECT_EQ(s.face(6, 2), 2);
  EXPECT_EQ(s.face(4, 6), 2);
}

}  // namespace
}  // namespace origamic
