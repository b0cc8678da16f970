// SPDX-License-Identifier: GPL-3.0-or-later
#include "fold_gltf.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "origamic/error.hpp"
#include "origamic/version.hpp"

namespace origamic {
namespace {

// glTF colour factors are linear; paper colours are sRGB.
double linear_from_srgb(std::uint8_t value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

template <typename T>
std::size_t append(std::vector<unsigned char>& data, const std::vector<T>& values) {
  const std::size_t offset = data.size();
  data.resize(offset + values.size() * sizeof(T));
  std::memcpy(data.data() + offset, values.data(), values.size() * sizeof(T));
  return offset;
}

int add_view(tinygltf::Model& model, std::size_t offset, std::size_t length, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

tinygltf::Asset asset_of(const FoldedPopup& popup) {
  tinygltf::Asset asset;
  asset.version = "2.0";
  asset.generator = std::string("origamic ") + version;
  tinygltf::Value::Object extras;
  extras["opening_angle_deg"] = tinygltf::Value(popup.options.angle_deg);
  extras["paper_thickness_mm"] = tinygltf::Value(popup.options.thickness_mm);
  extras["sheet_width_mm"] = tinygltf::Value(popup.sheet.width_mm);
  extras["sheet_height_mm"] = tinygltf::Value(popup.sheet.height_mm);
  asset.extras = tinygltf::Value(extras);
  return asset;
}

// The positions in metres, glTF's unit, as accessor 0 with the bounds glTF requires of it.
void add_positions(tinygltf::Model& model, tinygltf::Buffer& buffer, const std::vector<glm::dvec3>& positions_mm) {
  std::vector<float> positions;
  positions.reserve(3 * positions_mm.size());
  std::vector<double> low(3, std::numeric_limits<double>::max()), high(3, std::numeric_limits<double>::lowest());
  for (const glm::dvec3& p : positions_mm)
    for (int k = 0; k < 3; ++k) {
      const float metres = static_cast<float>(p[k] / 1000);
      positions.push_back(metres);
      low[k] = std::min(low[k], double{metres});
      high[k] = std::max(high[k], double{metres});
    }
  const std::size_t offset = append(buffer.data, positions);
  tinygltf::Accessor accessor;
  accessor.bufferView = add_view(model, offset, positions.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.count = positions_mm.size();
  accessor.type = TINYGLTF_TYPE_VEC3;
  accessor.minValues = low;
  accessor.maxValues = high;
  model.accessors.push_back(accessor);
}

struct ColourGroups {
  std::vector<Rgb8> colours;
  std::vector<std::vector<std::uint32_t>> indices;  // per colour: its triangles' vertices
};

// Triangles grouped by colour, in first-use order so the same popup gives the same bytes.
ColourGroups colour_groups(const FoldedPopup& popup) {
  std::map<std::tuple<int, int, int>, std::size_t> colour_group;
  ColourGroups groups;
  for (std::size_t i = 0; i < popup.triangles.size(); ++i) {
    const Rgb8 c = triangle_colour(popup, i, true);
    const auto [it, added] = colour_group.try_emplace({c.r, c.g, c.b}, groups.colours.size());
    if (added) {
      groups.colours.push_back(c);
      groups.indices.emplace_back();
    }
    for (const std::uint32_t v : popup.triangles[i]) groups.indices[it->second].push_back(v);
  }
  return groups;
}

int add_indices(tinygltf::Model& model, tinygltf::Buffer& buffer, const std::vector<std::uint32_t>& indices) {
  const std::size_t offset = append(buffer.data, indices);
  tinygltf::Accessor accessor;
  accessor.bufferView =
      add_view(model, offset, indices.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  accessor.count = indices.size();
  accessor.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

int add_material(tinygltf::Model& model, Rgb8 colour, bool double_sided) {
  tinygltf::Material material;
  material.name = "paper_" + std::to_string(colour.r) + "_" + std::to_string(colour.g) + "_" + std::to_string(colour.b);
  material.pbrMetallicRoughness.baseColorFactor = {linear_from_srgb(colour.r), linear_from_srgb(colour.g),
                                                   linear_from_srgb(colour.b), 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0;
  material.pbrMetallicRoughness.roughnessFactor = 1;
  material.doubleSided = double_sided;
  model.materials.push_back(material);
  return static_cast<int>(model.materials.size() - 1);
}

// One primitive per paper colour, over the positions of accessor 0.
tinygltf::Mesh popup_mesh(tinygltf::Model& model, tinygltf::Buffer& buffer, const FoldedPopup& popup) {
  const ColourGroups groups = colour_groups(popup);
  // A zero-thickness sheet is seen from both sides; a slab is closed and needs no back faces.
  const bool double_sided = popup.options.thickness_mm <= 0;
  tinygltf::Mesh mesh;
  mesh.name = "popup";
  for (std::size_t g = 0; g < groups.colours.size(); ++g) {
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = 0;
    primitive.indices = add_indices(model, buffer, groups.indices[g]);
    primitive.material = add_material(model, groups.colours[g], double_sided);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    mesh.primitives.push_back(primitive);
  }
  return mesh;
}

void add_scene(tinygltf::Model& model, const tinygltf::Mesh& mesh) {
  tinygltf::Node node;
  node.name = "popup";
  if (!mesh.primitives.empty()) {  // glTF has no empty meshes: a popup with no faces is an empty node
    model.meshes.push_back(mesh);
    node.mesh = 0;
  }
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

}  // namespace

std::string gltf_bytes(const FoldedPopup& popup, const std::string& name, bool binary) {
  tinygltf::Model model;
  model.asset = asset_of(popup);
  tinygltf::Buffer buffer;
  if (!popup.positions.empty()) add_positions(model, buffer, popup.positions);
  const tinygltf::Mesh mesh = popup_mesh(model, buffer, popup);
  if (!buffer.data.empty()) model.buffers.push_back(buffer);  // glTF has no empty buffers either
  add_scene(model, mesh);

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, !binary, binary) || out.str().empty())
    throw OutputError(name + ": cannot write glTF");
  return out.str();
}

}  // namespace origamic
