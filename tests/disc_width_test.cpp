// SPDX-License-Identifier: GPL-3.0-or-later
#include "disc_width.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

std::vector<std::pair<int, int>> rectangle(int cols, int rows) {
  std::vector<std::pair<int, int>> pixels;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) pixels.emplace_back(x + 5, y - 3);
  return pixels;
}

TEST(DiscWidth, AStripIsAsWideAsItsRows) {
  // The middle row of 11 lies 6 rows from the rows outside; 12 rows have two middle rows, 6 from them.
  EXPECT_DOUBLE_EQ(widest_disc_px(rectangle(40, 12)), 12);
  EXPECT_DOUBLE_EQ(widest_disc_px(rectangle(40, 11)), 12);
  EXPECT_DOUBLE_EQ(widest_disc_px(rectangle(40, 10)), 10);
  EXPECT_DOUBLE_EQ(widest_disc_px(rectangle(12, 40)), 12);
  EXPECT_DOUBLE_EQ(widest_disc_px(rectangle(1, 1)), 2);
  EXPECT_DOUBLE_EQ(widest_disc_px({}), 0);
}

TEST(DiscWidth, ADiagonalStripIsAsWideAcrossAsItIs) {
  // |x - y| <= 3: 7 pixels along a row, but a pixel on the diagonal has one outside at (+2, -2).
  std::vector<std::pair<int, int>> band;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 60; ++x)
      if (std::abs(x - y) <= 3) band.emplace_back(x, y);
  EXPECT_DOUBLE_EQ(widest_disc_px(band), 2 * std::sqrt(8.0));
}

TEST(DiscWidth, ACrescentIsAsNarrowAsItsStripThoughItsBoxIsWide) {
  // Half a ring 6 pixels wide, of radius 100: its principal box is about 100 by 200 pixels.
  std::vector<std::pair<int, int>> crescent;
  for (int y = -110; y <= 110; ++y)
    for (int x = 0; x <= 110; ++x)
      if (const double r = std::hypot(x, y); r >= 100 && r < 106) crescent.emplace_back(x, y);
  EXPECT_GT(oriented_box_min_side_px(crescent), 90);
  const double widest = widest_disc_px(crescent);
  EXPECT_GE(widest, 6);
  EXPECT_LE(widest, 8);
}

TEST(DiscWidth, ASquareIsFoundWhereTheSetHoldsOne) {
  EXPECT_TRUE(holds_square_px(rectangle(40, 12), 12));
  EXPECT_FALSE(holds_square_px(rectangle(40, 12), 13));
  EXPECT_FALSE(holds_square_px(rectangle(40, 11), 12));
  EXPECT_FALSE(holds_square_px({}, 1));
  // Two 6-row strips, one row apart: no square of 12 reaches across the gap, as the disc does not.
  std::vector<std::pair<int, int>> split;
  for (int y = 0; y < 13; ++y)
    for (int x = 0; x < 30; ++x)
      if (y != 6) split.emplace_back(x, y);
  EXPECT_FALSE(holds_square_px(split, 7));
  EXPECT_TRUE(holds_square_px(split, 6));
  EXPECT_LT(widest_disc_px(split), 12);
  // An L of two arms 8 wide holds a square of 8 where they meet, not of 9.
  std::vector<std::pair<int, int>> ell;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x)
      if (x < 8 || y >= 22) ell.emplace_back(x, y);
  EXPECT_TRUE(holds_square_px(ell, 8));
  EXPECT_FALSE(holds_square_px(ell, 9));
}

}  // namespace
}  // namespace origamic
