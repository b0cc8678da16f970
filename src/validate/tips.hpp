// SPDX-License-Identifier: GPL-3.0-or-later
// Internal to the tip repair (tip_repair.cpp): where a face narrower than W across a chord ends in a
// tip (tip_of, tip_walk.cpp), found by walking across the chord vertex line by vertex line, and one
// round of parting such tips off an analysed plan's arrangement (TipCutter, tip_cutter.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "exact_kernel.hpp"
#include "origamic/plan_analysis.hpp"
#include "plan_analysis_geometry.hpp"

namespace origamic::tips {

using exact::FT;

// A face's boundary edges in (u, v): u across a chord, v along it.
struct UvEdge {
  FT u0, v0, u1, v1;  // u0 < u1
  FT v_at(const FT& u) const { return analysis::crossing_v(u0, v0, u1, v1, u); }
};

// A tip of a face: where the cut across it goes (at u, from v_lo to v_hi) and a point inside it.
struct Tip {
  std::size_t region;
  bool along_Y;
  FT u, v_lo, v_hi;
  FT inside_u, inside_v;
};

// A face's boundary seen across chords along one axis: its edges in (u, v), and the u of its
// vertex lines, sorted, each once.
struct FaceLines {
  std::vector<UvEdge> edges;
  std::vector<FT> us;
};
/// The face's edges and vertex lines across chords along Y (along_Y) or along X.
FaceLines face_lines(const std::vector<analysis::Ring>& rings, bool along_Y);

/// Walks across the chord of a face narrower than W: one way the face must end within `reach`, the
/// other it must widen to `wide`; the tip is cut where it does, or on a vertex line of the face
/// within a hundredth of a millimetre of there where the face is still W wide.
std::optional<Tip> tip_of(const FaceLines& face, std::size_t region, bool along_Y, const analysis::Chord& chord,
                          const FT& W, const FT& wide, const FT& reach);

/// The bounded face of the arrangement each point lies in (none on an edge or a vertex), located all
/// at once by a sweep.
std::vector<std::optional<analysis::Face>> faces_at(const exact::Arrangement& arr,
                                                    const std::vector<exact::Point>& points);

// One round of tips on an analysed plan's arrangement: `run` cuts them in and gives each to a
// neighbour, `take_back` returns some, `lines` draws the plan as they are given.
class TipCutter {
 public:
  TipCutter(analysis::Analyzer& analyzer, const TipRepairOptions& options)
      : a_(analyzer), options_(options), first_new_(static_cast<std::int32_t>(analyzer.kind.size())) {}

  // The analysis whose arrangement the tips are cut into.
  const analysis::Analyzer& analyzer() const { return a_; }

  // Cuts the round's tips into the arrangement and gives each to a neighbour (see `settle`).
  void run();

  // The tips given away from or to the faces `held` go back to their own.
  void take_back(const std::set<std::int32_t>& held);

  // The costliest quarter of the tips given (Given::moved_mm3), at least one, go back to their own.
  void take_back_costliest();

  // How many tips are given to a neighbour now (not taken back).
  int tips() const;

  // The lines as the tips are given: those of a tip back with its own face drawn as they were.
  std::vector<PlanPolyline> lines();

 private:
  using Arrangement = exact::Arrangement;
  using Face = analysis::Face;
  using Halfedge = analysis::Halfedge;
  using Point = exact::Point;
  // The fold edges between two faces, by their labels.
  using FoldCounts = std::map<std::pair<std::int32_t, std::int32_t>, int>;
  // The tips' faces as labelled in the round: each with the face it comes from, and that face's
  // label or the neighbour's it was given to.
  struct Given {
    Arrangement::Face_const_handle tip;
    std::int32_t from;
    double moved_mm3 = 0;  // its area times how far its plane moves (in h + d): what it costs the picture
  };
  // A neighbour to give a tip to, and how far its plane lies from the tip's own there (in h + d).
  struct Neighbour {
    std::int32_t face = -1;
    double gap_mm = 0;
  };
  analysis::Analyzer& a_;
  const TipRepairOptions& options_;
  std::vector<Given> given_;
  std::int32_t first_new_;  // the index of the round's first cut among the arrangement's lines

  // The round's tips, at most one a face: along Y first.
  std::vector<Tip> find_tips(const FT& W, const FT& wide, const FT& reach) const;

  // A tip of face r across its chords along Y (along_Y) or along X.
  std::optional<Tip> tip_across(std::size_t r, bool along_Y, const FT& W, const FT& wide, const FT& reach) const;

  // A cut ending a hair from a point of another line would meet it in a file: that tip stays.
  std::vector<Tip> clear_of_points(std::vector<Tip> tips) const;

  // Each cut goes in; the face it parts keeps its label on both sides until the tip's is given.
  void cut_in(const std::vector<Tip>& tips);

  // Whether the edge lies on a mountain or a valley line.
  bool is_fold(Halfedge he) const;

  // The fold edges between each pair of faces, both ways round.
  FoldCounts folds_between_faces() const;

  // Which tips may go, decided on the labels as they are before any goes.
  std::vector<bool> tips_that_may_go(const std::vector<Tip>& tips, const std::vector<std::optional<Face>>& tip_faces,
                                     const FoldCounts& folds_between, const FT& wide) const;

  // Whether face `region` keeps a fold outside its tip `f` with each neighbour: a tip whose sides
  // hold all of its face's folds with a neighbour stays, or that neighbour would come loose.
  bool leaves_neighbours_a_fold(Face f, std::int32_t region, const FoldCounts& folds_between) const;

  // The placed neighbour of the tip's face `f` whose plane is nearest the face's own at the tip's
  // inside point (face -1 for none).
  Neighbour nearest_neighbour(const Tip& tip, const Point& inside, Face f) const;

  // A tip given to a face whose own tip went elsewhere may touch no other part of it: it goes back.
  void settle();
};

}  // namespace origamic::tips
