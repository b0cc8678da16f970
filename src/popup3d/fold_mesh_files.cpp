// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files of a folded pop-up: OBJ and PLY through OpenMesh's IO, glTF and GLB through tinygltf.
#include "origamic/fold3d.hpp"

// OpenMesh's VectorT leaves its elements uninitialized by default, which GCC 12 reports wherever a
// point or colour property grows (OpenMesh/Core/Utils/Property.hh, push_back of T()); the values are set.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <stdlib.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "fold_gltf.hpp"
#include "om_mesh.hpp"
#include "origamic/error.hpp"
#include "quiet_openmesh.hpp"

namespace origamic {

std::vector<OutputFile> folded_mesh_files(const FoldedPopup& popup, const std::filesystem::path& path,
                                          MeshFormat format) {
  if (format == MeshFormat::Gltf || format == MeshFormat::Glb)
    return {{path, gltf_bytes(popup, path.string(), format == MeshFormat::Glb)}};
  const QuietOpenMesh quiet;
  OmMesh mesh;
  mesh.request_face_colors();
  for (const glm::dvec3& p : popup.positions) mesh.add_vertex(OmMesh::Point(p.x, p.y, p.z));
  for (std::size_t i = 0; i < popup.triangles.size(); ++i) {
    const auto& t = popup.triangles[i];
    const OmMesh::FaceHandle f =
        mesh.add_face(mesh.vertex_handle(t[0]), mesh.vertex_handle(t[1]), mesh.vertex_handle(t[2]));
    if (!f.is_valid()) throw std::logic_error("folded_mesh_files: a triangle fold_popup added is refused");
    const Rgb8 c = triangle_colour(popup, i, true);
    mesh.set_color(f, {c.r, c.g, c.b});
  }
  OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceColor;
  constexpr std::streamsize precision = 9;  // as many digits as a float holds
  if (format == MeshFormat::Ply) {
    options += OpenMesh::IO::Options::Binary;
    std::ostringstream out;
    if (!OpenMesh::IO::write_mesh(mesh, out, ".ply", options, precision))
      throw OutputError(path.string() + ": cannot write PLY");
    return {{path, out.str()}};
  }

  // OpenMesh writes an OBJ's materials only beside a file of that name: write both in a private
  // folder, read them back, and leave publishing to write_files.
  const std::filesystem::path mat = std::filesystem::path(path).replace_extension(".mat");
  std::string folder = (std::filesystem::temp_directory_path() / "origamic-mesh-XXXXXX").string();
  if (!mkdtemp(folder.data())) throw OutputError(path.string() + ": cannot make a temporary folder to write OBJ");
  const std::filesystem::path staged = std::filesystem::path(folder) / path.filename();
  const std::filesystem::path staged_mat = std::filesystem::path(folder) / mat.filename();
  const bool written = OpenMesh::IO::write_mesh(mesh, staged.string(), options, precision);
  auto slurp = [](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::vector<OutputFile> files = {{path, slurp(staged)}};
  const bool has_materials = std::filesystem::exists(staged_mat);  // none without a face
  if (has_materials) {
    // OBJ readers look for materials in a .mtl file: OpenMesh's .mat is published under that name.
    const std::filesystem::path mtl = std::filesystem::path(path).replace_extension(".mtl");
    std::string& obj = files[0].bytes;
    const std::string written_line = "mtllib " + mat.filename().string() + "\n";
    const auto at = obj.find(written_line);
    if (at == std::string::npos) throw std::logic_error("folded_mesh_files: OpenMesh's OBJ names no " + mat.string());
    obj.replace(at, written_line.size(), "mtllib " + mtl.filename().string() + "\n");
    files.push_back({mtl, slurp(staged_mat)});
  }
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
  if (!written || files[0].bytes.empty() || (has_materials != !popup.triangles.empty()))
    throw OutputError(path.string() + ": cannot write OBJ");
  return files;
}

}  // namespace origamic
