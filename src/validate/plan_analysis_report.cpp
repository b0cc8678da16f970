// SPDX-License-Identifier: GPL-3.0-or-later
// The verdict of a plan's analysis for the terminal and as JSON, and the names of its problem kinds.
#include <map>
#include <nlohmann/json.hpp>

#include "origamic/plan_analysis.hpp"

namespace origamic {
namespace {

nlohmann::json point_json(PlanPoint p) { return nlohmann::json::array({p.X, p.Y}); }

// "3 inconsistent folds", "1 dangling": the counts of the verdict line.
std::string counted(PlanProblemKind kind, int count) {
  const auto noun = [&](const char* one, const char* many) {
    return std::to_string(count) + " " + (count == 1 ? one : many);
  };
  switch (kind) {
    case PlanProblemKind::ConflictingLines:
      return noun("conflicting line", "conflicting lines");
    case PlanProblemKind::SheetNotSplit:
      return noun("sheet not split", "sheets not split");
    case PlanProblemKind::FoldNotHorizontal:
      return noun("slanted fold", "slanted folds");
    case PlanProblemKind::FoldInsideFace:
      return noun("fold inside a face", "folds inside faces");
    case PlanProblemKind::InconsistentFold:
      return noun("inconsistent fold", "inconsistent folds");
    case PlanProblemKind::WrongFoldKind:
      return noun("wrong fold kind", "wrong fold kinds");
    case PlanProblemKind::NarrowStrip:
      return noun("narrow strip", "narrow strips");
    case PlanProblemKind::OutsideCard:
      return noun("face outside the card", "faces outside the card");
    default:
      return std::to_string(count) + " " + std::string(to_string(kind));  // floating, dangling, invalid
  }
}

}  // namespace

std::string_view to_string(PlanProblemKind kind) {
  switch (kind) {
    case PlanProblemKind::ConflictingLines:
      return "conflicting_lines";
    case PlanProblemKind::SheetNotSplit:
      return "sheet_not_split";
    case PlanProblemKind::FoldNotHorizontal:
      return "fold_not_horizontal";
    case PlanProblemKind::FoldInsideFace:
      return "fold_inside_face";
    case PlanProblemKind::InconsistentFold:
      return "inconsistent_fold";
    case PlanProblemKind::WrongFoldKind:
      return "wrong_fold_kind";
    case PlanProblemKind::Floating:
      return "floating";
    case PlanProblemKind::Dangling:
      return "dangling";
    case PlanProblemKind::Invalid:
      return "invalid";
    case PlanProblemKind::NarrowStrip:
      return "narrow_strip";
    case PlanProblemKind::OutsideCard:
      return "outside_card";
    case PlanProblemKind::CutInsideFace:
      return "cut_inside_face";
    case PlanProblemKind::OutsideSheet:
      return "outside_sheet";
  }
  return "?";
}

std::string analysis_summary_line(const PlanAnalysis& analysis) {
  std::string line = std::string("plan ") + (analysis.valid() ? "VALID" : "INVALID") + ": " +
                     std::to_string(analysis.faces) + " faces";
  std::map<PlanProblemKind, int> errors;
  for (const PlanProblem& p : analysis.problems)
    if (is_error(p.kind)) ++errors[p.kind];
  std::string counts;
  for (const auto& [kind, count] : errors) {
    counts += (counts.empty() ? "" : ", ") + counted(kind, count);
    if (kind == PlanProblemKind::NarrowStrip && analysis.narrow_between_folds > 0)
      counts += " (" + std::to_string(analysis.narrow_between_folds) + " between two folds)";
  }
  if (!counts.empty()) line += "; " + counts;
  if (analysis.warnings > 0)
    line += " (" + std::to_string(analysis.warnings) + (analysis.warnings == 1 ? " warning)" : " warnings)");
  return line;
}

std::string analysis_json(const PlanAnalysis& analysis, const std::string& file_name) {
  const Validity& v = analysis.validity;
  nlohmann::json problems = nlohmann::json::array();
  for (const PlanProblem& p : analysis.problems) {
    problems.push_back({{"kind", std::string(to_string(p.kind))},
                        {"severity", is_error(p.kind) ? "error" : "warning"},
                        {"at", point_json(p.at)},
                        {"from", point_json(p.from)},
                        {"to", point_json(p.to)},
                        {"face", p.region},
                        {"value_mm", p.value_mm},
                        {"message", p.message}});
    if (p.folds_apart_mm > 0) problems.back()["folds_apart_mm"] = p.folds_apart_mm;
    if (p.kind == PlanProblemKind::NarrowStrip) problems.back()["narrow_chords"] = p.narrow_chords;
  }
  nlohmann::json faces = nlohmann::json::array();
  for (std::size_t r = 0; r < analysis.regions.size(); ++r) {
    const PlanRegion& region = analysis.regions[r];
    const std::int32_t node = analysis.node[r];
    faces.push_back({{"node", node},
                     {"role", node == 0   ? "back plane"
                              : node == 1 ? "floor"
                                          : "face"},
                     {"placed", region.placed},
                     {"orientation", region.placed ? (region.orientation == Orientation::V ? "V" : "H") : ""},
                     {"depth_mm", region.depth_mm},
                     {"status", std::string(to_string(region.status))},
                     {"inside", point_json(region.inside)},
                     {"area_mm2", analysis.area_mm2[r]},
                     {"holes", region.rings.empty() ? 0 : region.rings.size() - 1}});
  }
  const nlohmann::json report = {
      {"file", file_name},
      {"units", "mm"},
      {"verdict", analysis.valid() ? "valid" : "invalid"},
      {"summary", analysis_summary_line(analysis)},
      {"sheet",
       {{"min_X", analysis.sheet.min_X},
        {"min_Y", analysis.sheet.min_Y},
        {"max_X", analysis.sheet.max_X},
        {"max_Y", analysis.sheet.max_Y}}},
      {"main_fold_Y", analysis.main_fold_Y},
      {"counts",
       {{"faces", analysis.faces},
        {"regions", analysis.regions.size()},
        {"valid", v.valid},
        {"indirect", v.indirect},
        {"floating", v.floating},
        {"dangling", v.dangling},
        {"invalid", v.invalid},
        {"narrow_between_folds", analysis.narrow_between_folds},
        {"errors", analysis.errors},
        {"warnings", analysis.warnings}}},
      {"length_mm", {{"cut", analysis.cut_mm}, {"mountain", analysis.mountain_mm}, {"valley", analysis.valley_mm}}},
      {"arrangement_valid", analysis.arrangement_valid},
      {"problems", problems},
      {"faces", faces}};
  return report.dump(2) + "\n";
}

}  // namespace origamic
