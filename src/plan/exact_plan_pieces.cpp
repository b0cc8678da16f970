// SPDX-License-Identifier: GPL-3.0-or-later
// The exact plan's pieces of paper, and the verdict on each raster face from the verdict on its
// pieces (exact_plan_state.hpp).

// Exact numbers here are never shared between threads (see exact_kernel.hpp).
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <cstddef>
#include <map>
#include <vector>

#include "exact_plan_state.hpp"
#include "union_find.hpp"

namespace origamic::exact {
namespace {

// How badly a status falls short, for the worst piece of a face.
int shortfall(FaceStatus s) {
  switch (s) {
    case FaceStatus::Valid:
      return 0;
    case FaceStatus::Indirect:
      return 1;
    case FaceStatus::Removed:
      return 2;
    case FaceStatus::Dangling:
      return 3;
    case FaceStatus::Invalid:
      return 4;
    case FaceStatus::Floating:
      return 5;
  }
  return 5;
}

}  // namespace

bool negligible(Arrangement::Halfedge_const_handle he) {
  const FT tolerance(kFoldLineTolerance_mm);
  return CGAL::compare_squared_distance(he->source()->point(), he->target()->point(), tolerance * tolerance) ==
         CGAL::SMALLER;
}

Pieces pieces_of(const Arrangement& arr) {
  std::vector<Arrangement::Face_const_handle> faces;
  std::map<Arrangement::Face_const_handle, std::int32_t> index;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
    if (!f->is_unbounded() && f->data() >= 0) index[f] = static_cast<std::int32_t>(faces.size()), faces.push_back(f);
  UnionFind<std::int32_t> sets(faces.size());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const auto a = e->face(), b = e->twin()->face();
    if (a == b || a->is_unbounded() || b->is_unbounded() || a->data() < 0 || a->data() != b->data() || negligible(e))
      continue;
    sets.join(index.at(a), index.at(b));
  }
  Pieces pieces;
  std::map<std::int32_t, std::int32_t> piece_of_root;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto [it, fresh] = piece_of_root.try_emplace(sets.root(static_cast<std::int32_t>(i)),
                                                       static_cast<std::int32_t>(pieces.label.size()));
    if (fresh) pieces.label.push_back(faces[i]->data());
    pieces.of[faces[i]] = it->second;
  }
  return pieces;
}

namespace {

// A piece of the back plane or the floor is a sliver where twice its area over its perimeter (a
// strip's width) is under this many W. A turned pyramid's rim left one 18 mm long and 0.13 mm deep
// hanging by the main fold, and the plan did not stand. Over the 37 models at W = 3 mm, 0.1 W
// changes no other plan; 0.25 and 0.5 W change arch_city_block's, whose planes refit then stand:
// p95 3.12 -> 2.84 W, its supports adding 1.95 -> 1.67 W over its sliced plan, places 73 -> 91
// (the refit weighs the picture, not places).
constexpr double kCardSliver_W = 0.25;

}  // namespace

bool card_piece_falls_out(FaceStatus status, double area_mm2, double perimeter_mm, double min_strip_mm) {
  const bool crumb = area_mm2 < min_strip_mm * min_strip_mm / 8;
  const bool sliver = 2 * area_mm2 < kCardSliver_W * min_strip_mm * perimeter_mm;
  return (status == FaceStatus::Dangling && (crumb || sliver)) || (status == FaceStatus::Floating && sliver);
}

PieceVerdict face_validity(const Validity& by_node, const PieceFacts& piece, std::size_t faces, double min_strip_mm) {
  const Pieces& pieces = piece.pieces;
  const std::vector<double>& piece_area = piece.area;
  const double crumb = min_strip_mm * min_strip_mm / 8;
  PieceVerdict verdict;
  verdict.cut_out.assign(pieces.label.size(), 0);
  Validity& v = verdict.validity;
  v.status.assign(faces, FaceStatus::Valid);
  v.reaches_back_plane.assign(faces, true);
  v.reaches_floor.assign(faces, true);
  v.fold_lines.assign(faces, 2);
  std::vector<int> worst(faces, -1);
  std::vector<std::uint8_t> kept(faces, 0);  // some piece of the face stays in the sheet
  for (std::size_t p = 0; p < pieces.label.size(); ++p) {
    const auto f = static_cast<std::size_t>(pieces.label[p]), k = static_cast<std::size_t>(piece.node[p]);
    if (k < 2) continue;  // the card's halves themselves
    if ((piece_area[p] < crumb || piece.among_holes[p]) && by_node.status[k] == FaceStatus::Floating) {
      verdict.cut_out[p] = 1;
      continue;
    }
    // So do a crumb and a sliver of the back plane or the floor (card_piece_falls_out).
    if (f < 2 && card_piece_falls_out(by_node.status[k], piece_area[p], piece.perimeter[p], min_strip_mm)) {
      verdict.cut_out[p] = 1;
      continue;
    }
    kept[f] = 1;
    if (f < 2) {  // a loose piece of the back plane or the floor
      if (by_node.status[k] == FaceStatus::Valid || by_node.status[k] == FaceStatus::Indirect) continue;
      ++verdict.loose_card_pieces;
      v.floating += by_node.status[k] == FaceStatus::Floating, v.dangling += by_node.status[k] == FaceStatus::Dangling;
      v.invalid += by_node.status[k] == FaceStatus::Invalid;
      continue;
    }
    if (shortfall(by_node.status[k]) <= worst[f]) continue;
    worst[f] = shortfall(by_node.status[k]);
    v.status[f] = by_node.status[k];
    v.reaches_back_plane[f] = by_node.reaches_back_plane[k];
    v.reaches_floor[f] = by_node.reaches_floor[k];
    v.fold_lines[f] = by_node.fold_lines[k];
  }
  // A face all of whose pieces fell out is a hole.
  for (std::size_t p = 0; p < pieces.label.size(); ++p)
    if (const auto f = static_cast<std::size_t>(pieces.label[p]); f >= 2 && verdict.cut_out[p] && !kept[f])
      v.status[f] = FaceStatus::Removed;
  count_statuses(v);
  return verdict;
}

}  // namespace origamic::exact
