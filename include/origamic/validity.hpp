// SPDX-License-Identifier: GPL-3.0-or-later
// Validity of a pop-up (seed §4.4, first half), decided on the face graph alone: faces are nodes,
// folds are edges. The exact core builds the graph from exact folds; nothing here measures.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace origamic {

enum class FaceStatus : std::uint8_t {
  Valid,     // a path to the back plane and one to the floor that share no face
  Indirect,  // not valid by itself, held by a fold and a connective face (Chen and Zhang 2006)
  Floating,  // no chain of folds joins it to the back plane or the floor
  Dangling,  // all its folds on one line: it swings about it
  Invalid,   // any other face that is not held
  Removed,   // cut out of the sheet (a hole): no support could hold it
};

std::string_view to_string(FaceStatus status);

/// A fold between faces a and b; `line` numbers the distinct fold lines (equal exact Y, equal id).
struct Fold {
  std::int32_t a = 0;
  std::int32_t b = 0;
  std::int32_t line = 0;
};

/// Face 0 is the back plane and face 1 the floor, as in the raster plan.
struct FaceGraph {
  std::int32_t faces = 2;
  std::vector<Fold> folds;
  std::vector<std::uint8_t> holes;  // per face, empty or 1 for a face cut out of the sheet: Removed
};

struct Validity {
  std::vector<FaceStatus> status;  // per face; back plane and floor are Valid
  std::vector<bool> reaches_back_plane;          // reachable from the back plane without the floor
  std::vector<bool> reaches_floor;          // reachable from the floor without the back plane
  std::vector<int> fold_lines;     // distinct fold lines per face
  int valid = 0, indirect = 0, floating = 0, dangling = 0, invalid = 0, removed = 0;  // over faces 2 ..

  /// Every face valid or indirect (the seed counts indirect faces as valid features).
  bool ok() const { return floating + dangling + invalid == 0; }
};

/// Seed §4.4: a face is valid when it has a path to the back plane and a path to the floor that go
/// through no common face. Faces whose folds all lie on one line are hinges and hold nothing, so
/// they are set aside first (repeatedly, as setting one aside can leave a neighbour on one line).
/// Of the rest, the valid faces are those in one biconnected block with a node joined to both the
/// back plane and the floor (Menger: two such disjoint paths exist exactly then). The sets X and Y
/// are computed as the seed grows them; faces outside the valid set are classified as it says.
Validity validity_of(const FaceGraph& graph);

/// Adds the status of every face but the back plane and the floor to the counts.
void count_statuses(Validity& validity);

}  // namespace origamic
