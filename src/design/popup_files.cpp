// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/popup_files.hpp"

#include <algorithm>

namespace origamic {

void check_popup_file_options(const PopupFileOptions& files) {
  fold_popup({}, Sheet{}, {.angle_deg = 90, .thickness_mm = files.thickness_mm});
  frame_view(glm::dvec3(0.0), glm::dvec3(1.0), files.render);
}

std::vector<OutputFile> popup_files(const DesignResult& result, const DesignOptions& options, const std::string& base,
                                    const PopupFileOptions& files, const TriangleMesh& model) {
  std::vector<OutputFile> out;
  if (!files.fold_model && !files.renders) return out;
  const std::vector<PlanRegion>& regions = result.plan.regions;
  const FoldedPopup popup = fold_popup(regions, options.sheet, {.angle_deg = 90, .thickness_mm = files.thickness_mm});
  if (files.fold_model)
    for (auto& file : folded_mesh_files(popup, base + "_popup.obj", MeshFormat::Obj)) out.push_back(std::move(file));
  if (!files.renders) return out;

  // The pop-up and the model from one viewpoint, framing both and the whole card.
  const ColouredMesh popup_picture = popup_scene(popup, true);
  const ColouredMesh model_picture = model_scene(apply(result.placement, model), options.sheet);
  const auto [lo, hi] = bounds_of({&popup_picture, &model_picture});
  const View view = frame_view(lo, hi, files.render);
  out.push_back({base + "_popup.png", image_png(render(popup_picture, view, files.render), base + "_popup.png")});
  out.push_back({base + "_model.png", image_png(render(model_picture, view, files.render), base + "_model.png")});

  if (files.opening_deg.empty()) return out;
  RenderOptions small = files.render;
  small.width_px = std::max(8, small.width_px / 2);
  small.height_px = std::max(8, small.height_px / 2);
  std::vector<Image> frames = opening_frames(regions, options.sheet, files.opening_deg, files.thickness_mm, small);
  std::vector<int> delays;
  for (std::size_t i = 0; i < files.opening_deg.size(); ++i)
    delays.push_back(i == 0 || i + 1 == files.opening_deg.size() || files.opening_deg[i] == 90 ? files.hold_cs
                                                                                                : files.frame_cs);
  // And back again, without repeating the end frames.
  for (std::size_t i = frames.size() - 1; i-- > 1;) {
    frames.push_back(frames[i]);
    delays.push_back(delays[i]);
  }
  out.push_back({base + "_opening.gif", animated_gif(frames, delays, base + "_opening.gif")});
  return out;
}

}  // namespace origamic
