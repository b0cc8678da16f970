// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: the tips of faces narrower than W parted off on the exact arrangement of a plan's lines
// (blunt_narrow_tips, plan_analysis.hpp), round after round, each round's lines analysed again
// (plan_analysis.cpp); where a face ends in a tip is found by tip_walk.hpp. One exact run at a
// time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include <CGAL/Arr_batched_point_location.h>
#include <CGAL/Arr_observer.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "exact_kernel.hpp"
#include "exact_runs.hpp"
#include "origamic/plan_analysis.hpp"
#include "plan_analysis_geometry.hpp"
#include "tip_walk.hpp"

namespace origamic {
namespace {

using analysis::Analyzer;
using analysis::Chord;
using analysis::Face;
using analysis::Halfedge;
using analysis::Place;
using analysis::Ring;
using analysis::ring_area;
using analysis::rings_of;
using exact::Arrangement;
using exact::FT;
using exact::Point;
using tips::face_lines;
using tips::FaceLines;
using tips::Tip;
using tips::tip_of;

// The bounded face of the arrangement each point lies in (none on an edge or a vertex), located all
// at once by a sweep.
std::vector<std::optional<Face>> faces_at(const Arrangement& arr, const std::vector<Point>& points) {
  std::vector<std::pair<Point, CGAL::Arr_point_location_result<Arrangement>::Type>> found;
  CGAL::locate(arr, points.begin(), points.end(), std::back_inserter(found));
  const auto before = [](const Point& a, const Point& b) { return CGAL::compare_xy(a, b) == CGAL::SMALLER; };
  std::map<Point, Face, decltype(before)> face_of(before);
  for (const auto& [p, where] : found)
    if (const Face* f = boost::get<Face>(&where); f && !(*f)->is_unbounded()) face_of.emplace(p, *f);
  std::vector<std::optional<Face>> out;
  for (const Point& p : points) {
    const auto it = face_of.find(p);
    out.push_back(it == face_of.end() ? std::nullopt : std::optional<Face>(it->second));
  }
  return out;
}

// Closer than this a new cut's line and a vertex's are one in a file (its Y rounded from the sheet's
// lower edge, about 1e-14 mm): far below any cutter, far above the rounding.
constexpr double kHair_mm = 1e-9;
// How many points of the lines a file's rounding of Y (from the sheet's lower edge, `low`) makes
// one with another: the design's own plans have a few (res_bunny: 1), which its reader takes as
// drawn.
std::size_t points_merged_in_files(const std::vector<PlanPolyline>& lines, double low) {
  std::set<std::pair<double, double>> exact, filed;
  for (const PlanPolyline& line : lines)
    for (const PlanPoint& p : line.points) exact.emplace(p.X, p.Y), filed.emplace(p.X, (p.Y - low) + low);
  return exact.size() - filed.size();
}

// A point of the plan at u across a chord and v along it, the chord along Y (along_Y) or along X.
Point on_plan(bool along_Y, const FT& u, const FT& v) { return along_Y ? Point(u, v) : Point(v, u); }

// The fold edges between two faces, by their labels.
using FoldCounts = std::map<std::pair<std::int32_t, std::int32_t>, int>;

// Each halfedge of a face's outer boundaries, in order.
template <typename Visit>
void for_each_outer_halfedge(Face f, Visit visit) {
  for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
    auto he = *ccb;
    do visit(Halfedge(he));
    while (++he != *ccb);
  }
}

// The lowest and highest Y of a face's outer boundary.
struct YRange {
  FT lowest, highest;
};
YRange y_range(Face f) {
  FT lowest = f->outer_ccb()->source()->point().y(), highest = lowest;
  for_each_outer_halfedge(f, [&](Halfedge he) {
    const FT& y = he->target()->point().y();
    lowest = CGAL::min(lowest, y), highest = CGAL::max(highest, y);
  });
  return {lowest, highest};
}

// One round of tips on an analysed plan's arrangement: `run` cuts them in and gives each to a
// neighbour, `take_back` returns some, `lines` draws the plan as they are given.
class TipCutter {
 public:
  TipCutter(Analyzer& analyzer, const TipRepairOptions& options)
      : a_(analyzer), options_(options), first_new_(static_cast<std::int32_t>(analyzer.kind.size())) {}

  const Analyzer& analyzer() const { return a_; }

  // Cuts the round's tips into the arrangement and gives each to a neighbour (see `settle`).
  void run() {
    if (a_.narrowest.empty()) return;  // no strip widths measured: nothing to part
    const FT W(options_.min_strip_mm), wide = W + FT(options_.margin_mm), reach(options_.max_tip_mm);
    const std::vector<Tip> tips = clear_of_points(find_tips(W, wide, reach));
    cut_in(tips);
    const FoldCounts folds_between = folds_between_faces();
    // Each tip's face goes to its neighbour whose plane is nearest the face's own there.
    std::vector<Point> insides;
    for (const Tip& tip : tips) insides.push_back(on_plan(tip.along_Y, tip.inside_u, tip.inside_v));
    const std::vector<std::optional<Face>> tip_faces = faces_at(a_.arr, insides);
    const std::vector<bool> may_go = tips_that_may_go(tips, tip_faces, folds_between, wide);
    for (std::size_t i = 0; i < tips.size(); ++i) {
      if (!may_go[i]) continue;
      const std::int32_t best = nearest_neighbour(tips[i], insides[i], *tip_faces[i]);
      if (best < 0) continue;
      a_.arr.non_const_handle(*tip_faces[i])->set_data(best);
      given_.push_back({*tip_faces[i], static_cast<std::int32_t>(tips[i].region)});
    }
    settle();
  }

  // The tips given away from or to the faces `held` go back to their own.
  void take_back(const std::set<std::int32_t>& held) {
    for (const auto& [t, from] : given_)
      if (held.contains(from) || held.contains(t->data())) a_.arr.non_const_handle(t)->set_data(from);
    settle();
  }

  int tips() const {
    return static_cast<int>(std::ranges::count_if(given_, [](const Given& g) { return g.tip->data() != g.from; }));
  }

  // The lines as the tips are given: those of a tip back with its own face drawn as they were.
  std::vector<PlanPolyline> lines() {
    std::set<Arrangement::Face_const_handle> changed;
    for (const auto& [t, from] : given_)
      if (t->data() != from) changed.insert(t);
    return arrangement_lines(a_, changed, first_new_);
  }

 private:
  // The tips' faces as labelled in the round: each with the face it comes from, and that face's
  // label or the neighbour's it was given to.
  struct Given {
    Arrangement::Face_const_handle tip;
    std::int32_t from;
  };
  Analyzer& a_;
  const TipRepairOptions& options_;
  std::vector<Given> given_;
  std::int32_t first_new_;  // the index of the round's first cut among the arrangement's lines

  // The round's tips, at most one a face: along Y first.
  std::vector<Tip> find_tips(const FT& W, const FT& wide, const FT& reach) const {
    std::vector<Tip> tips;
    for (std::size_t r = 0; r < a_.faces.size(); ++r) {
      if (a_.cut_out[r] || !a_.place[r].placed) continue;
      for (const bool along_Y : {true, false})
        if (std::optional<Tip> tip = tip_across(r, along_Y, W, wide, reach)) {
          tips.push_back(*tip);
          break;
        }
    }
    return tips;
  }

  // A tip of face r across its chords along Y (along_Y) or along X.
  std::optional<Tip> tip_across(std::size_t r, bool along_Y, const FT& W, const FT& wide, const FT& reach) const {
    const std::size_t axis = along_Y ? 0 : 1;
    const std::optional<Chord>& chord = a_.narrowest[r][axis];  // the analysis's, at this W
    if (!chord) return std::nullopt;
    const FaceLines face = face_lines(a_.rings[r], along_Y);
    std::optional<Tip> tip = tip_of(face, r, along_Y, *chord, W, wide, reach);
    // Where the narrowest chord parts no tip, the next narrowest may (a tip longer than its reach
    // from its end): 37 models at W = 3 mm, places 3,925 -> 3,892 (rounds stopped after one that
    // gained under 1 %, as then).
    for (auto other = a_.other_chords[r][axis].begin(); !tip && other != a_.other_chords[r][axis].end(); ++other)
      tip = tip_of(face, r, along_Y, chord_of(*other, along_Y), W, wide, reach);
    return tip;
  }

  // A cut ending a hair from a point of another line would meet it in a file: that tip stays.
  std::vector<Tip> clear_of_points(std::vector<Tip> tips) const {
    std::vector<std::pair<double, double>> points;
    for (auto v = a_.arr.vertices_begin(); v != a_.arr.vertices_end(); ++v)
      points.emplace_back(exact::approx_x(v->point()), exact::approx_y(v->point()));
    std::ranges::sort(points);
    const auto near_a_point = [&](const Point& p) {
      const double x = exact::approx_x(p), y = exact::approx_y(p);
      for (auto it =
               std::ranges::lower_bound(points, std::pair{x - kHair_mm, -std::numeric_limits<double>::infinity()});
           it != points.end() && it->first <= x + kHair_mm; ++it)
        if (std::abs(it->second - y) <= kHair_mm && (it->first != x || it->second != y)) return true;
      return false;
    };
    std::erase_if(tips, [&](const Tip& tip) {
      return near_a_point(on_plan(tip.along_Y, tip.u, tip.v_lo)) || near_a_point(on_plan(tip.along_Y, tip.u, tip.v_hi));
    });
    return tips;
  }

  // Each cut goes in; the face it parts keeps its label on both sides until the tip's is given.
  void cut_in(const std::vector<Tip>& tips) {
    struct KeepLabels : CGAL::Arr_observer<Arrangement> {
      using CGAL::Arr_observer<Arrangement>::Arr_observer;
      void after_split_face(Arrangement::Face_handle f, Arrangement::Face_handle new_f, bool) override {
        new_f->set_data(f->data());
      }
    } keep_labels(a_.arr);
    for (const Tip& tip : tips) {
      const Point p = on_plan(tip.along_Y, tip.u, tip.v_lo);
      const Point q = on_plan(tip.along_Y, tip.u, tip.v_hi);
      a_.kind.push_back(LineKind::Cut);
      CGAL::insert(a_.arr, exact::Traits::Curve_2(exact::Kernel::Segment_2(p, q),
                                                  static_cast<std::int32_t>(a_.kind.size() - 1)));
    }
    keep_labels.detach();
  }

  bool is_fold(Halfedge he) const {
    for (const std::int32_t d : he->curve().data()) {
      const LineKind k = a_.kind[static_cast<std::size_t>(d)];
      if (k == LineKind::Mountain || k == LineKind::Valley) return true;
    }
    return false;
  }

  // The fold edges between each pair of faces, both ways round.
  FoldCounts folds_between_faces() const {
    FoldCounts folds_between;
    for (auto e = a_.arr.edges_begin(); e != a_.arr.edges_end(); ++e) {
      const Halfedge he = e;
      if (he->face()->is_unbounded() || he->twin()->face()->is_unbounded() || !is_fold(he)) continue;
      ++folds_between[{he->face()->data(), he->twin()->face()->data()}];
      ++folds_between[{he->twin()->face()->data(), he->face()->data()}];
    }
    return folds_between;
  }

  // Which tips may go, decided on the labels as they are before any goes.
  std::vector<bool> tips_that_may_go(const std::vector<Tip>& tips, const std::vector<std::optional<Face>>& tip_faces,
                                     const FoldCounts& folds_between, const FT& wide) const {
    std::vector<bool> may_go(tips.size(), false);
    std::set<Arrangement::Face_const_handle> seen;
    for (std::size_t i = 0; i < tips.size(); ++i) {
      const std::optional<Face>& f = tip_faces[i];
      if (!f || (*f)->data() != static_cast<std::int32_t>(tips[i].region) || !seen.insert(*f).second) continue;
      // The cut must have parted a tip off, not left the face whole: a tip is at most its reach
      // long and `wide` across.
      double area = 0;
      for (const Ring& ring : rings_of(*f)) area += ring_area(ring);
      if (!(area <= options_.max_tip_mm * CGAL::to_double(wide)) || !(2 * area <= a_.result.area_mm2[tips[i].region]))
        continue;
      may_go[i] = leaves_neighbours_a_fold(*f, static_cast<std::int32_t>(tips[i].region), folds_between);
    }
    return may_go;
  }

  // Whether face `region` keeps a fold outside its tip `f` with each neighbour: a tip whose sides
  // hold all of its face's folds with a neighbour stays, or that neighbour would come loose.
  bool leaves_neighbours_a_fold(Face f, std::int32_t region, const FoldCounts& folds_between) const {
    std::map<std::int32_t, int> tip_folds;
    for_each_outer_halfedge(f, [&](Halfedge he) {
      if (!he->twin()->face()->is_unbounded() && is_fold(he)) ++tip_folds[he->twin()->face()->data()];
    });
    return std::ranges::none_of(tip_folds, [&](const auto& g) {
      const auto all = folds_between.find({region, g.first});
      return all != folds_between.end() && g.second == all->second;
    });
  }

  // The placed neighbour of the tip's face `f` whose plane is nearest the face's own at the tip's
  // inside point; -1 for none.
  std::int32_t nearest_neighbour(const Tip& tip, const Point& inside, Face f) const {
    const Place& own = a_.place[tip.region];
    const double Y = CGAL::to_double(inside.y());
    const double key = key_of_plane(own.orientation, CGAL::to_double(own.depth), Y);
    // A neighbour's plane must keep the tip on the card: a V(d) face's points at height Y + d >= 0,
    // an H(h) face's at depth h - Y >= 0. (Given regardless, a tip poked through the back plane
    // or the floor in 27 rounds over the 37 models at W = 3 mm, and each such round was refused.)
    const YRange range = y_range(f);
    const auto keeps_on_card = [&](const Place& p) {
      return !CGAL::is_negative(p.orientation == Orientation::V ? range.lowest + p.depth : p.depth - range.highest);
    };
    std::int32_t best = -1;
    double best_gap = std::numeric_limits<double>::infinity();
    for_each_outer_halfedge(f, [&](Halfedge he) {
      const Arrangement::Face_const_handle other = he->twin()->face();
      const std::int32_t n = other->data();
      if (!other->is_unbounded() && n >= 0 && n != static_cast<std::int32_t>(tip.region) &&
          !a_.cut_out[static_cast<std::size_t>(n)] && a_.place[static_cast<std::size_t>(n)].placed &&
          keeps_on_card(a_.place[static_cast<std::size_t>(n)])) {
        const Place& theirs = a_.place[static_cast<std::size_t>(n)];
        const double gap = std::abs(key_of_plane(theirs.orientation, CGAL::to_double(theirs.depth), Y) - key);
        if (gap < best_gap) best_gap = gap, best = n;
      }
    });
    return best;
  }

  // A tip given to a face whose own tip went elsewhere may touch no other part of it: it goes back.
  void settle() {
    std::set<Arrangement::Face_const_handle> tips;
    for (const Given& g : given_) tips.insert(g.tip);
    for (bool again = true; again;) {
      again = false;
      for (auto& [t, from] : given_) {
        if (t->data() == from) continue;
        bool joined = false;
        for_each_outer_halfedge(t, [&](Halfedge he) {
          const Face other = he->twin()->face();
          joined = joined || (other->data() == t->data() && !tips.contains(other));
        });
        if (!joined) a_.arr.non_const_handle(t)->set_data(from), again = true;
      }
    }
  }
};

// The faces of `before` with more narrow places after a round of tips (`after`, each of its regions
// lying in the face `cut_face` names of the cut arrangement, labelled as in `before`; -1 for none).
std::set<std::int32_t> narrow_places_grew(const PlanAnalysis& before, const PlanAnalysis& after,
                                          const std::vector<std::int32_t>& cut_face) {
  std::map<std::int32_t, int> change;
  for (const PlanProblem& p : before.problems)
    if (p.kind == PlanProblemKind::NarrowStrip && p.region >= 0) --change[p.region];
  for (const PlanProblem& p : after.problems)
    if (p.kind == PlanProblemKind::NarrowStrip && p.region >= 0) {
      assert(static_cast<std::size_t>(p.region) < cut_face.size());
      if (const std::int32_t face = cut_face[static_cast<std::size_t>(p.region)]; face >= 0) ++change[face];
    }
  std::set<std::int32_t> grew;
  for (const auto& [face, n] : change)
    if (n > 0) grew.insert(face);
  return grew;
}

// The places narrower than W an analysis finds.
std::ptrdiff_t narrow_places(const PlanAnalysis& a) {
  return std::ranges::count_if(a.problems, [](const PlanProblem& p) { return p.kind == PlanProblemKind::NarrowStrip; });
}

// Whether a plan stands: no error but places narrower than W.
bool stands(const PlanAnalysis& a) {
  return std::ranges::none_of(
      a.problems, [](const PlanProblem& p) { return is_error(p.kind) && p.kind != PlanProblemKind::NarrowStrip; });
}

// A round's tips as kept: the lines, their analysis, per region of it the face of the cut
// arrangement it lies in.
struct KeptRound {
  std::vector<PlanPolyline> lines;
  std::unique_ptr<Analyzer> analyzer;
  std::vector<std::int32_t> cut_face;
  int tips = 0;
};

// The round the cutter has cut, as kept: its tips as they are if the plan with them stands, has
// fewer places narrower than W, merges no more points in a file than the lines `before` did, and
// `keep` accepts it. A round refused is tried again, up to `retries` times, without the tips from
// or to the faces that now have more places than before. A round kept may still have given some
// faces more places than they had: once, their tips go back and the round without them is kept if
// it has fewer places still: over the 37 models at W = 3 mm, 26 of the 26 rounds so tried were kept
// without them, and places 3,892 -> 3,802 (rounds stopped after one that gained under 1 %; tried
// twice, the same). None if no try is kept.
std::optional<KeptRound> kept_round(TipCutter& cutter, const std::vector<PlanPolyline>& before,
                                    const TipRepairOptions& options, const TipRoundCheck& keep) {
  const PlanAnalysis& was = cutter.analyzer().result;
  const double low = was.sheet.min_Y + was.main_fold_Y;  // the drawing's frame
  const std::size_t merged_before = points_merged_in_files(before, low);
  // The cutter's tips as they are, analysed; none if there is none, two points become one in a
  // file, or the plan no longer stands.
  const auto analysed = [&]() -> std::optional<KeptRound> {
    KeptRound round{cutter.lines(), std::make_unique<Analyzer>(AnalysisOptions{.min_strip_mm = options.min_strip_mm}),
                    {}, cutter.tips()};
    if (round.tips == 0 || points_merged_in_files(round.lines, low) > merged_before) return std::nullopt;
    round.analyzer->run(round.lines);
    if (!stands(round.analyzer->result)) return std::nullopt;
    return round;
  };
  const auto better = [&](const KeptRound& round, const PlanAnalysis& than) {
    const PlanAnalysis& now = round.analyzer->result;
    return narrow_places(now) < narrow_places(than) && (!keep || keep(round.lines, now));
  };
  const auto cut_faces = [&](const PlanAnalysis& now) {
    std::vector<Point> insides;
    for (const PlanRegion& region : now.regions) insides.emplace_back(region.inside.X, region.inside.Y);
    std::vector<std::int32_t> faces;
    for (const std::optional<Face>& f : faces_at(cutter.analyzer().arr, insides)) faces.push_back(f ? (*f)->data() : -1);
    return faces;
  };
  // Names the round's regions by the cut arrangement's faces, and takes back the tips from or to
  // the faces that have more places than before; whether that leaves some tips, fewer than tried.
  const auto take_back_grown = [&](KeptRound& round) {
    round.cut_face = cut_faces(round.analyzer->result);
    const std::set<std::int32_t> grew = narrow_places_grew(was, round.analyzer->result, round.cut_face);
    if (grew.empty()) return false;
    cutter.take_back(grew);
    return cutter.tips() != 0 && cutter.tips() != round.tips;
  };
  std::optional<KeptRound> kept;
  for (int attempt = 0;; ++attempt) {
    kept = analysed();
    if (!kept) return std::nullopt;
    if (better(*kept, was)) break;
    if (attempt >= options.retries || !take_back_grown(*kept)) return std::nullopt;
  }
  if (!take_back_grown(*kept)) return kept;
  std::optional<KeptRound> pruned = analysed();
  if (!pruned || !better(*pruned, kept->analyzer->result)) return kept;
  pruned->cut_face = cut_faces(pruned->analyzer->result);
  return pruned;
}

}  // namespace

TipRepair blunt_narrow_tips(const std::vector<PlanPolyline>& lines, const TipRepairOptions& options,
                            const TipRoundCheck& keep) {
  const auto lock = exact_run_lock();
  TipRepair out{lines, {}, {}, 0, 0};
  // Each round's analysis is the next one's start.
  auto current = std::make_unique<Analyzer>(AnalysisOptions{.min_strip_mm = options.min_strip_mm});
  current->run(lines);
  for (const PlanRegion& region : current->result.regions) out.origin.push_back(region.inside);
  for (int round = 0; round < options.rounds && narrow_places(current->result) > 0; ++round) {
    std::optional<KeptRound> kept;
    {
      TipCutter cutter(*current, options);  // it cuts `current`'s arrangement: gone with it below
      cutter.run();
      kept = kept_round(cutter, out.lines, options, keep);
    }
    if (!kept) break;
    const auto places_before = narrow_places(current->result), places_after = narrow_places(kept->analyzer->result);
    // Each new region comes from the region of the cut arrangement its inside point lies in.
    std::vector<PlanPoint> origin;
    for (std::size_t i = 0; i < kept->cut_face.size(); ++i)
      origin.push_back(kept->cut_face[i] >= 0 ? out.origin[static_cast<std::size_t>(kept->cut_face[i])]
                                              : kept->analyzer->result.regions[i].inside);
    out.origin = std::move(origin);
    out.lines = std::move(kept->lines);
    out.tips += kept->tips;
    ++out.rounds;
    current = std::move(kept->analyzer);
    if (static_cast<double>(places_before - places_after) < options.min_round_gain * static_cast<double>(places_before))
      break;
  }
  out.analysis = std::move(current->result);
  return out;
}

}  // namespace origamic
