// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/supports.hpp"

#include <algorithm>
#include <climits>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <utility>

#include "exact_runs.hpp"
#include "raster_plan_edits.hpp"
#include "support_choice.hpp"
#include "support_mirror.hpp"
#include "support_picture.hpp"

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
// Each step of the last resort (cut_out_cheapest) costs a pass of rounds and an exact plan, and the
// crumbs no support holds at a curved model's rim went one or two a step (seedlike/sphere's 7, each
// 0.05-0.7 % of it, took 6 exact plans). Giving the cheapest away together while they make up no more
// than this share of the model: seedlike/sphere 1.70 -> 1.31 s, seedlike/torus 1.25 -> 1.07 s,
// res_dragon_full 3.13 -> 2.51 s, res_armadillo 8.5 -> 3.2 s (medians of 9, 9, 5 and 5 runs,
// alternating); 33 of the 37 plans the same, the mean p95 2.48 W as before. 2 % changed 5 plans;
// all at once took arch_german_semidetached from 4.6 to 24 W: there, the faces given a quarter at a
// time let supports reach the rest.
constexpr double kGiveAwayModelShare = 0.01;
// The orders from this one on (and the last, should there be fewer) may cut faces in two again.
constexpr int kSplitRetryFromOrder = 3;
// Later orders reach farther (SupportReach), each from its order on (and at the last, should there be
// fewer): the first keeps to the plain rules, which most models stand by, and fast.
constexpr int kBelowTipsFromOrder = 1;
constexpr int kCornersFromOrder = 1;

// What every face order starts from and keeps to.
struct OrderSetting {
  const RasterMaps& maps;
  const Sheet& sheet;
  const PlanOptions& plan_options;
  const SupportOptions& options;
  std::shared_ptr<const ExactPlan> initial;  // the exact plan of the raster plan
};

// What one order may do beyond the plain rules.
struct OrderRules {
  // Before any of the model is cut out, a few more rounds in which supports may cut faces in two.
  bool retry_splits = false;
  SupportReach reach;
};

// One greedy run of the support loop in the face order that `random` draws: passes of rounds on
// the raster graph, each ending in a verdict of the exact plan, which always has the last word.
class FaceOrderRun {
 public:
  FaceOrderRun(const OrderSetting& setting, RasterPlan raster_plan, OrderRules rules, std::mt19937& random)
      : setting_(setting),
        raster_plan_(std::move(raster_plan)),
        rules_(rules),
        random_(random),
        tolerance_(fold_snap_tolerance_mm(setting.plan_options, raster_plan_, setting_.maps.grid)),
        // A part of a face under W x W / 8 (a crumb left where a support or a slanted cut met it)
        // joins a neighbour rather than become a face to be supported.
        crumb_px_(std::int64_t{raster_plan_.block_px} * raster_plan_.block_px / 8) {
    report().round_bound = raster_plan_.face.cols / std::max(1, raster_plan_.block_px) + 1;
    for (std::size_t f = 2; f < raster_plan_.faces.size(); ++f) model_pixels_ += raster_plan_.faces[f].pixels;
  }

  SupportedPlan run();

 private:
  SupportReport& report() { return result_.report; }
  std::vector<std::int32_t> invalid_faces() const { return unsupported(verdicts_, setting_.options.allow_dangling); }
  bool rounds_left() const { return result_.report.rounds < result_.report.round_bound; }

  // The verdict of the raster graph.
  void settle() {
    verdicts_ = raster_verdicts(setting_.maps.grid, raster_plan_, aligned_fold_tolerance_mm(setting_.maps.grid));
    exact_ = false;
  }
  void adopt(std::shared_ptr<const ExactPlan> exact_plan) {
    last_exact_plan_ = std::move(exact_plan);
    result_.plan = last_exact_plan_->verdict();
    confirmed_ = {raster_plan_.face, raster_plan_.faces};
    ++report().exact_builds;
    verdicts_ = verdicts_of(result_.plan);
    exact_ = true;
    painted_since_.clear();
  }
  // The verdict of the exact plan of the raster plan as it is.
  void confirm() {
    last_exact_plan_.reset();  // one arrangement at a time in memory
    adopt(std::make_shared<const ExactPlan>(setting_.maps, raster_plan_, setting_.sheet, setting_.plan_options));
  }
  // Why rounds stopped, and how many faces were invalid then (SupportStop::None: none was).
  struct Stopped {
    SupportStop why = SupportStop::None;
    int faces = 0;
  };
  Stopped support_rounds();
  Stopped pass();
  bool part_faces(const std::vector<std::int32_t>& invalid, int loose);
  bool cut_out_cheapest(std::vector<std::int32_t> invalid);
  // Cuts the faces out, each with why, counting their pixels against the model's (pieces of the
  // back plane or the floor aside: card, not model).
  void cut_out(const std::vector<std::int32_t>& faces, const std::vector<std::pair<double, double>>& costs,
               const std::string& reason);
  // What becomes of a face that has taken pixels of one given away before it in the same call: it
  // is judged as it is now, with them (the last resort), or kept for the next round to judge anew.
  enum class Grown { JudgedAsItIs, KeptForNextRound };
  // Gives each face (but pieces of card) to its neighbours where that shows the model better than
  // its hole would; returns the indices of those it did not give away.
  // `picture`, where given, is the plan's as it is.
  std::vector<std::size_t> give_away(const std::vector<std::int32_t>& faces, Grown grown,
                                     std::optional<SupportPicture> picture = std::nullopt);
  void share(std::int32_t f, const SupportPicture::Shares& shares, std::span<const PixelAt> pixels,
             SupportPicture& picture);
  std::vector<std::vector<PixelAt>> pixels_of(const std::vector<std::int32_t>& faces) const;
  bool card_piece(std::int32_t f) const {  // a piece of the back plane or the floor
    return f > kFloorFace && raster_plan_.faces[static_cast<std::size_t>(f)].depth_mm == 0;
  }
  // A face held for less than its hole was costly only beside the join it could have had: one
  // into a face that then went itself (arch_church at W = 2: two roof faces each joining the
  // other, 15.7% of the model cut out). It is not cut out; the next round sees it anew. Nor is a
  // face that took pixels of another one given away here: its costs were found without them. A
  // piece of card, which no one takes, is. Nor is such a face given away after them: it is not the
  // face that was judged. Given on, the strips a side-facing slope slices into went one into the
  // next, all into one plane (arch_german_semidetached's rear gables: p95 3.74 W); judged anew the
  // next round, 1.73 W. Over the 37 models the mean p95 went 2.19 -> 2.03 W at W = 3 mm (res_knot
  // 5.09 -> 3.23 W), 2.62 -> 2.25 W at 2 mm, 2.10 -> 1.99 W at 5 mm; places narrower than W 4,214 ->
  // 4,303, 7,260 -> 7,633 and 2,218 -> 2,292. Such a face stays no neighbour for those after it in
  // the batch, as a face kept always was: as one, 2.07 W (res_knot 2.54 W, but res_teapot 5.01 W
  // with 1.3% of it cut out).
  void cut_out_costly(const std::vector<SupportChoice::CostlyFace>& costly) {
    std::vector<std::int32_t> faces;
    std::vector<std::int64_t> pixels_before;
    for (const SupportChoice::CostlyFace& c : costly)
      faces.push_back(c.face), pixels_before.push_back(raster_plan_.faces[static_cast<std::size_t>(c.face)].pixels);
    std::vector<std::int32_t> kept;
    std::vector<std::pair<double, double>> costs;
    for (const std::size_t i : give_away(faces, Grown::KeptForNextRound)) {
      const bool grew = raster_plan_.faces[static_cast<std::size_t>(faces[i])].pixels > pixels_before[i];
      if (card_piece(faces[i]) || (!grew && costly[i].hold > costly[i].hole))
        kept.push_back(faces[i]), costs.emplace_back(costly[i].hold, costly[i].hole);
    }
    cut_out(kept, costs, "holding it would cost the picture more than its hole");
  }
  SupportedPlan finish();

  const OrderSetting& setting_;
  RasterPlan raster_plan_;
  OrderRules rules_;
  std::mt19937& random_;
  double tolerance_;
  std::int64_t crumb_px_;
  SupportedPlan result_;
  bool exact_ = false;  // whether verdicts_ is the exact plan's word on raster_plan_
  bool allow_splits_ = true;
  bool splits_retried_ = false;
  int split_rounds_left_ = 0;
  FaceVerdicts verdicts_;
  // The face map and faces the last exact verdict was built of: an undone pass goes back to them,
  // and so does the end (the plan kept is drawn in full from that verdict; a crumb joined to a
  // neighbour after it would make them disagree).
  std::pair<Grid<std::int32_t>, std::vector<RasterFace>> confirmed_;
  // The supports painted since the last verdict: rounds find what their supports reach on its exact
  // plan and on these (and on what else changed since, which the raster shows).
  std::vector<Candidate> painted_since_;
  // The exact plan of the last verdict, kept: the plan kept is drawn in full from it. (Freed here,
  // not on another thread: CGAL is built without thread support, its reference counts not atomic.)
  std::shared_ptr<const ExactPlan> last_exact_plan_;
  std::int64_t model_pixels_ = 0, cut_out_pixels_ = 0;
};

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
                        setting_.options, round_reach);
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
  const std::int64_t cut_out_pixels_before = cut_out_pixels_;
  const Stopped why = support_rounds();
  if (from_exact && why.why != SupportStop::None && invalid_faces().size() > invalid_before) {
    raster_plan_.face = confirmed_.first;
    raster_plan_.faces = confirmed_.second;
    report().supports = supports_before;  // the rounds still count against the bound
    report().cut_out = cut_out_before;
    report().cut_out_faces.resize(cut_out_faces_before);
    report().joined_faces.resize(joined_faces_before);
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

// The last resort: of the faces no support holds, the quarter whose holes cost the picture least
// (one at least) are given to a neighbour (give_away) or else cut out of the sheet (holes, reported
// as "removed"). That can open the way for supports to the others. A card missing more than a
// quarter of its model is no likeness: then nothing is cut, and false returned unless a face was
// given away. (Cutting the smaller half by area at once, as before, took out
// 17 % of arch_stepped_tower where a face at a time takes out 3 %.) The next cheapest beyond the
// quarter are given away with it (never cut out) while all those taken stay under
// kGiveAwayModelShare of the model.
bool FaceOrderRun::cut_out_cheapest(std::vector<std::int32_t> invalid) {
  SupportPicture picture(setting_.maps, raster_plan_);
  std::ranges::sort(invalid, [&](std::int32_t a, std::int32_t b) {
    return std::pair{picture.hole_error(a), a} < std::pair{picture.hole_error(b), b};
  });
  const std::size_t quarter = std::max<std::size_t>(1, invalid.size() / 4);
  const auto pixels = [&](std::int32_t f) { return raster_plan_.faces[static_cast<std::size_t>(f)].pixels; };
  std::int64_t taken_pixels = 0;
  for (std::size_t i = 0; i < quarter; ++i) taken_pixels += pixels(invalid[i]);
  const double share_px = kGiveAwayModelShare * static_cast<double>(model_pixels_);
  std::size_t taken = quarter;
  while (taken < invalid.size() && static_cast<double>(taken_pixels + pixels(invalid[taken])) <= share_px)
    taken_pixels += pixels(invalid[taken++]);
  invalid.resize(taken);
  const double W = raster_plan_.min_strip_mm;
  std::vector<double> hole_costs;
  for (const std::int32_t f : invalid) hole_costs.push_back(std::max(0.0, picture.hole_error(f)) / (W * W));
  std::vector<std::size_t> kept = give_away(invalid, Grown::JudgedAsItIs, std::move(picture));
  const bool gave_away = kept.size() < invalid.size();
  std::erase_if(kept, [&](std::size_t i) { return i >= quarter; });  // only the quarter is cut out
  std::int64_t more = 0;
  for (const std::size_t i : kept) more += pixels(invalid[i]);
  if (4 * (cut_out_pixels_ + more) > model_pixels_) {
    report().stop_at_quota = true;
    return gave_away;  // the faces given away are progress
  }
  std::vector<std::int32_t> faces;
  std::vector<std::pair<double, double>> costs;
  for (const std::size_t i : kept) faces.push_back(invalid[i]), costs.emplace_back(-1.0, hole_costs[i]);
  cut_out(faces, costs, "no support holds it");
  return true;
}

// A face no support holds (or none worth its cost) is given to its neighbours, each pixel to the
// one whose plane shows the model there best (SupportPicture::shared_join), when that shows it
// better than a hole, which shows the back plane or the floor and no model at all: the
// neighbours' paper reaches over it, and the plan has one face fewer to hold. Where a pixel is out
// of every share's reach, or the shares cost the hole or more, the face goes whole to the
// neighbour whose plane shows it best (SupportPicture::nearest_join). Either way only while the
// join adds no more than SupportOptions::join_error_cap_W per pixel. Given whole, it took the
// share cut out on the 37 models from 1.7% to 0.1% and the mean p95 error from 5.8 to 3.5 W;
// shared, 2.27 -> 2.19 W at W = 3 mm (arch_pavilion_csg 4.81 -> 3.29 W: its roof's front rings
// each half to the ring above, half to the one below, not all to one; res_knot 5.98 -> 5.09),
// 2.68 -> 2.63 W at W = 2 mm and 2.16 -> 2.10 W at 5 mm. The shares grow greedily and can cost
// more than one neighbour taking the face whole; taking the cheaper of the two gave 2.15 W, but
// 50 more places narrower than W and res_dragon_full's first frame over the 1 W bound (its other
// frame tried too: 3.1 -> 5.2 s, over its 3 s target). A face it keeps is no neighbour for those
// after it.
std::vector<std::size_t> FaceOrderRun::give_away(const std::vector<std::int32_t>& faces, Grown grown,
                                                 std::optional<SupportPicture> picture) {
  std::vector<std::size_t> kept;
  std::vector<std::int32_t> kept_faces;
  const double cap_mm = setting_.options.join_error_cap_W * raster_plan_.min_strip_mm;
  // The picture as the plan is now, each face given to it: it changes the faces around the next.
  std::vector<std::vector<PixelAt>> pixels = pixels_of(faces);
  std::vector<std::size_t> own_pixels;
  for (const std::vector<PixelAt>& p : pixels) own_pixels.push_back(p.size());
  std::vector<std::size_t> place(raster_plan_.faces.size(), faces.size());  // each face's in `faces`
  for (std::size_t i = 0; i < faces.size(); ++i) place[static_cast<std::size_t>(faces[i])] = i;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::int32_t f = faces[i];
    if (!card_piece(f) && !(grown == Grown::KeptForNextRound && pixels[i].size() > own_pixels[i])) {
      if (!picture) picture.emplace(setting_.maps, raster_plan_);
      const auto worth = [&](double error) {
        return error < picture->hole_error(f) &&
               picture->mean_error_mm(error, static_cast<std::int64_t>(pixels[i].size())) <= cap_mm;
      };
      SupportPicture::Shares shares = picture->shared_join(raster_plan_, pixels[i], kept_faces);
      if (!worth(shares.error)) {
        const SupportPicture::Join to = picture->nearest_join(raster_plan_, pixels[i], kept_faces);
        shares = {std::vector<std::int32_t>(pixels[i].size(), to.into), to.error};
      }
      if (worth(shares.error)) {
        share(f, shares, pixels[i], *picture);
        // A face still to come that took some of f takes those pixels with it, in row order.
        std::vector<std::pair<std::size_t, std::size_t>> took;  // such a face, its pixels before
        for (std::size_t k = 0; k < pixels[i].size(); ++k)
          if (const std::size_t j = place[static_cast<std::size_t>(shares.into[k])]; j > i && j < faces.size()) {
            if (std::ranges::find(took, j, &std::pair<std::size_t, std::size_t>::first) == took.end())
              took.emplace_back(j, pixels[j].size());
            pixels[j].push_back(pixels[i][k]);
          }
        for (const auto& [j, before] : took)
          std::ranges::inplace_merge(pixels[j], pixels[j].begin() + static_cast<std::ptrdiff_t>(before),
                                     [](PixelAt a, PixelAt b) {
                                       return std::pair{a.r, a.c} < std::pair{b.r, b.c};
                                     });
        continue;
      }
    }
    kept.push_back(i);
    kept_faces.push_back(f);
  }
  return kept;
}

// The pixels of each of the faces, in row order, in one pass over the plan.
std::vector<std::vector<PixelAt>> FaceOrderRun::pixels_of(const std::vector<std::int32_t>& faces) const {
  std::vector<std::int32_t> slot(raster_plan_.faces.size(), -1);
  for (std::size_t i = 0; i < faces.size(); ++i)
    slot[static_cast<std::size_t>(faces[i])] = static_cast<std::int32_t>(i);
  std::vector<std::vector<PixelAt>> pixels(faces.size());
  const Grid<std::int32_t>& face = raster_plan_.face;
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c)
      if (const std::int32_t f = face(c, r); f >= 0 && slot[static_cast<std::size_t>(f)] >= 0)
        pixels[static_cast<std::size_t>(slot[static_cast<std::size_t>(f)])].push_back({c, r});
  return pixels;
}

void FaceOrderRun::cut_out(const std::vector<std::int32_t>& faces, const std::vector<std::pair<double, double>>& costs,
                           const std::string& reason) {
  if (faces.empty()) return;
  std::vector<std::int32_t> slot(raster_plan_.faces.size(), -1);
  for (std::size_t i = 0; i < faces.size(); ++i)
    slot[static_cast<std::size_t>(faces[i])] = static_cast<std::int32_t>(i);
  std::vector<PlanPoint> at(faces.size());
  std::vector<std::uint8_t> found(faces.size(), 0);
  const PixelGrid& grid = setting_.maps.grid;
  for (int r = 0; r < raster_plan_.face.rows; ++r)
    for (int c = 0; c < raster_plan_.face.cols; ++c)
      if (const std::int32_t f = raster_plan_.face(c, r); f >= 0 && slot[static_cast<std::size_t>(f)] >= 0) {
        const auto i = static_cast<std::size_t>(slot[static_cast<std::size_t>(f)]);
        if (!found[i]) found[i] = 1, at[i] = {grid.X(c), grid.Y(r)};
      }
  const double pixel_mm2 = 1 / (grid.px_per_mm * grid.px_per_mm);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    RasterFace& face = raster_plan_.faces[static_cast<std::size_t>(faces[i])];
    face.hole = true;
    ++report().cut_out;
    const bool card = card_piece(faces[i]);
    if (!card) cut_out_pixels_ += face.pixels;
    CutOutFace entry;
    entry.at = at[i], entry.area_mm2 = static_cast<double>(face.pixels) * pixel_mm2;
    if (i < costs.size()) entry.hold_cost = costs[i].first, entry.hole_cost = costs[i].second;
    entry.reason = card ? "a piece of the back plane or the floor that nothing holds" : reason;
    report().cut_out_faces.push_back(std::move(entry));
  }
  report().cut_out_share =
      static_cast<double>(cut_out_pixels_) / static_cast<double>(std::max<std::int64_t>(1, model_pixels_));
}

// Gives each of face f's pixels (in row order) to the face `shares` names for it, and reports it;
// the picture follows.
void FaceOrderRun::share(std::int32_t f, const SupportPicture::Shares& shares, std::span<const PixelAt> pixels,
                         SupportPicture& picture) {
  const PixelGrid& grid = setting_.maps.grid;
  const double W = raster_plan_.min_strip_mm;
  JoinedFace entry;
  if (!pixels.empty()) entry.at = {grid.X(pixels.front().c), grid.Y(pixels.front().r)};
  RasterFace& joined = raster_plan_.faces[static_cast<std::size_t>(f)];
  entry.area_mm2 = static_cast<double>(joined.pixels) / (grid.px_per_mm * grid.px_per_mm);
  entry.joined_cost = shares.error / (W * W);  // negative where the neighbours show the model better
  entry.hole_cost = picture.hole_error(f) / (W * W);
  std::vector<std::int32_t> receivers;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    raster_plan_.face(pixels[k].c, pixels[k].r) = shares.into[k];
    ++raster_plan_.faces[static_cast<std::size_t>(shares.into[k])].pixels;
    if (std::ranges::find(receivers, shares.into[k]) == receivers.end()) receivers.push_back(shares.into[k]);
  }
  for (const std::int32_t g : receivers) {
    std::vector<PixelAt> part;
    for (std::size_t k = 0; k < pixels.size(); ++k)
      if (shares.into[k] == g) part.push_back(pixels[k]);
    picture.give(f, g, raster_plan_.faces[static_cast<std::size_t>(g)], part);
  }
  joined.pixels = 0;
  report().joined_faces.push_back(entry);
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
std::optional<SupportedPlan> supports_in_frame(const RasterMaps& maps, RasterPlan raster_plan,
                                               const SupportRequest& request, FrameTurn turn) {
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
  SupportedPlan mirrored = supports_in_face_orders(
      mirror_image(maps), with_faces_in_scan_order(mirror_image(std::move(raster_plan))), request);
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

SupportedPlan add_supports(const RasterMaps& maps, RasterPlan raster_plan, const Sheet& sheet,
                           const PlanOptions& plan_options, const SupportOptions& options) {
  return std::move(*supports_in_frame(maps, std::move(raster_plan), {sheet, plan_options, options}, FrameTurn::First));
}

std::optional<SupportedPlan> add_supports_in_other_frame(const RasterMaps& maps, RasterPlan raster_plan,
                                                         const Sheet& sheet, const PlanOptions& plan_options,
                                                         const SupportOptions& options) {
  return supports_in_frame(maps, std::move(raster_plan), {sheet, plan_options, options}, FrameTurn::Other);
}

}  // namespace origamic
