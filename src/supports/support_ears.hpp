// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: which supports to add, as a graph problem (seed §4.4, validity). A face stands when it
// has a path of folds to the back plane and one to the floor that share no face: it lies in one
// biconnected block with them. An ear, a path from one standing face to another through faces that
// do not stand, each entered and left on two different fold lines (a face folded on one line only
// swings about it), makes every face on it stand (an ear keeps a block biconnected). So supports
// are chosen ear by ear over the folds the plan has (free) and the candidate supports (their cost):
// one support closes a chain of slices that already folds onto each other, where holding each of
// them on its own would paint a strip per slice. The ear taken first is that of the face hardest to
// hold (whose cheapest ear costs most): a dome's top is held only by a support over its back to the
// back plane, and the ear through it holds every ring of the chain below it, where taking the
// cheapest ear first (a lower ring's support to the back plane) leaves the rings above it to one
// support each.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace origamic {

/// A fold the plan has, between faces a and b on the plan line Y.
struct FoldEdge {
  std::int32_t a = 0, b = 0;
  double Y = 0;
};

/// A support that may be added: it folds onto `face` on the line face_Y and onto `target` on
/// target_Y, at this cost (>= 0), of which `picture` is what it costs the likeness (the rest: the
/// faces it would cut in two).
struct SupportEdge {
  std::int32_t face = 0, target = 0;
  double face_Y = 0, target_Y = 0;
  double cost = 0;
  double picture = 0;
  std::vector<std::int32_t> cuts;  // the faces it cuts in two: no ear through it may pass them
};

struct Ear {
  std::vector<std::int32_t> faces;    // the faces it makes stand, in path order
  std::vector<std::size_t> supports;  // indices of the support edges it adds
  double cost = 0;
  double picture = 0;  // of which the likeness's part
};

/// The folds and candidate supports of a plan, searched for ears.
class EarSearch {
 public:
  /// \pre every face index in folds and supports is below `faces`.
  EarSearch(std::int32_t faces, std::span<const FoldEdge> folds, std::span<const SupportEdge> supports);

  /// Of the faces marked `open` whose cheapest ear costs the picture at most their `limit` (what
  /// cutting them out costs it), the one whose cheapest ear costs most, with that ear: a path from
  /// one standing face to another through open faces, over the folds (cost 0) and the support edges
  /// marked `usable`, each face on it once; then, hardest first, the cheapest ears of other faces
  /// that share no face and no support with those before them. None if no open face has such an
  /// ear; `beyond_limit` lists the open faces whose every ear costs the picture more than their
  /// limit, with what their cheapest ear costs it.
  /// \pre standing, open and limit: one entry per face; usable: one per support edge.
  struct Choice {
    std::vector<Ear> ears;
    std::vector<std::pair<std::int32_t, double>> beyond_limit;
  };
  Choice hardest(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
                 const std::vector<double>& limit, const std::vector<std::uint8_t>& usable) const;
  /// The same, the cheapest first.
  Choice cheapest(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
                  const std::vector<double>& limit, const std::vector<std::uint8_t>& usable) const;

 private:
  struct Arc {
    std::int32_t to;
    double here_Y, there_Y;  // the fold lines at this end and the other
    double cost, picture;
    std::int64_t support;  // the support edge, -1 for a fold
  };
  class Paths;
  Choice pick(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
              const std::vector<double>& limit, const std::vector<std::uint8_t>& usable, bool hardest) const;
  std::vector<std::vector<Arc>> arcs_;           // per face
  std::vector<std::vector<std::int32_t>> cuts_;  // per support edge
};

}  // namespace origamic
