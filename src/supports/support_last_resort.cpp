// SPDX-License-Identifier: GPL-3.0-or-later
// The support loop's last resort (face_order_run.hpp): faces no support holds given to their
// neighbours, or cut out of the sheet.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "face_order_run.hpp"
#include "number_text.hpp"

namespace origamic {
namespace {

// Each step of the last resort (cut_out_cheapest) costs a pass of rounds and an exact plan, and the
// crumbs no support holds at a curved model's rim went one or two a step (seedlike/sphere's 7, each
// 0.05-0.7 % of it, took 6 exact plans). Giving the cheapest away together while they make up no more
// than this share of the model: seedlike/sphere 1.70 -> 1.31 s, seedlike/torus 1.25 -> 1.07 s,
// res_dragon_full 3.13 -> 2.51 s, res_armadillo 8.5 -> 3.2 s (medians of 9, 9, 5 and 5 runs,
// alternating); 33 of the 37 plans the same, the mean p95 2.48 W as before. 2 % changed 5 plans;
// all at once took arch_german_semidetached from 4.6 to 24 W: there, the faces given a quarter at a
// time let supports reach the rest.
constexpr double kGiveAwayModelShare = 0.01;

}  // namespace

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
  const std::vector<std::uint8_t> held = held_at_any_cost();
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
      // A spared face has no hole to weigh: any join within the cap is worth it. An infinite error
      // is no join (no neighbour may take the face), never worth it, spared or not: the cap is
      // unbounded by default, inf <= inf passed it, and a spared face of a scrambled knot was
      // given to face -1 (tools/fuzz.py: the run crashed).
      const bool spared = static_cast<std::size_t>(f) < held.size() && held[static_cast<std::size_t>(f)];
      const auto worth = [&](double error) {
        return std::isfinite(error) && (spared || error < picture->hole_error(f)) &&
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

std::vector<std::uint8_t> FaceOrderRun::held_at_any_cost() const {
  std::vector<std::uint8_t> held(raster_plan_.faces.size(), 0);
  if (spared_pixels_.empty()) return held;
  std::vector<std::int64_t> spared(raster_plan_.faces.size(), 0), all(raster_plan_.faces.size(), 0);
  for (const std::int32_t f : raster_plan_.face.values)
    if (f >= 0) ++all[static_cast<std::size_t>(f)];
  for (const std::vector<PixelAt>& pixels : spared_pixels_)
    for (const PixelAt p : pixels)
      if (const std::int32_t f = raster_plan_.face(p.c, p.r); f > kFloorFace) ++spared[static_cast<std::size_t>(f)];
  for (std::size_t f = 0; f < held.size(); ++f) held[f] = spared[f] > 0 && 2 * spared[f] >= all[f];
  return held;
}

void FaceOrderRun::spare(std::int32_t f, double hold_cost, double hole_cost) {
  std::vector<PixelAt> own = pixels_of({f}).front();
  if (own.empty()) return;
  const PixelGrid& grid = setting_.maps.grid;
  CutOutFace entry;
  entry.at = {grid.X(own.front().c), grid.Y(own.front().r)};
  entry.area_mm2 = static_cast<double>(own.size()) / (grid.px_per_mm * grid.px_per_mm);
  entry.hold_cost = hold_cost, entry.hole_cost = hole_cost;
  entry.reason =
      "its hole would take more than " + number_text(100 * setting_.options.holes_model_share) + " % of the model";
  report().spared_faces.push_back(std::move(entry));
  spared_pixels_.push_back(std::move(own));
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
  assert(shares.into.size() == pixels.size());
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    assert(shares.into[k] >= 0);
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

}  // namespace origamic
