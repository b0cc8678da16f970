// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "origamic/plan.hpp"
#include "support_candidates.hpp"
#include "support_ears.hpp"
#include "support_picture.hpp"

namespace origamic {
namespace {

// Two supports one above the other in the same columns, less than a strip width apart, leave a strip
// of paper narrower than W between two parallel folds (seed §4.3.2): the wedge's ramp had treads of
// 0.3-0.6 mm where a riser up from one slice and one down from the next took rows of the slice between.
// Over the 37 models narrow places went 5,360 -> 5,194, mean p95 2.56 -> 2.49 W. Keeping supports side
// by side W apart too (5,119) cost the sphere 0.35 W of p95 and the temple 0.64 W: not done.
bool too_close(PixelRect a, PixelRect b, int block_px) {
  const int col_gap = std::max(a.c0, b.c0) - std::min(a.c1, b.c1);
  const int row_gap = std::max(a.r0, b.r0) - std::min(a.r1, b.r1);
  return col_gap < 0 && 0 < row_gap && row_gap < block_px;
}

// The pixels the supports chosen so far cover, and the rows just outside them, of the face they
// leave and the face they reach, which must stay those faces for the support to fold onto them. Two
// supports may share an anchor; neither may cover the other's, nor lie above or below it less than W
// away.
class Claims {
 public:
  Claims(int cols, int rows, int block_px) : mark_(cols, rows, kFree), block_px_(block_px) {}

  bool fits(const Candidate& s) const { return fits_columns(s, s.c0, s.c1); }
  bool fits_columns(const Candidate& s, int c0, int c1) const {
    for (int c = c0; c < c1; ++c) {
      for (int r = s.r0; r < s.r1; ++r)
        if (mark_(c, r) != kFree) return false;
      for (const int r : {s.face_row, s.target_row})
        if (mark_.contains(c, r) && mark_(c, r) == kCovered) return false;
    }
    const PixelRect columns{c0, c1, s.r0, s.r1};
    return std::ranges::none_of(claimed_, [&](PixelRect t) { return too_close(columns, t, block_px_); });
  }
  void claim(const Candidate& s) {
    for (int c = s.c0; c < s.c1; ++c) {
      for (int r = s.r0; r < s.r1; ++r) mark_(c, r) = kCovered;
      for (const int r : {s.face_row, s.target_row})
        if (mark_.contains(c, r)) mark_(c, r) = std::max(mark_(c, r), kAnchor);
    }
    claimed_.push_back(s.pixels());
  }

 private:
  static constexpr std::uint8_t kFree = 0, kAnchor = 1, kCovered = 2;
  Grid<std::uint8_t> mark_;
  int block_px_;
  std::vector<PixelRect> claimed_;
};

// Whether one support covers what the other covers or folds onto, or lies above or below it less
// than W away.
bool interfere(const Candidate& a, const Candidate& b, int block_px) {
  if (too_close(a.pixels(), b.pixels(), block_px)) return true;
  if (a.c1 <= b.c0 || b.c1 <= a.c0) return false;
  const auto covers = [](const Candidate& s, int r) { return s.r0 <= r && r < s.r1; };
  return (a.r0 < b.r1 && b.r0 < a.r1) || covers(a, b.face_row) || covers(a, b.target_row) || covers(b, a.face_row) ||
         covers(b, a.target_row);
}

// Seed §4.4, last part: a support grows a column at a time to either side while that column still
// joins the same two faces, covers no other face and shows the model no worse than what it covers.
// It may cover rows of the two faces it joins, but not so as to cut either in two.
void widen(const Grid<std::int32_t>& face, const Claims& claims, const SupportPicture& picture,
           const CandidateFinder& finder, Candidate& s) {
  auto column_fits = [&](int c) {
    if (c < 0 || c >= face.cols || face(c, s.face_row) != s.face || face(c, s.target_row) != s.target) return false;
    if (!claims.fits_columns(s, c, c + 1)) return false;
    bool covers_them = false;
    for (int r = s.r0; r < s.r1; ++r) {
      if (face(c, r) != s.face && face(c, r) != s.target) return false;
      covers_them = true;
    }
    if (picture.added_error(s.orientation, s.depth_mm, {c, c + 1, s.r0, s.r1}) > 0) return false;
    if (!covers_them) return true;
    Candidate wider = s;
    wider.c0 = std::min(s.c0, c), wider.c1 = std::max(s.c1, c + 1);
    return !finder.cuts(s.face, wider) && !finder.cuts(s.target, wider);
  };
  while (column_fits(s.c0 - 1)) --s.c0;
  while (column_fits(s.c1)) ++s.c1;
}

}  // namespace

FaceVerdicts verdicts_of(const Plan& plan) {
  FaceVerdicts s{plan.validity, {}, {}};
  for (const PlanFace& face : plan.faces) {
    s.fold_on_top.push_back(face.fold_on_top);
    s.fold_on_bottom.push_back(face.fold_on_bottom);
  }
  return s;
}

SupportEdge support_edge(const Candidate& c, const std::vector<std::uint8_t>& stands, const SupportOptions& options,
                         double W) {
  double extra = 0;
  for (const std::int32_t x : c.cuts) extra += (stands[static_cast<std::size_t>(x)] ? 10 : 1) * options.split_cost_mm;
  const double face_Y = c.near.h - c.near.d, target_Y = c.far.h - c.far.d;
  if (std::abs(target_Y - face_Y) < W - kFoldLineTolerance_mm) extra += options.short_support_cost_mm;
  if (c.leaves_thin_strip()) extra += options.thin_strip_cost_mm;
  // A sixth of W: 0.5 mm at the default W = 3 mm, where a strip between two folds is a sliver.
  if (c.thin_strip_mm < W / 6) extra += options.sliver_strip_cost_mm;
  if (c.past_end) extra += options.past_end_cost_mm;
  return {c.face, c.target, face_Y, target_Y, c.cost + extra, c.cost, c.cuts};
}

namespace {

// Ear by ear, the hardest face's first: its faces stand from then on, and its supports claim their
// pixels, which no later support may overlap.
class EarTaker {
 public:
  EarTaker(const SupportRound& round, const FaceVerdicts& verdicts, const std::vector<std::int32_t>& invalid,
           const SupportOptions& options, SupportReach reach, const std::vector<std::uint8_t>& hold_at_any_cost)
      : round_(round),
        options_(options),
        picture_(round.maps, round.raster_plan),
        finder_(round, invalid, picture_, reach),
        candidates_(candidates_of(finder_, invalid, reach.split_faces)),
        stands_(round.raster_plan.faces.size(), 0),
        open_(round.raster_plan.faces.size(), 0),
        usable_(candidates_.size(), 1),
        limit_(round.raster_plan.faces.size(), 0),
        claims_(round.raster_plan.face.cols, round.raster_plan.face.rows, round.raster_plan.block_px) {
    const std::vector<RasterFace>& faces = round.raster_plan.faces;
    for (std::size_t f = 0; f < faces.size() && f < verdicts.validity.status.size(); ++f)
      stands_[f] = verdicts.validity.status[f] == FaceStatus::Valid && !faces[f].hole;
    // A face is held only while that costs the picture no more than cutting it out or, where it
    // may be cut out, giving it whole to its nearest neighbour (supports.cpp,
    // FaceOrderRun::give_away, which shares it among its neighbours where that costs less), a
    // join adding no more than SupportOptions::join_error_cap_W per pixel.
    // Bounded by the shares' error instead, the mean p95 over the 37 models went 2.19 -> 2.28 W
    // (res_knot 5.1 -> 8.2 W): more faces went to neighbours where a support would have held them.
    const double W = round.raster_plan.min_strip_mm;
    const std::vector<SupportPicture::Join> joins = options.cut_out_unsupported
                                                        ? picture_.nearest_joins(round.raster_plan, invalid)
                                                        : std::vector<SupportPicture::Join>(invalid.size());
    for (std::size_t i = 0; i < invalid.size(); ++i) {
      const auto f = static_cast<std::size_t>(invalid[i]);
      open_[f] = 1;
      const bool within_cap = picture_.mean_error_mm(joins[i].error, faces[f].pixels) <= options.join_error_cap_W * W;
      const double join = within_cap ? joins[i].error : std::numeric_limits<double>::infinity();
      // A face the holes may not take has no hole to weigh: it is held, or joined.
      const double hole = f < hold_at_any_cost.size() && hold_at_any_cost[f] ? std::numeric_limits<double>::infinity()
                                                                             : picture_.hole_error(invalid[i]);
      limit_[f] = std::max(0.0, std::min(hole, join)) / (W * W);
    }
  }

  // First the ears that cut no standing face in two, as many as there are; only when there are
  // none, one ear that does, the cheapest: the faces it cuts are pieces for the next round to hold,
  // as it sees them, where ears taken after it here would assume them whole.
  SupportChoice choose() {
    for (bool cutting = false;;) {
      std::vector<std::uint8_t> allowed = usable_;
      if (!cutting)
        for (std::size_t k = 0; k < allowed.size(); ++k) allowed[k] &= !cuts_standing(candidates_[k]);
      const EarSearch search(static_cast<std::int32_t>(stands_.size()), round_.folds, edges_now());
      EarSearch::Choice next =
          cutting ? search.cheapest(stands_, open_, limit_, allowed) : search.hardest(stands_, open_, limit_, allowed);
      if (next.ears.empty()) {
        if (!cutting && choice_.supports.empty()) {
          cutting = true;
          continue;
        }
        if (choice_.supports.empty())
          for (const auto& [f, hold] : next.beyond_limit) {
            const double W = round_.raster_plan.min_strip_mm;
            choice_.cut_out.push_back({f, hold, std::max(0.0, picture_.hole_error(f)) / (W * W)});
          }
        break;
      }
      // The batch in order, each ear but those to be sought again; a cutting ear alone.
      bool took = false;
      for (const Ear& ear : next.ears) {
        if (!admissible(ear)) continue;
        take(ear);
        took = true;
        if (cutting) break;
      }
      if (cutting && took) break;
    }
    return std::move(choice_);
  }

 private:
  std::vector<SupportEdge> edges_now() const {
    std::vector<SupportEdge> edges;
    edges.reserve(candidates_.size());
    for (const Candidate& c : candidates_)
      edges.push_back(support_edge(c, stands_, options_, round_.raster_plan.min_strip_mm));
    return edges;
  }
  int block_px() const { return round_.raster_plan.block_px; }
  bool cuts_standing(const Candidate& c) const {
    return std::ranges::any_of(c.cuts, [&](std::int32_t x) { return stands_[static_cast<std::size_t>(x)] != 0; });
  }
  // An ear's supports may interfere with each other or with those taken before (they were found
  // apart), or cut a face of their own ear in two, alone or with the supports before it (side by
  // side, touching, two that each leave a face whole may part it, or part a face they fold onto):
  // such a support is given up and the ear sought again without it. Tested one at a time, the faces
  // seedlike/sphere's ears joined were often still unheld the round after (15 of 20 after its
  // third), and it took 21 rounds of supports, now 12. Alone, a support is not asked whether it
  // parts the face it folds onto (a slanted edge of it may run into the support's columns): giving
  // those up took the 37 models at W = 3 mm from 4,235 to 4,052 places but their mean p95 from 1.788
  // to 1.836 W. Nor does widening ask the supports together (take): that left 4,236 places.
  bool admissible(const Ear& ear) {
    bool all = true;
    std::vector<PixelRect> with;
    for (const Candidate& s : choice_.supports) with.push_back(s.pixels());
    for (std::size_t i = 0; i < ear.supports.size(); ++i) {
      const Candidate& c = candidates_[ear.supports[i]];
      bool bad = !claims_.fits(c);
      for (std::size_t j = 0; j < i && !bad; ++j) bad = interfere(c, candidates_[ear.supports[j]], block_px());
      for (const std::int32_t x : c.cuts) bad = bad || std::ranges::find(ear.faces, x) != ear.faces.end();
      for (const std::int32_t x : ear.faces) bad = bad || finder_.cuts_with(x, with, c.pixels());
      for (const std::int32_t x : {c.face, c.target}) bad = bad || finder_.cuts_with(x, with, c.pixels());
      if (bad)
        usable_[ear.supports[i]] = 0, all = false;
      else
        with.push_back(c.pixels());
    }
    return all;
  }
  void take(const Ear& ear) {
    std::vector<Candidate>& chosen = choice_.supports;
    const std::size_t first_new = chosen.size();
    // All of the ear's supports are claimed before any is widened, so that none widens up to
    // another's columns less than W above or below it (the wedge's treads of 0.3 mm at its side).
    for (const std::size_t k : ear.supports) claims_.claim(candidates_[k]);
    for (const std::size_t k : ear.supports) {
      Candidate s = candidates_[k];
      widen(round_.raster_plan.face, claims_, picture_, finder_, s);
      claims_.claim(s);
      chosen.push_back(s);
    }
    for (const std::int32_t f : ear.faces)
      stands_[static_cast<std::size_t>(f)] = 1, open_[static_cast<std::size_t>(f)] = 0;
    for (std::size_t k = 0; k < candidates_.size(); ++k)
      for (std::size_t j = first_new; j < chosen.size() && usable_[k]; ++j)
        usable_[k] = !interfere(candidates_[k], chosen[j], block_px());
  }

  const SupportRound& round_;
  const SupportOptions& options_;
  const SupportPicture picture_;
  const CandidateFinder finder_;
  const std::vector<Candidate> candidates_;
  std::vector<std::uint8_t> stands_, open_, usable_;
  std::vector<double> limit_;
  Claims claims_;
  SupportChoice choice_;
};

}  // namespace

SupportChoice choose_supports(const SupportRound& round, const FaceVerdicts& verdicts,
                              const std::vector<std::int32_t>& invalid, const SupportOptions& options,
                              SupportReach reach, const std::vector<std::uint8_t>& hold_at_any_cost) {
  return EarTaker(round, verdicts, invalid, options, reach, hold_at_any_cost).choose();
}

}  // namespace origamic
