// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the origamic command's subcommands, each its options (add_*) and its run (run_*), for
// main.cpp, which parses the command line and reports errors. No algorithm lives here.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "origamic/design.hpp"
#include "origamic/error.hpp"
#include "origamic/fold_style.hpp"
#include "origamic/plan_analysis.hpp"
#include "origamic/plan_dxf_reader.hpp"

namespace origamic::cli {

// `origamic design MODEL`.
struct DesignArgs {
  std::string model;
  std::string card = "210x297";
  std::string up = "y";
  double rotate_deg = origamic::PlacementOptions{}.rotate_deg;
  std::optional<double> scale;
  std::string offset;
  double margin_mm = origamic::PlacementOptions{}.margin_mm;
  double px_per_mm = origamic::RasterOptions{}.px_per_mm;
  double min_strip_mm = origamic::SliceOptions{}.min_strip_mm;
  std::string out_dir;
  std::string maps_dir;
  bool strict = false;
  bool no_supports = false;
  bool allow_dangling = false;
  bool allow_narrow = false;
  bool merge_thin_slices = false;
  std::uint32_t seed = origamic::SupportOptions{}.seed;
  int orders = origamic::SupportOptions{}.orders;
  std::string colours = "laser";
  std::string dxf = "r12";
};

// Fabrication options of every plan file (issue 6, for makers).
struct FabricationArgs {
  std::string fold_style = "score";
  std::string perf = "1,1";
  double fold_inset_mm = origamic::FoldStyleOptions{}.inset_mm;
  std::string paper = "sheet";
};

// The 3D pop-up and its pictures (origamic/popup_files.hpp), written into --out.
struct PopupArgs {
  bool fold_model = false;
  bool renders = false;
  std::string render_size = "1200x900";
  double thickness_mm = 0;
};

void add_design_options(CLI::App& design, DesignArgs& args);
void add_fabrication_options(CLI::App& design, FabricationArgs& args);
void add_popup_options(CLI::App& design, PopupArgs& args);
int run_design(const DesignArgs& args, const FabricationArgs& fabrication, const PopupArgs& popup_args);

// `origamic validate PLAN.dxf`.
struct ValidateArgs {
  std::string plan;
  double min_strip_mm = origamic::AnalysisOptions{}.min_strip_mm;
  double tolerance_mm = origamic::AnalysisOptions{}.tolerance_mm;
  bool json = false;
  origamic::LayerNames layers;
};

void add_validate_options(CLI::App& validate, ValidateArgs& args);
int run_validate(const ValidateArgs& args);

// `origamic fold PLAN.dxf`: any plan, read and placed as `validate` does, folded at an angle.
struct FoldArgs {
  std::string plan;
  double angle_deg = 90;
  double thickness_mm = 0;
  std::string out;
  origamic::LayerNames layers;
};

void add_fold_options(CLI::App& fold, FoldArgs& args);
int run_fold(const FoldArgs& args);

// An error as one line of plain text (main.cpp).
std::string one_line(std::string_view message);

// An InputError as the command line says it: the flag for the library's field, the plan's file for
// its lines (main.cpp).
std::string cli_message(const InputError& e, const std::string& plan_file = {});

}  // namespace origamic::cli
