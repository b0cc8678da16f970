// SPDX-License-Identifier: GPL-3.0-or-later
// `origamic validate` and `origamic fold`: any plan's DXF read back, judged, and folded (commands.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "commands.hpp"
#include "origamic/fold3d.hpp"
#include "origamic/output.hpp"
#include "origamic/plan_analysis.hpp"

namespace origamic::cli {
namespace {

// Folds drawn as perforation cuts are read as the folds they stand for, run on to the cuts.
void add_perforation_layers(CLI::App& command, origamic::LayerNames& layers) {
  command
      .add_option("--perf-mountain-layer", layers.perforated_mountain, "layer of mountain folds drawn as perforations")
      ->capture_default_str();
  command.add_option("--perf-valley-layer", layers.perforated_valley, "layer of valley folds drawn as perforations")
      ->capture_default_str();
}

}  // namespace

void add_validate_options(CLI::App& validate, ValidateArgs& args) {
  validate
      .add_option("PLAN", args.plan,
                  "plan as ASCII DXF: cuts, mountain and valley folds on their layers, in mm, "
                  "Y = 0 the main fold")
      ->required();
  validate
      .add_option("--min-strip", args.min_strip_mm, "W: report faces narrower than this along X or Y, mm (0: no check)")
      ->capture_default_str();
  validate
      .add_option("--tolerance", args.tolerance_mm,
                  "a fold and the line Y = h - d of its faces agree within this, mm (absorbs the rounding of "
                  "coordinates in the file)")
      ->capture_default_str();
  validate.add_flag("--json", args.json, "print the report as JSON instead of text");
  validate.add_option("--cut-layer", args.layers.cut, "layer of the cuts")->capture_default_str();
  validate.add_option("--mountain-layer", args.layers.mountain, "layer of the mountain folds")->capture_default_str();
  validate.add_option("--valley-layer", args.layers.valley, "layer of the valley folds")->capture_default_str();
  validate
      .add_option("--outline-layer", args.layers.outline,
                  "layer of the sheet's edge (without one, the sheet is the bounding box of every line)")
      ->capture_default_str();
  add_perforation_layers(validate, args.layers);
}

int run_validate(const ValidateArgs& args) {
  const origamic::DxfDrawing drawing = origamic::read_dxf_drawing(args.plan, args.layers);
  origamic::AnalysisOptions options;
  options.min_strip_mm = args.min_strip_mm;
  options.tolerance_mm = args.tolerance_mm;
  options.unit = drawing.unit;
  origamic::PlanAnalysis analysis;
  try {
    analysis = origamic::analyze_plan(drawing.lines, options);
  } catch (const InputError& e) {
    throw InputError(cli_message(e, args.plan));  // the file for problems of the plan's lines
  }
  if (args.json) {
    std::fputs(origamic::analysis_json(analysis, args.plan).c_str(), stdout);
  } else {
    std::printf("%s\n", origamic::analysis_summary_line(analysis).c_str());
    if (analysis.main_fold_Y != 0 && !analysis.problems.empty())
      std::printf("note: places are given with Y up from the main fold, which the drawing has at Y = %g\n",
                  analysis.main_fold_Y);
    for (const origamic::PlanProblem& p : analysis.problems)
      std::printf("%s: %s: %s\n", origamic::is_error(p.kind) ? "error" : "warning",
                  std::string(origamic::to_string(p.kind)).c_str(), p.message.c_str());
  }
  return analysis.valid() ? 0 : 3;
}

void add_fold_options(CLI::App& fold, FoldArgs& args) {
  fold.add_option("PLAN", args.plan, "plan as ASCII DXF (cuts, mountain and valley folds on their layers, in mm)")
      ->required();
  fold.add_option("--angle", args.angle_deg, "opening angle in degrees: 0 closed, 90 standing, 180 flat")
      ->capture_default_str();
  fold.add_option("--thickness", args.thickness_mm, "paper thickness in mm (0: zero-thickness sheets)")
      ->capture_default_str();
  fold.add_option("-o,--out", args.out, "the folded pop-up as a mesh: .obj (with its .mtl), .ply, .gltf or .glb")
      ->required();
  fold.add_option("--cut-layer", args.layers.cut, "layer of the cuts")->capture_default_str();
  fold.add_option("--mountain-layer", args.layers.mountain, "layer of the mountain folds")->capture_default_str();
  fold.add_option("--valley-layer", args.layers.valley, "layer of the valley folds")->capture_default_str();
  add_perforation_layers(fold, args.layers);
}

int run_fold(const FoldArgs& args) {
  const std::string extension = std::filesystem::path(args.out).extension().string();
  const std::map<std::string, origamic::MeshFormat> formats = {{".obj", origamic::MeshFormat::Obj},
                                                               {".ply", origamic::MeshFormat::Ply},
                                                               {".gltf", origamic::MeshFormat::Gltf},
                                                               {".glb", origamic::MeshFormat::Glb}};
  const auto format = formats.find(extension);
  if (format == formats.end())
    throw InputError("--out: expected a .obj, .ply, .gltf or .glb file, not '" + args.out + "'");
  const origamic::DxfDrawing drawing = origamic::read_dxf_drawing(args.plan, args.layers);
  origamic::AnalysisOptions options;
  options.unit = drawing.unit;
  origamic::PlanAnalysis analysis;
  try {
    analysis = origamic::analyze_plan(drawing.lines, options);
  } catch (const InputError& e) {
    throw InputError(cli_message(e, args.plan));
  }
  const origamic::PlanBox& box = analysis.sheet;
  const origamic::Sheet sheet{box.max_X - box.min_X, 2 * std::max(box.max_Y, -box.min_Y)};
  const origamic::FoldedPopup popup =
      origamic::fold_popup(analysis.regions, sheet, {.angle_deg = args.angle_deg, .thickness_mm = args.thickness_mm});
  origamic::write_files(origamic::folded_mesh_files(popup, args.out, format->second));
  std::printf("%s\nfolded at %g degrees: %s (%d faces not reached by any fold left out)\n",
              origamic::analysis_summary_line(analysis).c_str(), args.angle_deg, args.out.c_str(),
              popup.unplaced_regions);
  return 0;
}

}  // namespace origamic::cli
