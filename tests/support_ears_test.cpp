// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_ears.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace origamic {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// Faces 0 (the back plane) and 1 (the floor) stand; 2.. are open.
struct Graph {
  std::int32_t faces;
  std::vector<std::uint8_t> standing, open;
  std::vector<double> limit;
  explicit Graph(std::int32_t n) : faces(n), standing(n, 0), open(n, 1), limit(n, kNoLimit) {
    standing[0] = standing[1] = 1;
    open[0] = open[1] = 0;
  }
};

std::vector<std::int32_t> sorted(std::vector<std::int32_t> v) {
  std::ranges::sort(v);
  return v;
}

TEST(SupportEars, TheHardestFaceOfAChainIsHeldFirstAndItsEarHoldsTheWholeChain) {
  // A dome's rings 2..5 fold onto each other in a chain up from the floor, each on its own line;
  // each could reach the back plane by a support across the rings behind it, the top (5) only at
  // the highest cost. The cheapest ear first would take ring 3's support and leave 4 and 5 to one
  // support each; the hardest first takes the top's and holds every ring by it.
  Graph g(6);
  const std::vector<FoldEdge> folds = {{1, 2, -10}, {2, 3, 10}, {3, 4, 20}, {4, 5, 30}};
  const std::vector<SupportEdge> supports = {
      {3, 0, 15, 60, 3, 3, {}}, {4, 0, 25, 70, 5, 5, {}}, {5, 0, 35, 80, 8, 8, {}}};
  const EarSearch search(g.faces, folds, supports);
  const std::vector<std::uint8_t> usable(supports.size(), 1);
  const EarSearch::Choice hardest = search.hardest(g.standing, g.open, g.limit, usable);
  ASSERT_FALSE(hardest.ears.empty());
  EXPECT_EQ(sorted(hardest.ears[0].faces), (std::vector<std::int32_t>{2, 3, 4, 5}));
  EXPECT_EQ(hardest.ears[0].supports, (std::vector<std::size_t>{2}));
  EXPECT_DOUBLE_EQ(hardest.ears[0].cost, 8);
  EXPECT_EQ(hardest.ears.size(), 1u) << "the other faces' ears pass through the same rings";
  const EarSearch::Choice cheapest = search.cheapest(g.standing, g.open, g.limit, usable);
  ASSERT_FALSE(cheapest.ears.empty());
  EXPECT_EQ(cheapest.ears[0].supports, (std::vector<std::size_t>{0}));
}

TEST(SupportEars, AFaceHeldOnOneLineOnlySwingsAndHasNoEar) {
  Graph g(3);
  const std::vector<std::uint8_t> usable(1, 1);
  // Face 2 folds onto the floor at Y = 5; a support onto the back plane from the same line leaves
  // it hinged, one from another line holds it.
  for (const double support_Y : {5.0, 9.0}) {
    const std::vector<FoldEdge> folds = {{1, 2, 5}};
    const std::vector<SupportEdge> supports = {{2, 0, support_Y, 40, 1, 1, {}}};
    const EarSearch::Choice c = EarSearch(g.faces, folds, supports).hardest(g.standing, g.open, g.limit, usable);
    EXPECT_EQ(c.ears.empty(), support_Y == 5.0) << support_Y;
  }
}

TEST(SupportEars, AnEarJoinsTwoDifferentStandingFaces) {
  // Face 2 reaches the back plane twice, on two lines, and the floor not at all: no ear. A
  // second standing face (3) it reaches is as good as the floor.
  Graph g(4);
  g.open[3] = 0;
  const std::vector<SupportEdge> supports = {{2, 0, 5, 40, 1, 1, {}}, {2, 0, 9, 44, 1, 1, {}}};
  const std::vector<std::uint8_t> usable(supports.size(), 1);
  EXPECT_TRUE(EarSearch(g.faces, {}, supports).hardest(g.standing, g.open, g.limit, usable).ears.empty());
  g.standing[3] = 1;
  const std::vector<FoldEdge> folds = {{2, 3, 9}};
  const EarSearch::Choice c = EarSearch(g.faces, folds, supports).hardest(g.standing, g.open, g.limit, usable);
  ASSERT_EQ(c.ears.size(), 1u);
  EXPECT_EQ(c.ears[0].faces, (std::vector<std::int32_t>{2}));
  EXPECT_EQ(c.ears[0].supports, (std::vector<std::size_t>{0}));
}

TEST(SupportEars, AFaceWhoseEarCostsThePictureMoreThanItsHoleIsLeftToBeCutOut) {
  Graph g(3);
  const std::vector<FoldEdge> folds = {{1, 2, -5}};
  // Its only support costs 50 (of which 40 the picture); its hole would cost 30.
  const std::vector<SupportEdge> supports = {{2, 0, 5, 40, 50, 40, {}}};
  const std::vector<std::uint8_t> usable(1, 1);
  g.limit[2] = 30;
  const EarSearch::Choice c = EarSearch(g.faces, folds, supports).hardest(g.standing, g.open, g.limit, usable);
  EXPECT_TRUE(c.ears.empty());
  ASSERT_EQ(c.beyond_limit.size(), 1u);
  EXPECT_EQ(c.beyond_limit[0].first, 2);
  EXPECT_DOUBLE_EQ(c.beyond_limit[0].second, 40);
  g.limit[2] = 45;  // the picture's part is what counts against the hole
  EXPECT_EQ(EarSearch(g.faces, folds, supports).hardest(g.standing, g.open, g.limit, usable).ears.size(), 1u);
}

TEST(SupportEars, NoEarPassesAFaceOneOfItsSupportsCutsInTwo) {
  // Faces 2 and 3 fold onto each other; 2 folds onto the floor. The cheap support from 3 to the
  // back plane cuts 2 in two, so the ear through 2 and 3 must take the dearer one.
  Graph g(4);
  const std::vector<FoldEdge> folds = {{1, 2, -5}, {2, 3, 5}};
  const std::vector<SupportEdge> supports = {{3, 0, 9, 40, 1, 1, {2}}, {3, 0, 9.5, 41, 4, 4, {}}};
  const std::vector<std::uint8_t> usable(supports.size(), 1);
  const EarSearch::Choice c = EarSearch(g.faces, folds, supports).hardest(g.standing, g.open, g.limit, usable);
  ASSERT_EQ(c.ears.size(), 1u);
  EXPECT_EQ(c.ears[0].supports, (std::vector<std::size_t>{1}));
  EXPECT_DOUBLE_EQ(c.ears[0].cost, 4);
}

}  // namespace
}  // namespace origamic
