// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: an OpenMesh importer that keeps what its readers parse as a plain triangle soup.
// Building a halfedge mesh only to flatten it again cost a third of a large model's load, and the
// halfedge mesh splits non-manifold faces off their neighbours' vertices.
#pragma once

#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <array>
#include <cstdint>
#include <vector>

namespace origamic {

class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  std::vector<OpenMesh::Vec3d> points;
  std::vector<OpenMesh::Vec3f> normals;  // per point; zero where the file gave none
  std::vector<std::array<std::uint32_t, 3>> triangles;

  using VertexHandle = OpenMesh::VertexHandle;
  using FaceHandle = OpenMesh::FaceHandle;
  using HalfedgeHandle = OpenMesh::HalfedgeHandle;
  using EdgeHandle = OpenMesh::EdgeHandle;

  VertexHandle add_vertex(const OpenMesh::Vec3f& point) override { return add_vertex(OpenMesh::Vec3d(point)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& point) override {
    points.push_back(point);
    normals.emplace_back(0.f, 0.f, 0.f);
    return VertexHandle(static_cast<int>(points.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
  void set_point(VertexHandle v, const OpenMesh::Vec3f& point) override {
    if (holds(v)) points[static_cast<std::size_t>(v.idx())] = OpenMesh::Vec3d(point);
  }
  void set_normal(VertexHandle v, const OpenMesh::Vec3f& normal) override {
    if (holds(v)) normals[static_cast<std::size_t>(v.idx())] = normal;
  }
  void set_normal(VertexHandle v, const OpenMesh::Vec3d& normal) override { set_normal(v, OpenMesh::Vec3f(normal)); }

  // Like OpenMesh's own importer: a face with a vertex index out of range or a repeated vertex is
  // refused; a polygon becomes a fan of triangles around its first vertex.
  FaceHandle add_face(const VHandles& corners) override {
    if (corners.size() < 3) return FaceHandle();
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (!holds(corners[i])) return FaceHandle();
      for (std::size_t j = i + 1; j < corners.size(); ++j)
        if (corners[i] == corners[j]) return FaceHandle();
    }
    const auto index = [&](std::size_t i) { return static_cast<std::uint32_t>(corners[i].idx()); };
    for (std::size_t i = 2; i < corners.size(); ++i) triangles.push_back({index(0), index(i - 1), index(i)});
    return FaceHandle(static_cast<int>(faces_++));
  }

  void reserve(unsigned int vertices, unsigned int, unsigned int faces) override {
    points.reserve(vertices);
    normals.reserve(vertices);
    triangles.reserve(faces);
  }
  std::size_t n_vertices() const override { return points.size(); }
  std::size_t n_faces() const override { return faces_; }
  std::size_t n_edges() const override { return 0; }

  // Connectivity, colours, texture coordinates and status: not kept.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  bool holds(VertexHandle v) const { return v.idx() >= 0 && static_cast<std::size_t>(v.idx()) < points.size(); }

  std::size_t faces_ = 0;
};

}  // namespace origamic
