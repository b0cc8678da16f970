// SPDX-License-Identifier: GPL-3.0-or-later
// The main job: model file in, plan out, one stage after another (seed Figure 4.1).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "origamic/likeness.hpp"
#include "origamic/mesh_io.hpp"
#include "origamic/oa.hpp"
#include "origamic/placement.hpp"
#include "origamic/plan.hpp"
#include "origamic/plan_analysis.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"
#include "origamic/supports.hpp"

namespace origamic {

struct DesignOptions {
  Sheet sheet;  // the flat card
  LoadOptions load;
  PlacementOptions placement;
  RasterOptions raster;
  SegmentOptions segment;
  SliceOptions slice;
  PlanOptions plan;
  SupportOptions supports;
  // Places narrower than W do not make the plan invalid: they are listed (issue 23: W is the user's
  // promise to their cutter, and a plan that breaks it is no valid plan unless they say so).
  bool allow_narrow = false;
  // Rounds of parting off the tips narrower than W (blunt_narrow_tips), at most, each kept only if
  // the plan stands, has fewer narrow places and shows the model as well; 0 leaves the plan as
  // supported. They stop sooner after a round that gained little (TipRepairOptions::min_round_gain).
  // When it was chosen, the rounds going on regardless, on the 37 models at W = 3 mm: 4,628 places,
  // 4,343 after 2 rounds, 4,278 after 3, 4,244 after 4 (each round cost res_dragon_full about 0.1 s).
  int tip_rounds = 3;
  // Once supports hold every face, faces whose planes show the model far off (a round shaft's
  // slices given one plane) move to the plane that shows it best, where the plan still stands
  // (refit_planes, src/design/plane_refit.hpp), pass after pass, each frame's plan (supports.hpp)
  // before the frames are compared; false leaves the plan as supported.
  bool refit_planes = true;
  // Then, where a strip lies between two folds closer than W, one of the faces beside it moves its
  // plane to W from the other's (spread_fold_pairs, src/design/fold_spacing.hpp), where the plan
  // still stands, shows the model as well and has fewer such strips; false leaves them.
  bool spread_fold_pairs = true;
  // The maps' normals (12 bytes a pixel), which nothing after slicing reads but the pictures of
  // --dump-maps (N.png), are dropped after slicing unless kept: their memory goes to the supports
  // (seedlike/torus peak memory 153 -> 142 MB).
  bool keep_normals = false;
  // Told as each stage begins, in words ("slicing"): a terminal shows the run's progress with it.
  std::function<void(std::string_view stage)> on_stage;
};

struct StageTime {
  std::string stage;
  double ms = 0;
};

struct DesignResult {
  std::filesystem::path model_file;
  std::string format;
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  bool file_normals = false;
  std::size_t faces_dropped = 0;  // faces of the file passed over for a corner repeated
  Placement placement;
  RasterMaps maps;  // without normals unless DesignOptions::keep_normals
  Segmentation segmentation;
  RasterPlan raster_plan;
  Plan plan;  // the final plan: with supports unless they are off
  // Every place the final plan is narrower than W, along X or Y, measured exactly on its lines as
  // `origamic validate --min-strip W` measures them (PlanProblemKind::NarrowStrip).
  std::vector<PlanProblem> narrow_strips;
  int tips_parted = 0;  // tips narrower than W parted off the supported plan (DesignOptions::tip_rounds)
  SupportReport supports;
  // The likeness of the card to the model (likeness.hpp): of the sliced raster plan, before any
  // support, and of the finished plan, its regions as drawn, after supports and cut-outs.
  Likeness sliced_likeness;
  Likeness likeness;
  CardView card;                // the finished plan as the 45-degree view sees it
  bool allow_dangling = false;  // dangling faces do not make the plan invalid
  bool allow_narrow = false;    // places narrower than W do not make the plan invalid
  std::vector<StageTime> times;
};

/// The design's verdict: its plan stands (plan_stands: every face held, no loose piece of card) and,
/// unless allow_narrow, has no place narrower than W (narrow_strips), as `origamic validate
/// --min-strip W` finds its DXF.
bool design_valid(const DesignResult& result);

/// The options that shaped a design, in one line for the plan files ("card 210x297 mm, W 3 mm, 4
/// px/mm, up y, margin 10 mm, supports seed 1").
std::string settings_text(const DesignOptions& options);

/// Runs the pipeline on a model file, up to the exact plan with its validity verdict. Designs called
/// from several threads take turns: one exact run at a time per process.
/// \throws InputError for a bad file or absurd options.
DesignResult design(const std::filesystem::path& model_file, const DesignOptions& options);

/// The same on a model already read (load_mesh; its file's facts are taken from it, and model_file,
/// which may be empty, only names it in the result and in errors): a caller that needs the mesh
/// again, for a picture of the model, reads the file once. No "load" stage time.
DesignResult design(const LoadedMesh& model, const DesignOptions& options,
                    const std::filesystem::path& model_file = {});

}  // namespace origamic
