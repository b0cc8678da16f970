// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/raster.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>

#include "helpers.hpp"
#include "origamic/error.hpp"
#include "origamic/placement.hpp"
#include "origamic/raster_images.hpp"

namespace origamic {
namespace {

// Pixel centres strictly inside (a, b) along an axis of px_per_mm, counted from the interval's size.
double expected_pixels(double a, double b, double px_per_mm) { return (b - a) * px_per_mm; }

struct PixelBox {
  int count = 0;
  int min_col = 1 << 30, max_col = -1, min_row = 1 << 30, max_row = -1;
  void add(int col, int row) {
    ++count;
    min_col = std::min(min_col, col);
    max_col = std::max(max_col, col);
    min_row = std::min(min_row, row);
    max_row = std::max(max_row, row);
  }
  int cols() const { return max_col - min_col + 1; }
  int rows() const { return max_row - min_row + 1; }
};

// A box standing on the floor against the back plane, already in OA mm (x, h, d).
constexpr double kX0 = 40.2, kX1 = 151.9, kHeight = 61.7, kDepth = 37.3;

RasterMaps box_maps(double px_per_mm = 4.0) {
  const RayScene scene(test::box({kX0, 0, 0}, {kX1, kHeight, kDepth}));
  return raster(scene, Sheet{}, RasterOptions{.px_per_mm = px_per_mm});
}

TEST(Raster, GridCoversTheDefaultSheetWithAboutOneMegapixel) {
  const PixelGrid grid = PixelGrid::covering(Sheet{}, 4.0);
  EXPECT_EQ(grid.cols, 840);
  EXPECT_EQ(grid.rows, 1188);
  EXPECT_EQ(grid.rows_above_fold, 594);
  EXPECT_DOUBLE_EQ(grid.Y(593), 0.125);  // the main fold is the boundary between rows 593 and 594
  EXPECT_DOUBLE_EQ(grid.Y(594), -0.125);
}

// The box's outline breaks the picture where the box puts it, between pixel centres: its side
// x = 40.2 against the back plane (0.3 of the way from the centre at 40.125 to 40.375), its top's
// back edge at Y = h = 61.7 against the back plane (0.7 down from 61.875), and the crease between
// its front and top at Y = h - d = 24.4 (0.9 down from 24.625). Nothing breaks inside a face.
TEST(Raster, TheBoxsEdgesBreakThePictureBetweenPixelCentres) {
  const RasterMaps maps = box_maps();
  const PixelGrid& grid = maps.grid;
  // The row (column) whose centre is the last above Y (left of X).
  const auto row_at = [&](double Y) {
    return static_cast<int>(std::floor(grid.rows_above_fold - Y * grid.px_per_mm - 0.5));
  };
  const auto col_at = [&](double X) { return static_cast<int>(std::floor(X * grid.px_per_mm - 0.5)); };
  const double step = 1.0 / 1024;  // the bisection's resolution, of the way between centres
  ASSERT_DOUBLE_EQ(grid.X(col_at(40.2)), 40.125);
  EXPECT_NEAR(maps.break_right(col_at(40.2), row_at(-10)), 0.3, step);
  ASSERT_DOUBLE_EQ(grid.Y(row_at(61.7)), 61.875);
  EXPECT_NEAR(maps.break_below(col_at(100), row_at(61.7)), 0.7, step);
  ASSERT_DOUBLE_EQ(grid.Y(row_at(24.4)), 24.625);
  EXPECT_NEAR(maps.break_below(col_at(100), row_at(24.4)), 0.9, step);
  for (const double Y : {-10.0, 10.0, 40.0}) {  // the front, the top
    EXPECT_TRUE(std::isnan(maps.break_right(col_at(100), row_at(Y)))) << Y;
    EXPECT_TRUE(std::isnan(maps.break_below(col_at(100), row_at(Y)))) << Y;
  }
  EXPECT_TRUE(std::isnan(maps.break_below(col_at(20), row_at(61.7)))) << "the back plane alone";
}

TEST(Raster, BoxFrontFaceHasItsExactDepthAndExtent) {
  const RasterMaps maps = box_maps();
  PixelBox front, top;
  for (int row = 0; row < maps.grid.rows; ++row)
    for (int col = 0; col < maps.grid.cols; ++col) {
      if (maps.kind(col, row) != HitKind::Model) continue;
      if (std::abs(maps.d_mm(col, row) - kDepth) <= 1e-6) front.add(col, row);
      if (std::abs(maps.h_mm(col, row) - kHeight) <= 1e-6) top.add(col, row);
      EXPECT_NEAR(maps.h_mm(col, row) - maps.d_mm(col, row), maps.grid.Y(row), 1e-9);
    }
  // Front: X in (x0, x1), Y = h - d in (-depth, height - depth); top: Y in (height - depth, height).
  EXPECT_NEAR(front.cols(), expected_pixels(kX0, kX1, 4), 1.0);
  EXPECT_NEAR(front.rows(), expected_pixels(-kDepth, kHeight - kDepth, 4), 1.0);
  EXPECT_NEAR(top.cols(), expected_pixels(kX0, kX1, 4), 1.0);
  EXPECT_NEAR(top.rows(), expected_pixels(kHeight - kDepth, kHeight, 4), 1.0);
  EXPECT_EQ(front.count, front.cols() * front.rows());  // solid rectangles
  EXPECT_EQ(top.count, top.cols() * top.rows());
  EXPECT_EQ(maps.model_pixels, static_cast<std::size_t>(front.count + top.count));
}

TEST(Raster, FrontDepthIsConstantOnVerticalFacesAndTopDepthOnHorizontalOnes) {
  const RasterMaps maps = box_maps();
  const NormalisedDepths depths = normalised_depths(maps);
  std::vector<float> front_F, top_T, back_F, floor_T;
  for (int row = 0; row < maps.grid.rows; ++row)
    for (int col = 0; col < maps.grid.cols; ++col) {
      const HitKind kind = maps.kind(col, row);
      if (kind == HitKind::Model && maps.d_mm(col, row) == kDepth) {
        front_F.push_back(depths.F(col, row));
        EXPECT_EQ(maps.normal(col, row), glm::vec3(0, 0, 1));
      }
      if (kind == HitKind::Model && maps.h_mm(col, row) == kHeight) {
        top_T.push_back(depths.T(col, row));
        EXPECT_EQ(maps.normal(col, row), glm::vec3(0, 1, 0));
      }
      if (kind == HitKind::Back) back_F.push_back(depths.F(col, row));
      if (kind == HitKind::Floor) floor_T.push_back(depths.T(col, row));
    }
  for (const auto* values : {&front_F, &top_T, &back_F, &floor_T}) {
    ASSERT_FALSE(values->empty());
    EXPECT_EQ(std::ranges::count(*values, values->front()), static_cast<long>(values->size()));
  }
  // Normalised as in §4.1: the back plane is the furthest vertical face, the floor the lowest one.
  EXPECT_EQ(back_F.front(), 1.0f);
  EXPECT_EQ(floor_T.front(), 1.0f);
  EXPECT_LT(front_F.front(), back_F.front());
  EXPECT_NEAR(front_F.front(), (maps.reference.front_d_mm - kDepth) / maps.reference.front_d_mm, 1e-6);
}

TEST(Raster, BackAndFloorAreTheSignOfY) {
  const RasterMaps maps = box_maps(2.0);
  for (int row = 0; row < maps.grid.rows; ++row)
    for (int col = 0; col < maps.grid.cols; ++col) {
      const double Y = maps.grid.Y(row);
      switch (maps.kind(col, row)) {
        case HitKind::Back:
          ASSERT_GT(Y, 0);
          ASSERT_EQ(maps.d_mm(col, row), 0.0);
          ASSERT_EQ(maps.h_mm(col, row), Y);
          break;
        case HitKind::Floor:
          ASSERT_LT(Y, 0);
          ASSERT_EQ(maps.h_mm(col, row), 0.0);
          ASSERT_EQ(maps.d_mm(col, row), -Y);
          break;
        case HitKind::Model:
          ASSERT_GT(maps.grid.X(col), kX0);
          ASSERT_LT(maps.grid.X(col), kX1);
          break;
        case HitKind::Outside:
          FAIL() << "the default sheet is covered exactly";
      }
    }
}

TEST(Raster, SphereDepthMatchesTheClosedForm) {
  const glm::dvec3 c(105.3, 70.1, 40.2);
  const double r = 30;
  const RayScene scene(test::sphere(c, r, 512, 256));
  const RasterMaps maps = raster(scene, Sheet{}, RasterOptions{});
  // The pixel whose centre is nearest the centre's plan point, and a few around it.
  const int col0 = static_cast<int>(c.x * 4), row0 = maps.grid.rows_above_fold - static_cast<int>((c.y - c.z) * 4);
  for (int dr = -8; dr <= 8; dr += 4)
    for (int dc = -8; dc <= 8; dc += 4) {
      const int col = col0 + dc, row = row0 + dr;
      const double X = maps.grid.X(col), Y = maps.grid.Y(row);
      // |(X, Y + d, d) - c| = r, the root nearest the viewer.
      const double a = Y - c.y, k = r * r - (X - c.x) * (X - c.x);
      const double b = a - c.z;
      const double d = (-b + std::sqrt(b * b - 2 * (a * a + c.z * c.z - k))) / 2;
      ASSERT_EQ(maps.kind(col, row), HitKind::Model);
      // The facets of 512 x 256 lie within r (1 - cos(pi/256)) = 0.0023 mm of the sphere.
      EXPECT_NEAR(maps.d_mm(col, row), d, 0.004) << col << "," << row;
      const glm::dvec3 radial = (glm::dvec3(X, Y + d, d) - c) / r;
      EXPECT_GT(glm::dot(glm::dvec3(maps.normal(col, row)), radial), 0.9999);
    }
}

TEST(Raster, PixelCentresBeyondTheSheetAreOutside) {
  const RayScene scene(test::box({10, 0, 0}, {20, 10, 10}));
  const RasterMaps maps = raster(scene, Sheet{100.5, 60}, RasterOptions{.px_per_mm = 1});
  ASSERT_EQ(maps.grid.cols, 101);  // the last column's centre, X = 100.5, is on the edge
  EXPECT_EQ(maps.kind(100, 5), HitKind::Back);
  const RasterMaps narrower = raster(scene, Sheet{100.4, 60}, RasterOptions{.px_per_mm = 1});
  EXPECT_EQ(narrower.kind(100, 5), HitKind::Outside);
  EXPECT_TRUE(std::isnan(narrower.d_mm(100, 5)));
  // Every value of a pixel past the edge is written, though no ray is shot there (the grids are
  // made unfilled): unset depths, no normal, no break beside it.
  EXPECT_TRUE(std::isnan(narrower.h_mm(100, 5)));
  EXPECT_EQ(narrower.normal(100, 5), glm::vec3(0.0f));
  EXPECT_TRUE(std::isnan(narrower.break_right(99, 5)));  // its left neighbour's, towards it
  EXPECT_TRUE(std::isnan(narrower.break_right(100, 5)));
  EXPECT_TRUE(std::isnan(narrower.break_below(100, 5)));
  // Its normalised depths are the far reference's.
  const NormalisedDepths depths = normalised_depths(narrower);
  EXPECT_EQ(depths.D(100, 5), 1.0f);
  EXPECT_EQ(depths.F(100, 5), 1.0f);
  EXPECT_EQ(depths.T(100, 5), 1.0f);
}

TEST(Raster, OutputDoesNotDependOnTheThreadCount) {
  const RayScene scene(test::sphere({100, 40, 30}, 25, 64, 32));
  RasterMaps one, many;
  {
    const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = raster(scene, Sheet{}, RasterOptions{});
  }
  many = raster(scene, Sheet{}, RasterOptions{});
  ASSERT_EQ(one.d_mm.size(), many.d_mm.size());
  EXPECT_EQ(std::memcmp(one.d_mm.values.data(), many.d_mm.values.data(), one.d_mm.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(one.h_mm.values.data(), many.h_mm.values.data(), one.h_mm.size() * sizeof(double)), 0);
  EXPECT_EQ(one.kind.values, many.kind.values);
  EXPECT_EQ(std::memcmp(one.normal.values.data(), many.normal.values.data(), one.normal.size() * sizeof(glm::vec3)), 0);
  EXPECT_EQ(std::memcmp(one.break_right.values.data(), many.break_right.values.data(),
                        one.break_right.size() * sizeof(float)),
            0);
  EXPECT_EQ(std::memcmp(one.break_below.values.data(), many.break_below.values.data(),
                        one.break_below.size() * sizeof(float)),
            0);
}

// The map pictures draw N.png from the normals, which design() drops after slicing unless kept:
// without them, the others alone.
TEST(Raster, TheMapPicturesHaveNOnlyWhereTheMapsHaveNormals) {
  const RayScene scene(test::box({30, 40, 20}, {100, 80, 50}));
  RasterMaps maps = raster(scene, Sheet{}, RasterOptions{});
  const auto names = [&] {
    std::vector<std::string> out;
    for (const OutputFile& file : raster_image_files(maps, "maps")) out.push_back(file.path.filename().string());
    return out;
  };
  EXPECT_EQ(names(), (std::vector<std::string>{"D.png", "F.png", "T.png", "N.png", "kind.png"}));
  maps.normal = {};
  EXPECT_EQ(names(), (std::vector<std::string>{"D.png", "F.png", "T.png", "kind.png"}));
}

TEST(Raster, AbsurdResolutionIsRejected) {
  const RayScene scene(test::box({10, 0, 0}, {20, 10, 10}));
  EXPECT_THROW(raster(scene, Sheet{}, RasterOptions{.px_per_mm = 0}), InputError);
  EXPECT_THROW(raster(scene, Sheet{}, RasterOptions{.px_per_mm = -2}), InputError);
  EXPECT_THROW(raster(scene, Sheet{}, RasterOptions{.px_per_mm = 1000}), InputError);
}

}  // namespace
}  // namespace origamic
