// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: the tips of faces narrower than W parted off on the exact arrangement of a plan's lines
// (blunt_narrow_tips, plan_analysis.hpp), round after round, each round's lines analysed again
// (plan_analysis.cpp); each round's tips are found and cut in by tips.hpp. One exact run at a time:
// see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <cassert>
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
#include "tips.hpp"

namespace origamic {
namespace {

using analysis::Analyzer;
using analysis::Face;
using exact::Point;
using tips::faces_at;
using tips::TipCutter;

// How many points of the lines a file's rounding of Y (from the sheet's lower edge, `low`) makes
// one with another: the design's own plans have a few (res_bunny: 1), which its reader takes as
// drawn.
std::size_t points_merged_in_files(const std::vector<PlanPolyline>& lines, double low) {
  std::vector<std::pair<double, double>> exact, filed;
  for (const PlanPolyline& line : lines)
    for (const PlanPoint& p : line.points) exact.emplace_back(p.X, p.Y), filed.emplace_back(p.X, (p.Y - low) + low);
  const auto distinct = [](std::vector<std::pair<double, double>>& points) {
    std::ranges::sort(points);
    return static_cast<std::size_t>(std::ranges::unique(points).begin() - points.begin());
  };
  return distinct(exact) - distinct(filed);
}

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
// `keep` accepts it. One with fewer places that `keep` refuses is tried again without its costliest
// tips (TipRepairOptions::picture_retries). A round refused is tried again, up to `retries` times, without the tips
// from or to the faces that now have more places than before. A round kept may still have given some faces more places
// than they had: once, their tips go back and the round without them is kept if it has fewer places still: over the 37
// models at W = 3 mm, 26 of the 26 rounds so tried were kept without them, and places 3,892 -> 3,802 (rounds stopped
// after one that gained under 1 %; tried twice, the same). None if no try is kept.
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
  // Whether the round has fewer places than `than`, and whether the check given accepts it.
  struct Verdict {
    bool fewer = false, looks = false;
    bool better() const { return fewer && looks; }
  };
  const auto judged = [&](const KeptRound& round, const PlanAnalysis& than) {
    const PlanAnalysis& now = round.analyzer->result;
    Verdict v{narrow_places(now) < narrow_places(than), false};
    v.looks = v.fewer && (!keep || keep(round.lines, now));
    return v;
  };
  const auto better = [&](const KeptRound& round, const PlanAnalysis& than) { return judged(round, than).better(); };
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
  for (int attempt = 0, costly = 0;;) {
    kept = analysed();
    if (!kept) return std::nullopt;
    const Verdict verdict = judged(*kept, was);
    if (verdict.better()) break;
    // Fewer places, but the check refused the picture: the tips that move the most of it go back.
    if (verdict.fewer && costly < options.picture_retries && kept->tips > 1) {
      ++costly;
      cutter.take_back_costliest();
      continue;
    }
    if (attempt++ >= options.retries || !take_back_grown(*kept)) return std::nullopt;
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
