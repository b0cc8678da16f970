// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the OpenMesh mesh a folded pop-up is written as. fold_popup builds one alongside the
// popup, so every triangle it keeps is one the mesh files can hold.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace origamic {

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec3uc;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

}  // namespace origamic
