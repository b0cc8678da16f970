// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "origamic/version.hpp"

namespace origamic {
namespace {

nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json placement_json(const Placement& p, const PlacementOptions& options) {
  nlohmann::json linear = nlohmann::json::array();
  for (int row = 0; row < 3; ++row) linear.push_back({p.linear[0][row], p.linear[1][row], p.linear[2][row]});
  return {
      {"up", options.up == UpAxis::Y ? "y" : "z"},
      {"rotate_deg", options.rotate_deg},
      {"scale_mm_per_unit", p.scale},
      {"auto_scale", !options.scale.has_value()},
      {"auto_offset", !options.offset_mm.has_value()},
      {"margin_mm", options.margin_mm},
      {"transform",
       {{"comment", "oa_xhd_mm = linear * model_xyz + translation"},
        {"linear", linear},
        {"translation_mm", vec(p.translation)}}},
      {"oa_bbox_mm", {{"min_xhd", vec(p.min_oa)}, {"max_xhd", vec(p.max_oa)}}},
      {"plan_bbox_mm", {{"min_XY", {p.min_plan.X, p.min_plan.Y}}, {"max_XY", {p.max_plan.X, p.max_plan.Y}}}},
  };
}

nlohmann::json raster_plan_json(const DesignResult& result, const DesignOptions& options) {
  const RasterPlan& raster_plan = result.raster_plan;
  const double pixel_area_mm2 = 1 / (result.maps.grid.px_per_mm * result.maps.grid.px_per_mm);
  nlohmann::json faces = nlohmann::json::array();
  for (std::size_t i = 0; i < raster_plan.faces.size(); ++i) {
    const RasterFace& f = raster_plan.faces[i];
    const bool v = f.orientation == Orientation::V;
    faces.push_back({{"id", i},
                     {"orientation", v ? "V" : "H"},
                     {v ? "d_mm" : "h_mm", f.depth_mm},
                     {"segment", f.segment},
                     {"area_mm2", static_cast<double>(f.pixels) * pixel_area_mm2}});
  }
  return {
      {"min_strip_mm", options.slice.min_strip_mm},
      {"merge_thin_slices", options.slice.merge_thin_slices},
      {"block_px", raster_plan.block_px},
      {"segments", result.segmentation.count},
      {"subsegments", raster_plan.subsegments},
      {"removed_thin_faces", raster_plan.removed_thin},
      {"widened_thin_parts", raster_plan.widened_thin},
      {"face_count", raster_plan.faces.size()},
      {"faces", faces},
  };
}

nlohmann::json likeness_json(const Likeness& l) {
  return {{"mean_mm", l.mean_mm},
          {"p95_mm", l.p95_mm},
          {"mean_W", l.mean_W},
          {"p95_W", l.p95_W},
          {"coverage", l.coverage},
          {"support_share", l.support_share},
          {"cut_out_share", l.cut_out_share},
          {"model_pixels", l.model_pixels}};
}

// Faces and supports narrower than W, each with a plan point to find it by.
nlohmann::json narrow_json(const std::vector<NarrowStrip>& narrow) {
  nlohmann::json list = nlohmann::json::array();
  for (const NarrowStrip& n : narrow)
    list.push_back({{"face", n.face}, {"support", n.support}, {"width_mm", n.width_mm}, {"at_XY", {n.at.X, n.at.Y}}});
  return list;
}

// The faces cut out of the sheet, each with its place and why.
nlohmann::json cut_out_json(const std::vector<CutOutFace>& faces) {
  nlohmann::json list = nlohmann::json::array();
  for (const CutOutFace& f : faces)
    list.push_back({{"at_XY", {f.at.X, f.at.Y}},
                    {"area_mm2", f.area_mm2},
                    {"hold_cost", f.hold_cost},
                    {"hole_cost", f.hole_cost},
                    {"reason", f.reason}});
  return list;
}

nlohmann::json joined_json(const std::vector<JoinedFace>& faces) {
  nlohmann::json list = nlohmann::json::array();
  for (const JoinedFace& f : faces)
    list.push_back({{"at_XY", {f.at.X, f.at.Y}},
                    {"area_mm2", f.area_mm2},
                    {"joined_cost", f.joined_cost},
                    {"hole_cost", f.hole_cost}});
  return list;
}

nlohmann::json refit_json(const std::vector<RefitPlane>& planes, bool spread = false) {
  nlohmann::json list = nlohmann::json::array();
  for (const RefitPlane& p : planes) {
    list.push_back({{"at_XY", {p.at.X, p.at.Y}},
                    {"orientation", p.orientation == Orientation::V ? "V" : "H"},
                    {"support", p.support},
                    {"from_mm", p.from_mm},
                    {"to_mm", p.to_mm}});
    if (spread) list.back()["closed"] = p.closed;
  }
  return list;
}

// The places the plan is narrower than W, from the exact measure of its lines.
nlohmann::json narrow_places_json(const std::vector<PlanProblem>& narrow) {
  nlohmann::json list = nlohmann::json::array();
  for (const PlanProblem& p : narrow) {
    list.push_back({{"width_mm", p.value_mm},
                    {"from_XY", {p.from.X, p.from.Y}},
                    {"to_XY", {p.to.X, p.to.Y}},
                    {"message", p.message}});
    if (p.folds_apart_mm > 0) list.back()["folds_apart_mm"] = p.folds_apart_mm;
    list.back()["narrow_chords"] = p.narrow_chords;
  }
  return list;
}

// How many of the places narrower than W lie between two parallel folds less than W apart.
std::size_t between_folds(const std::vector<PlanProblem>& narrow) {
  return static_cast<std::size_t>(
      std::ranges::count_if(narrow, [](const PlanProblem& p) { return p.folds_apart_mm > 0; }));
}

// What a cutter draws: the cut lines' segments and vertices, how many segments are under 1 mm (a
// pixel staircase shows as many), and how far the cuts drawn on the model's edges pass from them.
nlohmann::json cuts_json(const Plan& plan) {
  std::size_t segments = 0, vertices = 0, short_segments = 0;
  for (const PlanPolyline& line : plan.lines) {
    if (line.kind != LineKind::Cut && line.kind != LineKind::CutOut) continue;
    vertices += line.points.size();
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      ++segments;
      const PlanPoint &a = line.points[i - 1], &b = line.points[i];
      short_segments += std::hypot(b.X - a.X, b.Y - a.Y) < 1;
    }
  }
  return {{"segments", segments},
          {"vertices", vertices},
          {"segments_under_1_mm", short_segments},
          {"off_model_edges_mm", plan.off_model_edges_mm}};
}

// The narrowest place of the plan under W, or null where it has none.
nlohmann::json narrowest_json(const std::vector<PlanProblem>& narrow) {
  if (narrow.empty()) return nullptr;
  return std::ranges::min(narrow, {}, &PlanProblem::value_mm).value_mm;
}

nlohmann::json plan_json(const DesignResult& result) {
  const Plan& plan = result.plan;
  nlohmann::json faces = nlohmann::json::array();
  for (std::size_t i = 0; i < plan.faces.size(); ++i) {
    const PlanFace& f = plan.faces[i];
    const bool v = f.orientation == Orientation::V;
    faces.push_back({{"id", i},
                     {"orientation", v ? "V" : "H"},
                     {v ? "d_mm" : "h_mm", f.depth_mm},
                     {"area_mm2", f.area_mm2},
                     {"status", to_string(f.status)},
                     {"fold_lines", plan.validity.fold_lines[i]},
                     {"support", f.support},
                     {"at_XY", {f.inside.X, f.inside.Y}}});
  }
  const Validity& v = plan.validity;
  return {{"verdict", design_valid(result) ? "valid" : "invalid"},
          {"stands", plan_stands(plan, result.allow_dangling)},
          {"narrow_strip_count", result.narrow_strips.size()},
          {"narrow_between_folds_count", between_folds(result.narrow_strips)},
          {"allow_narrow", result.allow_narrow},
          {"counts",
           {{"faces", plan.faces.size() - 2},
            {"valid", v.valid},
            {"indirect", v.indirect},
            {"floating", v.floating},
            {"dangling", v.dangling},
            {"invalid", v.invalid},
            {"removed", v.removed},
            {"loose_card_pieces", plan.loose_card_pieces}}},
          {"length_mm", {{"cut", plan.cut_mm}, {"mountain", plan.mountain_mm}, {"valley", plan.valley_mm}}},
          {"cuts", cuts_json(plan)},
          {"exact_checks",
           {{"arrangement_valid", plan.arrangement_valid},
            {"faces_tile_sheet", plan.faces_tile_sheet},
            {"arrangement_faces", plan.arrangement_faces},
            {"label_conflicts", plan.label_conflicts},
            {"folds_snapped", plan.folds_snapped},
            {"trimmed_to_card", plan.trimmed_to_card},
            {"raw_chains", plan.raw_chains},
            {"unsnapped_chains", plan.unsnapped_chains},
            {"unresolved_crossings", plan.unresolved_crossings},
            {"lost_faces", plan.lost_faces},
            {"collapsed_faces", plan.collapsed_faces},
            {"crumbs_cut_out", plan.crumbs_cut_out},
            {"loose_card_pieces", plan.loose_card_pieces},
            {"pieces", plan.pieces}}},
          {"faces", faces}};
}

}  // namespace

std::string report_json(const DesignResult& result, const DesignOptions& options) {
  const RasterMaps& maps = result.maps;
  nlohmann::json times = nlohmann::json::object();
  for (const auto& t : result.times) times[t.stage] = t.ms;
  const nlohmann::json report = {
      {"origamic_version", version},
      {"units", "mm"},
      {"model",
       {{"file", result.model_file.string()},
        {"format", result.format},
        {"triangles", result.triangles},
        {"vertices", result.vertices},
        {"faces_dropped", result.faces_dropped},
        {"normals", result.file_normals ? "file" : "computed"}}},
      {"sheet", {{"width_mm", options.sheet.width_mm}, {"height_mm", options.sheet.height_mm}}},
      {"placement", placement_json(result.placement, options.placement)},
      {"raster",
       {{"px_per_mm", maps.grid.px_per_mm},
        {"cols", maps.grid.cols},
        {"rows", maps.grid.rows},
        {"model_pixels", maps.model_pixels},
        {"front_d_mm", maps.reference.front_d_mm},
        {"top_h_mm", maps.reference.top_h_mm}}},
      {"raster_plan", raster_plan_json(result, options)},
      {"likeness",
       {{"comment", "|card h + d - model h + d| over the model's pixels in the 45-degree view; shares of them"},
        {"finished", likeness_json(result.likeness)},
        {"sliced", likeness_json(result.sliced_likeness)}}},
      {"plan", plan_json(result)},
      {"narrow_strips", narrow_places_json(result.narrow_strips)},
      {"narrowest_strip_mm", narrowest_json(result.narrow_strips)},
      {"narrow_tips_parted", result.tips_parted},
      {"supports",
       {{"added", result.supports.supports},
        {"rounds", result.supports.rounds},
        {"exact_builds", result.supports.exact_builds},
        {"passes_undone", result.supports.passes_undone},
        {"cut_out", result.supports.cut_out},
        {"cut_out_share", result.supports.cut_out_share},
        {"cut_out_faces", cut_out_json(result.supports.cut_out_faces)},
        {"spared_from_cut_out", cut_out_json(result.supports.spared_faces)},
        {"joined_to_neighbour", joined_json(result.supports.joined_faces)},
        {"planes_refit", refit_json(result.supports.planes_refit)},
        {"planes_spread", refit_json(result.supports.planes_spread, true)},
        {"narrow_strips", narrow_json(result.supports.narrow)},
        {"round_bound", result.supports.round_bound},
        {"orders", result.supports.orders},
        {"frames", result.supports.frames},
        {"mirror_image", result.supports.mirror_image},
        {"drawn_in_mirror_image", result.supports.drawn_in_mirror_image},
        {"converged", result.supports.converged},
        {"stop_reason", stop_reason(result.supports)}}},
      {"time_ms", times},
  };
  // File names need not be UTF-8: replace bytes JSON cannot carry rather than fail.
  return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

namespace {

// What the summary says of the places narrower than W, beside their number: how many lie between
// two folds, and that they are allowed, or that --allow-narrow would make a plan that stands valid.
std::string narrow_note(const DesignResult& result) {
  if (result.narrow_strips.empty()) return "";
  const std::size_t folds = between_folds(result.narrow_strips);
  std::string note = folds > 0 ? ", " + std::to_string(folds) + " of them between two folds" : "";
  if (result.allow_narrow) return note + " (allowed)";
  return note + (plan_stands(result.plan, result.allow_dangling) ? " (--allow-narrow accepts them)" : "");
}

}  // namespace

std::string summary_line(const DesignResult& result) {
  double total_ms = 0;
  for (const auto& t : result.times) total_ms += t.ms;
  const Validity& v = result.plan.validity;
  char line[768];
  std::snprintf(line, sizeof line,
                "%s: %zu triangles at %.4g mm/unit; %d segments -> %zu faces (W %.3g mm); likeness error p95 %.2f W, "
                "mean %.2f W (sliced p95 %.2f W), coverage %.1f%%, supports %.1f%%, cut out %.1f%%; %d supports; plan "
                "%s: %d valid, %d indirect, %d floating, %d dangling, %d invalid, %d removed; %zu %s narrower "
                "than W%s; %.0f ms",
                result.model_file.filename().c_str(), result.triangles, result.placement.scale,
                result.segmentation.count, result.raster_plan.faces.size() - 2, result.raster_plan.min_strip_mm,
                result.likeness.p95_W, result.likeness.mean_W, result.sliced_likeness.p95_W,
                100 * result.likeness.coverage, 100 * result.likeness.support_share,
                100 * result.likeness.cut_out_share, result.supports.supports,
                design_valid(result) ? "VALID" : "INVALID", v.valid, v.indirect, v.floating, v.dangling, v.invalid,
                v.removed, result.narrow_strips.size(), result.narrow_strips.size() == 1 ? "place" : "places",
                narrow_note(result).c_str(), total_ms);
  return line;
}

}  // namespace origamic
