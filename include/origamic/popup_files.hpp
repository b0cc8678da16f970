// SPDX-License-Identifier: GPL-3.0-or-later
// The 3D files of a design: the folded pop-up as a mesh and its pictures (`origamic design
// --fold-model --renders`), rendered into bytes for write_files.
#pragma once

#include <string>
#include <vector>

#include "origamic/design.hpp"
#include "origamic/output.hpp"
#include "origamic/render.hpp"

namespace origamic {

struct PopupFileOptions {
  bool fold_model = false;    // BASE_popup.obj and its materials BASE_popup.mat: the pop-up at 90 degrees
  bool renders = false;       // BASE_popup.png, BASE_model.png and BASE_opening.gif
  double thickness_mm = 0;    // paper thickness of the mesh and the pictures (fold3d.hpp)
  RenderOptions render;       // the stills; the animation's frames are half their size
  // The animation's angles. Not from 0: closed, zero-thickness faces all lie in one plane.
  std::vector<double> opening_deg = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 170, 180};
  int frame_cs = 8;           // each frame of the animation is shown this long (1/100 s) ...
  int hold_cs = 100;          // ... and the first, the standing (90 degrees) and the last this long
};

/// Checks the options before any work: the thickness (as fold_popup) and the pictures' size and
/// view (as frame_view). \throws InputError naming the option.
void check_popup_file_options(const PopupFileOptions& files);

/// The files, named BASE_popup.obj and so on (BASE is a path without extension). The pop-up is the
/// design's final plan's regions folded (fold_popup); the model picture places `model` (the mesh the
/// design was made of, as read) as the design did, and shows it from the same viewpoint as the
/// pop-up picture. The animation opens the card through opening_deg and closes it again.
/// \throws InputError for absurd options (fold_popup, frame_view).
std::vector<OutputFile> popup_files(const DesignResult& result, const DesignOptions& options, const std::string& base,
                                    const PopupFileOptions& files, const TriangleMesh& model);

}  // namespace origamic
