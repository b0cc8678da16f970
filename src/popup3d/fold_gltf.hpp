// SPDX-License-Identifier: GPL-3.0-or-later
// glTF 2.0 files of a folded pop-up, through tinygltf.
#pragma once

#include <string>

#include "origamic/fold3d.hpp"

namespace origamic {

/// The popup as one glTF 2.0 asset (JSON with its buffer embedded, or binary GLB when `binary`):
/// one mesh, one primitive per paper colour, positions in metres as glTF defines them (y up, as
/// the popup's world frame), no normals (glTF viewers then shade every triangle flat, as paper is).
/// \throws OutputError naming `name` if tinygltf cannot write it.
std::string gltf_bytes(const FoldedPopup& popup, const std::string& name, bool binary);

}  // namespace origamic
