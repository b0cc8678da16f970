// SPDX-License-Identifier: GPL-3.0-or-later
#include "face_pieces.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace origamic {
namespace {

// A face drawn in text, '#' its pixels, one string a row.
using Picture = std::vector<std::string>;

std::vector<FacePieces::RowRun> runs_of(const Picture& picture) {
  std::vector<FacePieces::RowRun> runs;
  for (int r = 0; r < static_cast<int>(picture.size()); ++r) {
    const std::string& row = picture[static_cast<std::size_t>(r)];
    for (int c = 0; c < static_cast<int>(row.size());) {
      if (row[static_cast<std::size_t>(c)] != '#') {
        ++c;
        continue;
      }
      int end = c;
      while (end < static_cast<int>(row.size()) && row[static_cast<std::size_t>(end)] == '#') ++end;
      runs.push_back({r, c, end});
      c = end;
    }
  }
  return runs;
}

// The 4-connected pieces of the picture less the rectangles, by flood fill.
int flood_pieces(Picture picture, const std::vector<PixelRect>& rects) {
  for (const auto& [c0, c1, r0, r1] : rects)
    for (int r = std::max(0, r0); r < std::min(r1, static_cast<int>(picture.size())); ++r)
      for (int c = std::max(0, c0); c < std::min(c1, static_cast<int>(picture[static_cast<std::size_t>(r)].size()));
           ++c)
        picture[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = '.';
  const auto at = [&](int c, int r) -> char& {
    return picture[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
  };
  int pieces = 0;
  for (int r = 0; r < static_cast<int>(picture.size()); ++r)
    for (int c = 0; c < static_cast<int>(picture[static_cast<std::size_t>(r)].size()); ++c) {
      if (at(c, r) != '#') continue;
      ++pieces;
      std::vector<std::pair<int, int>> stack{{c, r}};
      at(c, r) = 'o';
      while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int nx = x + dx, ny = y + dy;
          if (ny < 0 || ny >= static_cast<int>(picture.size()) || nx < 0 ||
              nx >= static_cast<int>(picture[static_cast<std::size_t>(ny)].size()) || at(nx, ny) != '#')
            continue;
          at(nx, ny) = 'o';
          stack.emplace_back(nx, ny);
        }
      }
    }
  return pieces;
}

TEST(FacePieces, ARingCutOnceStaysOnePieceAndCutTwiceFallsInTwo) {
  const Picture ring = {
      "#########",
      "#.......#",
      "#.......#",
      "#########",
  };
  const FacePieces pieces(runs_of(ring));
  EXPECT_EQ(pieces.pieces(), 1);
  EXPECT_EQ(pieces.pieces_without(3, 5, 0, 1), 1);    // through its top: a C is left
  EXPECT_EQ(pieces.pieces_without(3, 5, 0, 4), 2);    // through top and bottom
  EXPECT_EQ(pieces.pieces_without(0, 1, 0, 4), 1);    // its left side
  EXPECT_EQ(pieces.pieces_without(0, 9, 1, 3), 2);    // both sides' middles
  EXPECT_EQ(pieces.pieces_without(20, 22, 0, 4), 1);  // beside it
}

TEST(FacePieces, TouchingOnlyAtACornerIsTwoPieces) {
  const Picture corner = {
      "##..",
      "##..",
      "..##",
  };
  const FacePieces pieces(runs_of(corner));
  EXPECT_EQ(pieces.pieces(), 2);
  EXPECT_EQ(pieces.pieces_without(0, 1, 0, 3), 2);
  EXPECT_EQ(pieces.pieces_without(2, 4, 2, 3), 1);
}

// Every rectangle over random faces (blobs, combs, rings with holes), against a flood fill.
TEST(FacePieces, AgreesWithAFloodFillOnEveryRectangleOfRandomFaces) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 60; ++trial) {
    const int cols = 3 + static_cast<int>(random() % 9), rows = 3 + static_cast<int>(random() % 9);
    const unsigned fill = 35 + random() % 50;  // percent of pixels in the face
    Picture picture(static_cast<std::size_t>(rows), std::string(static_cast<std::size_t>(cols), '.'));
    for (std::string& row : picture)
      for (char& p : row) p = random() % 100 < fill ? '#' : '.';
    const std::vector<FacePieces::RowRun> runs = runs_of(picture);
    if (runs.empty()) continue;
    const FacePieces pieces(runs);
    ASSERT_EQ(pieces.pieces(), flood_pieces(picture, {}));
    for (int c0 = -1; c0 <= cols; ++c0)
      for (int c1 = c0 + 1; c1 <= cols + 1; ++c1)
        for (int r0 = -1; r0 <= rows; ++r0)
          for (int r1 = r0 + 1; r1 <= rows + 1; ++r1)
            ASSERT_EQ(pieces.pieces_without(c0, c1, r0, r1), flood_pieces(picture, {{c0, c1, r0, r1}}))
                << "trial " << trial << " rectangle [" << c0 << ", " << c1 << ") x [" << r0 << ", " << r1 << ")";
  }
}

// Several rectangles at once (pieces_less, for supports taken together), against a flood fill:
// random faces, one to three random rectangles each, some overlapping, some touching.
TEST(FacePieces, LessSeveralRectanglesAgreesWithAFloodFill) {
  std::mt19937 random(11);
  int parted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int cols = 3 + static_cast<int>(random() % 10), rows = 3 + static_cast<int>(random() % 10);
    const unsigned fill = 40 + random() % 55;
    Picture picture(static_cast<std::size_t>(rows), std::string(static_cast<std::size_t>(cols), '.'));
    for (std::string& row : picture)
      for (char& p : row) p = random() % 100 < fill ? '#' : '.';
    const std::vector<FacePieces::RowRun> runs = runs_of(picture);
    std::vector<PixelRect> rects;
    for (unsigned k = 0, n = 1 + random() % 3; k < n; ++k) {
      const int c0 = static_cast<int>(random() % static_cast<unsigned>(cols)) - 1;
      const int r0 = static_cast<int>(random() % static_cast<unsigned>(rows)) - 1;
      rects.push_back({c0, c0 + 1 + static_cast<int>(random() % 4), r0, r0 + 1 + static_cast<int>(random() % 6)});
    }
    const int expected = flood_pieces(picture, rects);
    ASSERT_EQ(pieces_less(runs, rects), expected) << "trial " << trial;
    parted += expected > flood_pieces(picture, {});
  }
  EXPECT_GT(parted, 300) << "the rectangles part faces often enough to test it";
}

}  // namespace
}  // namespace origamic
