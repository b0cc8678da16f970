// SPDX-License-Identifier: GPL-3.0-or-later
// Validity on face graphs written by hand: 0 back plane, 1 floor, fold lines numbered by their Y.
#include "origamic/validity.hpp"

#include <gtest/gtest.h>

namespace origamic {
namespace {

constexpr std::int32_t kMainFold = 100;  // the line Y = 0 between back plane and floor

FaceGraph graph(std::int32_t faces, std::vector<Fold> folds) {
  folds.push_back({0, 1, kMainFold});
  return {faces, std::move(folds), {}};
}

TEST(Validity, BoxAgainstTheBackPlaneIsValid) {
  // front V(d) 2, top H(h) 3: floor-front at Y = -d, front-top at h - d, top-back at h.
  const Validity v = validity_of(graph(4, {{1, 2, 0}, {2, 3, 1}, {3, 0, 2}}));
  EXPECT_TRUE(v.ok());
  EXPECT_EQ(v.valid, 2);
  EXPECT_EQ(v.status[2], FaceStatus::Valid);
  EXPECT_EQ(v.status[3], FaceStatus::Valid);
}

TEST(Validity, FloatingBoxIsFloatingEvenThoughItsTwoFacesAreFolded) {
  const Validity v = validity_of(graph(4, {{2, 3, 1}}));
  EXPECT_FALSE(v.ok());
  EXPECT_EQ(v.status[2], FaceStatus::Floating);
  EXPECT_EQ(v.status[3], FaceStatus::Floating);
  EXPECT_EQ(v.floating, 2);
}

TEST(Validity, ShelfOnTheBackPlaneOnlyIsDangling) {
  const Validity v = validity_of(graph(3, {{2, 0, 5}}));
  EXPECT_EQ(v.status[2], FaceStatus::Dangling);
  EXPECT_EQ(v.fold_lines[2], 1);
}

TEST(Validity, FaceHeldAlongOneLineByTwoFacesIsDanglingItSwingsAboutIt) {
  // Box 2/3 valid; face 4 (H) folds to the front 2 and to another V face 5 on the same line 7,
  // face 5 standing on the floor (line 8) and folded to 4 on line 7.
  const Validity v = validity_of(graph(6, {{1, 2, 0}, {2, 3, 1}, {3, 0, 2}, {4, 2, 7}, {4, 5, 7}, {5, 1, 8}}));
  EXPECT_EQ(v.status[4], FaceStatus::Dangling);
  EXPECT_EQ(v.fold_lines[4], 1);
  EXPECT_TRUE(v.reaches_back_plane[4] && v.reaches_floor[4])
      << "in X and Y, yet it swings: X and Y alone would call it valid";
}

TEST(Validity, TwoStepStaircaseIsValid) {
  // floor - V1 - H1 - V2 - H2 - back.
  const Validity v = validity_of(graph(6, {{1, 2, 0}, {2, 3, 1}, {3, 4, 2}, {4, 5, 3}, {5, 0, 4}}));
  EXPECT_TRUE(v.ok());
  EXPECT_EQ(v.valid, 4);
}

TEST(Validity, ChainHangingFromTheBackPlaneIsInvalidAndDangling) {
  // back - H 2 - V 3, nothing else: 3 swings on its one fold, 2 is left with one standing line.
  const Validity v = validity_of(graph(4, {{0, 2, 1}, {2, 3, 2}}));
  EXPECT_EQ(v.status[3], FaceStatus::Dangling);
  EXPECT_EQ(v.status[2], FaceStatus::Invalid);
  EXPECT_EQ(v.fold_lines[2], 2);
  EXPECT_FALSE(v.ok());
}

TEST(Validity, IndirectFaceHeldThroughAConnectiveFace) {
  // Valid box 2/3. Face 4 (V, coplanar with the front 2) stands on the floor (line 9) and its top
  // folds to face 5 (H), which folds to the box front along the same line 7: 5 is held along one
  // line only, so 4 is not valid by itself, but 5 ties 4's top to the front's top edge.
  const Validity v = validity_of(graph(6, {{1, 2, 0}, {2, 3, 1}, {3, 0, 2}, {1, 4, 9}, {4, 5, 7}, {5, 2, 7}}));
  EXPECT_EQ(v.status[4], FaceStatus::Indirect);
  EXPECT_EQ(v.status[5], FaceStatus::Dangling);
  EXPECT_EQ(v.indirect, 1);
  EXPECT_TRUE(v.reaches_back_plane[4] && v.reaches_floor[4]);
}

TEST(Validity, SetsXAndYGrowWithoutTheOtherPlane) {
  const Validity v = validity_of(graph(5, {{0, 2, 1}, {1, 3, 2}}));
  EXPECT_TRUE(v.reaches_back_plane[2]);
  EXPECT_TRUE(v.reaches_floor[3]);
  EXPECT_FALSE(v.reaches_back_plane[4] || v.reaches_floor[4]);
  EXPECT_EQ(v.status[4], FaceStatus::Floating);
}

}  // namespace
}  // namespace origamic
