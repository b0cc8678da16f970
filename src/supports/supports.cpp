// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/supports.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <utility>

#include "exact_runs.hpp"
#include "face_order_run.hpp"
#include "raster_plan_edits.hpp"
#include "support_choice.hpp"
#include "support_mirror.hpp"

namespace origamic {

bool needs_support(FaceStatus status, bool allow_dangling) {
  return status == FaceStatus::Floating || status == FaceStatus::Invalid ||
         (status == FaceStatus::Dangling && !allow_dangling);
}

std::vector<NarrowStrip> narrow_strips(const RasterPlan& raster_plan, const PixelGrid& grid) {
  const std::size_t n = raster_plan.faces.size();
  std::vector<int> lo(n, INT_MAX), hi(n, -1), lo_row(n, 0);
  for (int r = 0; r < raster_plan.face.rows; ++r)
    for (int c = 0; c < raster_plan.face.cols; ++c) {
      const std::int32_t f = raster_plan.face(c, r);
      if (f < 2) continue;
      const auto i = static_cast<std::size_t>(f);
      if (c < lo[i]) lo[i] = c, lo_row[i] = r;
      hi[i] = std::max(hi[i], c);
    }
  std::vector<NarrowStrip> narrow;
  for (std::size_t f = 2; f < n; ++f) {
    if (hi[f] < 0 || raster_plan.faces[f].hole || hi[f] - lo[f] + 1 >= raster_plan.block_px) continue;
    // Its place: its top pixel in its middle column, or its leftmost pixel if it has none there.
    int col = lo[f], row = lo_row[f];
    const int mid = (lo[f] + hi[f]) / 2;
    for (int r = 0; r < raster_plan.face.rows; ++r)
      if (raster_plan.face(mid, r) == static_cast<std::int32_t>(f)) {
        col = mid, row = r;
        break;
      }
    narrow.push_back({static_cast<std::int32_t>(f),
                      raster_plan.faces[f].support,
                      (hi[f] - lo[f] + 1) / grid.px_per_mm,
                      {grid.X(col), grid.Y(row)}});
  }
  return narrow;
}

std::string stop_reason(const SupportReport& report) {
  const std::string faces = std::to_string(report.stop_faces) + " faces ";
  std::string text;
  switch (report.stop) {
    case SupportStop::None: return text;
    case SupportStop::NoProgress: text = faces + "still invalid: no progress in 3 rounds"; break;
    case SupportStop::RoundBound:
      text = faces + "still invalid after " + std::to_string(report.round_bound) + " rounds (the loop's bound)";
      break;
    case SupportStop::Unreachable: text = faces + "invalid and no support reaches them"; break;
    case SupportStop::ExactInvalid: text = faces + "invalid in the exact plan"; break;
  }
  if (report.stop_loose_pieces > 0)
    text += "; " + std::to_string(report.stop_loose_pieces) + " loose pieces of the back plane or the floor";
  if (report.stop_at_quota) text += "; cutting them out would remove over a quarter of the model";
  return text;
}

bool plan_stands(const Validity& validity, bool allow_dangling) {
  return validity.floating + validity.invalid == 0 && (allow_dangling || validity.dangling == 0);
}

bool plan_stands(const Plan& plan, bool allow_dangling) {
  return plan_stands(plan.validity, allow_dangling) && plan.loose_card_pieces == 0;
}

namespace {

constexpr int kSplitRetryRounds = 8;
// The orders from this one on (and the last, should there be fewer) may cut faces in two again.
constexpr int kSplitRetryFromOrder = 3;
// Later orders reach farther (SupportReach), each from its order on (and at the last, should there be
// fewer): the first keeps to the plain rules, which most models stand by, and fast.
constexpr int kBelowTipsFromOrder = 1;
constexpr int kCornersFromOrder = 1;

}  // namespace

// Rounds of supports until every face stands or they stop helping; returns why they stopped.
FaceOrderRun::Stopped FaceOrderRun::support_rounds() {
  SupportReport& tally = report();
  std::size_t fewest_invalid = SIZE_MAX;
  int rounds_without_progress = 0;
  for (;;) {
    std::vector<std::int32_t> invalid = invalid_faces();
    if (invalid.empty()) return {};
    const int count = static_cast<int>(invalid.size());
    // Supports that split other faces can leave as many invalid faces as they fixed: give up
    // when three rounds in a row made no progress.
    if (invalid.size() < fewest_invalid)
      fewest_invalid = invalid.size(), rounds_without_progress = 0;
    else if (++rounds_without_progress >= 3)
      return {SupportStop::NoProgress, count};
    if (!rounds_left()) return {SupportStop::RoundBound, count};
    ++tally.rounds;
    std::shuffle(invalid.begin(), invalid.end(), random_);
    SupportReach round_reach = rules_.reach;
    round_reach.split_faces = allow_splits_ || split_rounds_left_-- > 0;
    const std::vector<FoldEdge> folds =
        raster_folds(setting_.maps.grid, raster_plan_, aligned_fold_tolerance_mm(setting_.maps.grid));
    const SupportChoice choice =
        choose_supports({setting_.maps, raster_plan_, *last_exact_plan_, painted_since_, folds}, verdicts_, invalid,
                        setting_.options, round_reach, held_at_any_cost());
    const std::vector<Candidate>& chosen = choice.supports;
    if (chosen.empty() && choice.cut_out.empty()) return {SupportStop::Unreachable, count};
    tally.supports += static_cast<int>(chosen.size());
    // Faces whose holding would cost the picture more than their hole are cut out (seed §4.4 never
    // cuts; a support across the model to a crumb at its back is worse than the crumb's hole), once
    // no support is left to add: the supports of this round may yet bring them a cheaper one.
    if (setting_.options.cut_out_unsupported && chosen.empty()) cut_out_costly(choice.cut_out);
    raster_plan_ = paint_supports(std::move(raster_plan_), chosen, setting_.maps.grid, tolerance_, crumb_px_);
    painted_since_.insert(painted_since_.end(), chosen.begin(), chosen.end());
    settle();
  }
}

// A pass of rounds from the last verdict, and the exact plan's verdict on where it ends; returns why
// the rounds stopped. A pass from an exact verdict that leaves more faces invalid than it found is
// undone: its supports did harm, and the exact plan of the raster plan before it is at hand. (Undoing
// passes that left as many, as the greedy choice did, repeats them: the ears of a state are the
// same each time.) Found is the fewer of the exact count and the raster graph's: the pass's end is counted on
// the raster graph, which may miss a face the exact plan sees.
FaceOrderRun::Stopped FaceOrderRun::pass() {
  const bool from_exact = exact_;
  std::size_t invalid_before = invalid_faces().size();
  if (exact_) {
    const FaceVerdicts raster =
        raster_verdicts(setting_.maps.grid, raster_plan_, aligned_fold_tolerance_mm(setting_.maps.grid));
    invalid_before = std::min(invalid_before, unsupported(raster, setting_.options.allow_dangling).size());
  }
  const int supports_before = report().supports, cut_out_before = report().cut_out;
  const std::size_t cut_out_faces_before = report().cut_out_faces.size();
  const std::size_t joined_faces_before = report().joined_faces.size();
  const std::size_t spared_before = spared_pixels_.size();
  const std::int64_t cut_out_pixels_before = cut_out_pixels_;
  const Stopped why = support_rounds();
  if (from_exact && why.why != SupportStop::None && invalid_faces().size() > invalid_before) {
    raster_plan_.face = confirmed_.first;
    raster_plan_.faces = confirmed_.second;
    report().supports = supports_before;  // the rounds still count against the bound
    report().cut_out = cut_out_before;
    report().cut_out_faces.resize(cut_out_faces_before);
    report().joined_faces.resize(joined_faces_before);
    report().spared_faces.resize(spared_before), spared_pixels_.resize(spared_before);
    cut_out_pixels_ = cut_out_pixels_before;
    report().cut_out_share =
        static_cast<double>(cut_out_pixels_) / static_cast<double>(std::max<std::int64_t>(1, model_pixels_));
    verdicts_ = verdicts_of(result_.plan);
    exact_ = true;
    painted_since_.clear();
    ++report().passes_undone;
  } else if (!exact_) {  // else the raster plan is still the exact plan's, and it stands as it is
    confirm();
  }
  return why;
}

// The exact plan decides on pieces of paper: a face it finds invalid may be in pieces the raster
// graph took for one. Those become faces of their own, and the rounds go on. From then on no
// support may cut a face in two: the pieces it made would need supports of their own, whose
// supports cut more faces, without end. A part under the crumb size (or a whole face) joins a
// neighbour instead: a face left without pixels is merged away, not a face the rounds would have to
// hold. A join adds no piece, so supports may still cut faces in two. Either way the raster plan is no
// longer the exact plan's. Returns whether the face map changed.
bool FaceOrderRun::part_faces(const std::vector<std::int32_t>& invalid, int loose) {
  std::vector<std::int32_t> apart = invalid;
  if (loose > 0) apart.insert(apart.end(), {kBackFace, kFloorFace});
  const auto before = raster_plan_.face.values;
  const int block_px = raster_plan_.block_px;
  SplitFaces split = split_disconnected_faces(std::move(raster_plan_), apart, crumb_px_, block_px);
  raster_plan_ = std::move(split.raster_plan);
  const bool parted = !split.parts.empty();
  if (!parted && raster_plan_.face.values == before) return false;
  allow_splits_ = allow_splits_ && !parted;
  raster_plan_ = merge_coplanar_faces(std::move(raster_plan_));
  settle();
  return true;
}

SupportedPlan FaceOrderRun::run() {
  adopt(setting_.initial);  // every pass, the first too, walks an exact plan
  std::size_t fewest_exact = SIZE_MAX;
  for (;;) {
    const Stopped why = pass();
    std::vector<std::int32_t> invalid = invalid_faces();
    const int loose = result_.plan.loose_card_pieces;
    if (invalid.empty() && loose == 0) break;
    SupportReport& tally = report();
    tally.stop = why.why == SupportStop::None ? SupportStop::ExactInvalid : why.why;
    tally.stop_faces = why.why == SupportStop::None ? static_cast<int>(invalid.size()) : why.faces;
    tally.stop_loose_pieces = loose;
    tally.stop_at_quota = false;
    if (rounds_left() && part_faces(invalid, loose)) continue;
    // The exact plan found fewer invalid faces than last time: another pass of rounds from its word.
    const bool progress = invalid.size() < fewest_exact;
    fewest_exact = std::min(fewest_exact, invalid.size());
    if (progress && rounds_left()) continue;
    if (invalid.empty()) break;  // only loose pieces the raster plan cannot tell apart
    if (!setting_.options.cut_out_unsupported) break;
    // Pieces of the back plane or the floor that strips around them parted from it are card, not
    // model: a hole there takes nothing from the likeness, so they go first and free of the quota.
    const auto model_faces = std::ranges::partition(invalid, [&](std::int32_t f) { return card_piece(f); });
    if (model_faces.begin() != invalid.begin()) {
      cut_out({invalid.begin(), model_faces.begin()}, {}, "");
    } else if (rules_.retry_splits && !splits_retried_ && rounds_left()) {
      // Before any of the model is cut out: a few more rounds in which supports may cut faces in
      // two again, so that a face held only by reaching across others (a ring's top) stands.
      splits_retried_ = true;
      split_rounds_left_ = kSplitRetryRounds;
      continue;
    } else if (!cut_out_cheapest(std::move(invalid))) {
      break;
    }
    // The rounds resume with the holes.
    raster_plan_ = merge_coplanar_faces(std::move(raster_plan_));
    raster_plan_ = align_folds_to_lines(std::move(raster_plan_), setting_.maps.grid, tolerance_);
    settle();
  }
  return finish();
}

// The plan kept: drawn in full from the last verdict, with the raster plan it was built of.
SupportedPlan FaceOrderRun::finish() {
  SupportReport& tally = report();
  tally.converged = tally.cut_out == 0 && invalid_faces().empty() && result_.plan.loose_card_pieces == 0;
  if (tally.converged) {
    tally.stop = SupportStop::None;
    tally.stop_faces = tally.stop_loose_pieces = 0;
    tally.stop_at_quota = false;
  }
  raster_plan_.face = std::move(confirmed_.first);
  raster_plan_.faces = std::move(confirmed_.second);
  result_.plan = last_exact_plan_->full();
  tally.narrow = narrow_strips(raster_plan_, setting_.maps.grid);
  result_.raster_plan = std::move(raster_plan_);
  return std::move(result_);
}

namespace {

bool stands(const SupportedPlan& s, bool allow_dangling) { return plan_stands(s.plan, allow_dangling); }

// How far a plan is from standing: its faces no support holds, then the share of the model cut out.
std::pair<int, double> shortfall(const SupportedPlan& s, bool allow_dangling) {
  const Validity& v = s.plan.validity;
  return {v.floating + v.invalid + (allow_dangling ? 0 : v.dangling) + s.plan.loose_card_pieces,
          s.report.cut_out_share};
}

// A plan that stands only by cutting out this share of the model or more is a poor likeness: the
// next face orders get their turn, and the best plan is kept. On the 37 models at seeds 1-4 it
// brought the mean share cut out from 7.3-8.3% to 4.7-5.3%, and the worst from 25% to 15%.
constexpr double kPoorLikenessShare = 0.15;

// What the support loop is asked for, beside the maps and the raster plan.
struct SupportRequest {
  const Sheet& sheet;
  const PlanOptions& plan_options;
  const SupportOptions& options;
};

// The support loop's face orders, one after another, on the raster plan as given.
SupportedPlan supports_in_face_orders(const RasterMaps& maps, RasterPlan raster_plan, const SupportRequest& request) {
  const auto& [sheet, plan_options, options] = request;
  // The greedy choice depends on the order the faces choose in, and one order can paint itself into
  // a corner that another avoids: the next orders of the same random sequence get their turn.
  std::mt19937 random(options.seed);
  const std::int64_t crumb_px = std::int64_t{raster_plan.block_px} * raster_plan.block_px / 8;
  raster_plan = split_into_pieces(std::move(raster_plan), crumb_px);
  const OrderSetting setting{maps, sheet, plan_options, options,
                             std::make_shared<const ExactPlan>(maps, raster_plan, sheet, plan_options)};
  std::optional<SupportedPlan> best;
  for (int order = 1; order <= std::max(1, options.orders); ++order) {
    const bool last = order >= options.orders;
    const OrderRules rules{order >= std::min(options.orders, kSplitRetryFromOrder),
                           {true, order >= std::min(options.orders, kBelowTipsFromOrder),
                            order >= std::min(options.orders, kCornersFromOrder)}};
    SupportedPlan run = FaceOrderRun(setting, last ? std::move(raster_plan) : raster_plan, rules, random).run();
    if (!best || shortfall(run, options.allow_dangling) < shortfall(*best, options.allow_dangling))
      best = std::move(run);
    best->report.orders = order;
    if (stands(*best, options.allow_dangling) && best->report.cut_out_share < kPoorLikenessShare) break;
  }
  return std::move(*best);
}

// Which of the two frames (first_support_frame) the supports are chosen in.
enum class FrameTurn { First, Other };

// The supports chosen in the first frame or the other, mirrored back; none in the other where the
// plan has only one.
std::optional<SupportedPlan> supports_in_frame(RasterMaps& maps, RasterPlan raster_plan, const SupportRequest& request,
                                               FrameTurn turn) {
  const auto& [sheet, plan_options, options] = request;
  const auto lock = exact_run_lock();
  // The loop breaks its ties one way and draws its face orders by id: it runs in a frame a mirrored
  // model shares, on ids a mirror image would have too, so that the mirrored model gets the mirrored
  // supports.
  raster_plan = with_faces_in_scan_order(std::move(raster_plan));
  const SupportFrame first = first_support_frame(raster_plan, maps.grid, sheet);
  if (first == SupportFrame::Only && turn == FrameTurn::Other) return std::nullopt;
  if ((first == SupportFrame::MirrorImage) == (turn == FrameTurn::Other))
    return supports_in_face_orders(maps, std::move(raster_plan), request);
  SupportedPlan mirrored = [&] {
    const MirroredMaps mirror(maps);
    return supports_in_face_orders(maps, with_faces_in_scan_order(mirror_image(std::move(raster_plan))), request);
  }();
  mirrored.report.mirror_image = true;
  SupportedPlan supported = mirror_image(std::move(mirrored), sheet);
  supported.report.narrow = narrow_strips(supported.raster_plan, maps.grid);  // placed as a run here places them
  // The plan is drawn in the user's frame from the raster plan kept, as every plan is: drawn from the
  // other side, its chains are simplified and snapped from the other end and may run a hair apart
  // (seedlike/sphere: 0.08 mm more cut in 6.5 m). Should that plan not stand, the mirrored one does.
  Plan drawn = build_plan(maps, supported.raster_plan, sheet, plan_options);
  if (plan_stands(drawn, options.allow_dangling) || !plan_stands(supported.plan, options.allow_dangling))
    supported.plan = std::move(drawn);
  else
    supported.report.drawn_in_mirror_image = true;
  return supported;
}

}  // namespace

SupportedPlan add_supports(RasterMaps& maps, RasterPlan raster_plan, const Sheet& sheet,
                           const PlanOptions& plan_options, const SupportOptions& options) {
  return std::move(*supports_in_frame(maps, std::move(raster_plan), {sheet, plan_options, options}, FrameTurn::First));
}

std::optional<SupportedPlan> add_supports_in_other_frame(RasterMaps& maps, RasterPlan raster_plan, const Sheet& sheet,
                                                         const PlanOptions& plan_options,
                                                         const SupportOptions& options) {
  return supports_in_frame(maps, std::move(raster_plan), {sheet, plan_options, options}, FrameTurn::Other);
}

}  // namespace origamic
