// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: one round of tips parted off an analysed plan's arrangement (TipCutter, tips.hpp): each
// cut in across its face where the face is W wide, and given to the neighbour whose plane lies
// nearest. One exact run at a time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include <CGAL/Arr_batched_point_location.h>
#include <CGAL/Arr_observer.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "exact_kernel.hpp"
#include "tips.hpp"

namespace origamic::tips {
namespace {

using analysis::Chord;
using analysis::Face;
using analysis::Halfedge;
using analysis::Place;
using analysis::Ring;
using analysis::ring_area;
using analysis::rings_of;
using exact::Arrangement;
using exact::Point;

// A round the picture refused goes back this share of its tips, the costliest (take_back_costliest):
// over the 37 models at W = 3 mm, a quarter 3,766 places, half (tried twice) 3,803.
constexpr std::size_t kCostliestShare = 4;

// Closer than this a new cut's line and a vertex's are one in a file (its Y rounded from the sheet's
// lower edge, about 1e-14 mm): far below any cutter, far above the rounding.
constexpr double kHair_mm = 1e-9;

// A point of the plan at u across a chord and v along it, the chord along Y (along_Y) or along X.
Point on_plan(bool along_Y, const FT& u, const FT& v) { return along_Y ? Point(u, v) : Point(v, u); }

// Each halfedge of a face's outer boundaries, in order.
template <typename Visit>
void for_each_outer_halfedge(Face f, Visit visit) {
  for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
    auto he = *ccb;
    do visit(Halfedge(he));
    while (++he != *ccb);
  }
}

// A face's area: its outer rings' less its holes'.
double area_of(Face f) {
  double area = 0;
  for (const Ring& ring : rings_of(f)) area += ring_area(ring);
  return area;
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

}  // namespace

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

void TipCutter::run() {
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
    const Neighbour best = nearest_neighbour(tips[i], insides[i], *tip_faces[i]);
    if (best.face < 0) continue;
    a_.arr.non_const_handle(*tip_faces[i])->set_data(best.face);
    given_.push_back({*tip_faces[i], static_cast<std::int32_t>(tips[i].region), area_of(*tip_faces[i]) * best.gap_mm});
  }
  settle();
}

void TipCutter::take_back(const std::set<std::int32_t>& held) {
  for (const Given& g : given_)
    if (held.contains(g.from) || held.contains(g.tip->data())) a_.arr.non_const_handle(g.tip)->set_data(g.from);
  settle();
}

void TipCutter::take_back_costliest() {
  std::vector<const Given*> given;
  for (const Given& g : given_)
    if (g.tip->data() != g.from) given.push_back(&g);
  // Of tips as costly, the first given stays first (given_ is in the order the tips were found).
  std::ranges::stable_sort(given, std::greater{}, &Given::moved_mm3);
  for (std::size_t i = 0; i < std::max<std::size_t>(1, given.size() / kCostliestShare) && i < given.size(); ++i)
    a_.arr.non_const_handle(given[i]->tip)->set_data(given[i]->from);
  settle();
}

int TipCutter::tips() const {
  return static_cast<int>(std::ranges::count_if(given_, [](const Given& g) { return g.tip->data() != g.from; }));
}

std::vector<PlanPolyline> TipCutter::lines() {
  std::set<Arrangement::Face_const_handle> changed;
  for (const Given& g : given_)
    if (g.tip->data() != g.from) changed.insert(g.tip);
  return arrangement_lines(a_, changed, first_new_);
}

std::vector<Tip> TipCutter::find_tips(const FT& W, const FT& wide, const FT& reach) const {
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

std::optional<Tip> TipCutter::tip_across(std::size_t r, bool along_Y, const FT& W, const FT& wide,
                                         const FT& reach) const {
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

std::vector<Tip> TipCutter::clear_of_points(std::vector<Tip> tips) const {
  std::vector<std::pair<double, double>> points;
  for (auto v = a_.arr.vertices_begin(); v != a_.arr.vertices_end(); ++v)
    points.emplace_back(exact::approx_x(v->point()), exact::approx_y(v->point()));
  std::ranges::sort(points);
  const auto near_a_point = [&](const Point& p) {
    const double x = exact::approx_x(p), y = exact::approx_y(p);
    for (auto it = std::ranges::lower_bound(points, std::pair{x - kHair_mm, -std::numeric_limits<double>::infinity()});
         it != points.end() && it->first <= x + kHair_mm; ++it)
      if (std::abs(it->second - y) <= kHair_mm && (it->first != x || it->second != y)) return true;
    return false;
  };
  std::erase_if(tips, [&](const Tip& tip) {
    return near_a_point(on_plan(tip.along_Y, tip.u, tip.v_lo)) || near_a_point(on_plan(tip.along_Y, tip.u, tip.v_hi));
  });
  return tips;
}

void TipCutter::cut_in(const std::vector<Tip>& tips) {
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
    CGAL::insert(a_.arr,
                 exact::Traits::Curve_2(exact::Kernel::Segment_2(p, q), static_cast<std::int32_t>(a_.kind.size() - 1)));
  }
  keep_labels.detach();
}

bool TipCutter::is_fold(Halfedge he) const {
  for (const std::int32_t d : he->curve().data()) {
    const LineKind k = a_.kind[static_cast<std::size_t>(d)];
    if (k == LineKind::Mountain || k == LineKind::Valley) return true;
  }
  return false;
}

TipCutter::FoldCounts TipCutter::folds_between_faces() const {
  FoldCounts folds_between;
  for (auto e = a_.arr.edges_begin(); e != a_.arr.edges_end(); ++e) {
    const Halfedge he = e;
    if (he->face()->is_unbounded() || he->twin()->face()->is_unbounded() || !is_fold(he)) continue;
    ++folds_between[{he->face()->data(), he->twin()->face()->data()}];
    ++folds_between[{he->twin()->face()->data(), he->face()->data()}];
  }
  return folds_between;
}

std::vector<bool> TipCutter::tips_that_may_go(const std::vector<Tip>& tips,
                                              const std::vector<std::optional<Face>>& tip_faces,
                                              const FoldCounts& folds_between, const FT& wide) const {
  std::vector<bool> may_go(tips.size(), false);
  std::set<Arrangement::Face_const_handle> seen;
  for (std::size_t i = 0; i < tips.size(); ++i) {
    const std::optional<Face>& f = tip_faces[i];
    if (!f || (*f)->data() != static_cast<std::int32_t>(tips[i].region) || !seen.insert(*f).second) continue;
    // The cut must have parted a tip off, not left the face whole: a tip is at most its reach
    // long and `wide` across.
    const double area = area_of(*f);
    if (!(area <= options_.max_tip_mm * CGAL::to_double(wide)) || !(2 * area <= a_.result.area_mm2[tips[i].region]))
      continue;
    may_go[i] = leaves_neighbours_a_fold(*f, static_cast<std::int32_t>(tips[i].region), folds_between);
  }
  return may_go;
}

bool TipCutter::leaves_neighbours_a_fold(Face f, std::int32_t region, const FoldCounts& folds_between) const {
  std::map<std::int32_t, int> tip_folds;
  for_each_outer_halfedge(f, [&](Halfedge he) {
    if (!he->twin()->face()->is_unbounded() && is_fold(he)) ++tip_folds[he->twin()->face()->data()];
  });
  return std::ranges::none_of(tip_folds, [&](const auto& g) {
    const auto all = folds_between.find({region, g.first});
    return all != folds_between.end() && g.second == all->second;
  });
}

TipCutter::Neighbour TipCutter::nearest_neighbour(const Tip& tip, const Point& inside, Face f) const {
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
  Neighbour best{-1, std::numeric_limits<double>::infinity()};
  for_each_outer_halfedge(f, [&](Halfedge he) {
    const Arrangement::Face_const_handle other = he->twin()->face();
    const std::int32_t n = other->data();
    if (!other->is_unbounded() && n >= 0 && n != static_cast<std::int32_t>(tip.region) &&
        !a_.cut_out[static_cast<std::size_t>(n)] && a_.place[static_cast<std::size_t>(n)].placed &&
        keeps_on_card(a_.place[static_cast<std::size_t>(n)])) {
      const Place& theirs = a_.place[static_cast<std::size_t>(n)];
      const double gap = std::abs(key_of_plane(theirs.orientation, CGAL::to_double(theirs.depth), Y) - key);
      if (gap < best.gap_mm) best = {n, gap};
    }
  });
  return best;
}

void TipCutter::settle() {
  std::set<Arrangement::Face_const_handle> tips;
  for (const Given& g : given_) tips.insert(g.tip);
  for (bool again = true; again;) {
    again = false;
    for (const Given& g : given_) {
      if (g.tip->data() == g.from) continue;
      bool joined = false;
      for_each_outer_halfedge(g.tip, [&](Halfedge he) {
        const Face other = he->twin()->face();
        joined = joined || (other->data() == g.tip->data() && !tips.contains(other));
      });
      if (!joined) a_.arr.non_const_handle(g.tip)->set_data(g.from), again = true;
    }
  }
}

}  // namespace origamic::tips
