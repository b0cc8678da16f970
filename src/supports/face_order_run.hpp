// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: one greedy run of the support loop in one face order (supports.cpp), and its last
// resort, faces no support holds given away or cut out (support_last_resort.cpp).
#pragma once

#include <cassert>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "exact_plan.hpp"
#include "origamic/plan.hpp"
#include "origamic/supports.hpp"
#include "support_choice.hpp"
#include "support_picture.hpp"

namespace origamic {

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
    assert(last_exact_plan_);  // run() adopts the initial plan first
    const ChainFallbacks known = last_exact_plan_->verdict().fallbacks;
    last_exact_plan_.reset();  // one arrangement at a time in memory
    adopt(std::make_shared<const ExactPlan>(setting_.maps, raster_plan_, setting_.sheet, setting_.plan_options, known));
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
    const auto holes_may_take =
        static_cast<std::int64_t>(setting_.options.holes_model_share * static_cast<double>(model_pixels_));
    std::int64_t cut = cut_out_pixels_;
    const std::vector<std::uint8_t> held = held_at_any_cost();  // spared before: neither cut nor spared again
    for (const std::size_t i : give_away(faces, Grown::KeptForNextRound)) {
      const RasterFace& face = raster_plan_.faces[static_cast<std::size_t>(faces[i])];
      const bool grew = face.pixels > pixels_before[i];
      if (card_piece(faces[i])) {
        kept.push_back(faces[i]), costs.emplace_back(costly[i].hold, costly[i].hole);
      } else if (!grew && costly[i].hold > costly[i].hole && !held[static_cast<std::size_t>(faces[i])]) {
        if (cut + face.pixels > holes_may_take) {
          spare(faces[i], costly[i].hold, costly[i].hole);
          continue;
        }
        cut += face.pixels;
        kept.push_back(faces[i]), costs.emplace_back(costly[i].hold, costly[i].hole);
      }
    }
    cut_out(kept, costs, "holding it would cost the picture more than its hole");
  }
  SupportedPlan finish();
  // Face f is not cut out: its hole would take more than SupportOptions::holes_model_share of the
  // model. The next rounds hold it whatever that costs (or give it to a neighbour); the report says
  // so.
  void spare(std::int32_t f, double hold_cost, double hole_cost);
  // The faces the holes may not take, by id as the raster plan numbers them now: those at least
  // half of whose pixels were a spared face's (a spared face in pieces, each piece; a support across
  // one holds it already).
  std::vector<std::uint8_t> held_at_any_cost() const;

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
  // The pixels of each face spared (spare), as report().spared_faces lists them.
  std::vector<std::vector<PixelAt>> spared_pixels_;
};

}  // namespace origamic
