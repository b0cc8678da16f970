// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/mesh_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>

#include "helpers.hpp"
#include "origamic/error.hpp"

namespace origamic {
namespace {

using test::TempDir;

void expect_same_extent(const TriangleMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi, double tol) {
  glm::dvec3 a(1e300), b(-1e300);
  for (const auto& p : mesh.positions) {
    a = glm::min(a, p);
    b = glm::max(b, p);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a[k], lo[k], tol);
    EXPECT_NEAR(b[k], hi[k], tol);
  }
}

TEST(MeshIo, EveryFormatReadsTheSameBox) {
  const glm::dvec3 lo(-1.5, 0.25, 2), hi(3, 4.5, 7.75);
  const TriangleMesh box = test::box(lo, hi);
  const TempDir dir;
  using Writer = std::function<void(const std::filesystem::path&, const TriangleMesh&)>;
  const std::vector<std::pair<std::string, Writer>> files = {
      {"box.obj", test::write_obj},          {"box.off", test::write_off},
      {"box.ply", test::write_ply_ascii},    {"box_binary.ply", test::write_ply_binary},
      {"box.stl", test::write_stl_ascii},    {"box_binary.STL", test::write_stl_binary},
  };
  for (const auto& [name, write] : files) {
    SCOPED_TRACE(name);
    write(dir / name, box);
    const LoadedMesh loaded = load_mesh(dir / name);
    EXPECT_EQ(loaded.mesh.triangles.size(), 12u);
    EXPECT_EQ(loaded.mesh.positions.size(), 8u);  // STL corners are welded back to 8 vertices
    EXPECT_EQ(loaded.mesh.corner_normals.size(), 36u);
    expect_same_extent(loaded.mesh, lo, hi, 0.0);  // all coordinates are exact in float

    test::gzip_file(dir / name, dir / (name + ".gz"));
    const LoadedMesh gzipped = load_mesh(dir / (name + ".gz"));
    EXPECT_TRUE(gzipped.gzipped);
    EXPECT_EQ(gzipped.mesh.positions, loaded.mesh.positions);
    EXPECT_EQ(gzipped.mesh.triangles, loaded.mesh.triangles);
  }
}

TEST(MeshIo, PolygonsAreTriangulatedAndUnusedVerticesDropped) {
  const TempDir dir;
  // A unit square as one quad, plus a stray vertex far away that no face uses.
  test::write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 100 100 100\nf 1 2 3 4\n");
  const LoadedMesh loaded = load_mesh(dir / "quad.obj");
  EXPECT_EQ(loaded.mesh.triangles.size(), 2u);
  EXPECT_EQ(loaded.mesh.positions.size(), 4u);
  expect_same_extent(loaded.mesh, {0, 0, 0}, {1, 1, 0}, 0.0);
}

TEST(MeshIo, ComputedNormalsAreSmoothOnASphereAndSharpOnABox) {
  const TempDir dir;
  test::write_obj(dir / "box.obj", test::box({0, 0, 0}, {1, 1, 1}));
  const LoadedMesh box = load_mesh(dir / "box.obj");
  EXPECT_FALSE(box.file_normals);
  for (std::size_t f = 0; f < box.mesh.triangles.size(); ++f) {
    const auto& t = box.mesh.triangles[f];
    const glm::dvec3 face = glm::normalize(glm::cross(box.mesh.positions[t[1]] - box.mesh.positions[t[0]],
                                                      box.mesh.positions[t[2]] - box.mesh.positions[t[0]]));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::dot(glm::dvec3(box.mesh.corner_normals[3 * f + c]), face), 1.0, 1e-6);
  }
  const glm::dvec3 centre(0.5, -2, 3);
  test::write_obj(dir / "sphere.obj", test::sphere(centre, 2.0, 48, 24));
  const LoadedMesh sphere = load_mesh(dir / "sphere.obj");
  for (std::size_t f = 0; f < sphere.mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 radial = glm::normalize(sphere.mesh.positions[sphere.mesh.triangles[f][c]] - centre);
      // Averaged over the ring of faces: within a few degrees of the true normal, not a face's.
      EXPECT_GT(std::abs(glm::dot(glm::dvec3(sphere.mesh.corner_normals[3 * f + c]), radial)), 0.998);
    }
}

// Three triangles on one edge, like the pages of an open book, are not a manifold. They load as the
// file has them: five vertices, the spine's two shared by every page, none copied apart.
TEST(MeshIo, NonManifoldFacesKeepTheirSharedVertices) {
  const TempDir dir;
  test::write_text(dir / "book.off", "OFF\n5 3 0\n0 0 0\n0 0 1\n1 0 0\n0 1 0\n-1 -1 0\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  const LoadedMesh book = load_mesh(dir / "book.off");
  ASSERT_EQ(book.mesh.triangles.size(), 3u);
  EXPECT_EQ(book.mesh.positions.size(), 5u);
  EXPECT_EQ(book.mesh.positions[0], glm::dvec3(0, 0, 0));
  EXPECT_EQ(book.mesh.positions[1], glm::dvec3(0, 0, 1));
  for (const auto& page : book.mesh.triangles) EXPECT_EQ(page[0] + page[1], 1u);  // each page on the spine
}

TEST(MeshIo, FileNormalsAreUsedWhenPresent) {
  const TempDir dir;
  test::write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 0 2\nvn 0 0 2\nf 1//1 2//2 3//3\n");
  const LoadedMesh loaded = load_mesh(dir / "tri.obj");
  EXPECT_TRUE(loaded.file_normals);
  for (const auto& n : loaded.mesh.corner_normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // normalised
}

TEST(MeshIo, FileNormalsFartherThanTheFeatureAngleFromTheirFaceTakeItsNormal) {
  const TempDir dir;
  for (const bool inward : {false, true}) {
    SCOPED_TRACE(inward ? "wound inwards" : "wound outwards");
    test::write_text(dir / "cube.obj", test::box_obj({1, 1, 1}, true, inward));
    const LoadedMesh loaded = load_mesh(dir / "cube.obj");
    ASSERT_TRUE(loaded.file_normals);
    ASSERT_EQ(loaded.mesh.triangles.size(), 12u);
    for (std::size_t f = 0; f < 12; ++f) {
      // The face's outward normal: the axis its corners share, away from the centre.
      const auto& t = loaded.mesh.triangles[f];
      const glm::dvec3 centre =
          (loaded.mesh.positions[t[0]] + loaded.mesh.positions[t[1]] + loaded.mesh.positions[t[2]]) / 3.0;
      glm::dvec3 outward(0.0);
      for (int axis = 0; axis < 3; ++axis)
        if (std::abs(centre[axis] - 0.5) > 0.49) outward[axis] = centre[axis] > 0.5 ? 1 : -1;
      for (std::size_t c = 0; c < 3; ++c)
        EXPECT_LT(glm::length(glm::dvec3(loaded.mesh.corner_normals[3 * f + c]) - outward), 1e-6) << "triangle " << f;
    }
  }
}

TEST(MeshIo, FileNormalsWithinTheFeatureAngleOfTheirFaceAreKept) {
  const TempDir dir;
  // 30 degrees off the face's normal (0, 0, 1), inside the default feature angle of 40.
  test::write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.5 0 0.8660254\nf 1//1 2//1 3//1\n");
  const LoadedMesh loaded = load_mesh(dir / "tri.obj");
  for (const auto& n : loaded.mesh.corner_normals) EXPECT_LT(glm::length(n - glm::vec3(0.5f, 0, 0.8660254f)), 1e-6f);
}

// Two triangles folded 20 degrees along a seam, once sharing the seam's vertices and once each with
// its own copies at the same points (a mesh cut along its patch seams, as res_teapot's is): the
// computed normals are the same, smooth across the seam.
TEST(MeshIo, ComputedNormalsAreSmoothAcrossASeamOfRepeatedVertices) {
  const TempDir dir;
  const std::string points = "v 0 0 0\nv 0 1 0\nv -1 0.5 0\nv 0.9396926 0.5 0.3420201\n";
  test::write_text(dir / "shared.obj", points + "f 1 2 3\nf 2 1 4\n");
  test::write_text(dir / "seam.obj", points + "v 0 0 0\nv 0 1 0\nf 1 2 3\nf 6 5 4\n");
  const LoadedMesh shared = load_mesh(dir / "shared.obj"), seam = load_mesh(dir / "seam.obj");
  ASSERT_EQ(shared.mesh.corner_normals.size(), 6u);
  ASSERT_EQ(seam.mesh.corner_normals.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_LT(glm::length(seam.mesh.corner_normals[k] - shared.mesh.corner_normals[k]), 1e-6f) << "corner " << k;
  // On the seam the normal lies between the two faces' (0, 0, 1) and (-0.34, 0, 0.94).
  EXPECT_GT(glm::dot(seam.mesh.corner_normals[0], glm::vec3(0, 0, 1)), 0.98f);
  EXPECT_LT(glm::dot(seam.mesh.corner_normals[0], glm::vec3(0, 0, 1)), 0.99999f);
}

// Every bad input gets an InputError whose one-line message names the file and the problem.
void expect_input_error(const std::filesystem::path& file, const std::string& problem) {
  SCOPED_TRACE(file.filename().string());
  try {
    load_mesh(file);
    ADD_FAILURE() << "no error for " << file;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MeshIo, BadInputsAreReportedWithFileAndProblem) {
  const TempDir dir;
  const TriangleMesh box = test::box({0, 0, 0}, {1, 2, 3});
  test::write_stl_binary(dir / "whole.stl", box);
  const std::string stl = test::read_bytes(dir / "whole.stl");
  test::write_text(dir / "cut.stl", stl.substr(0, stl.size() - 20));
  test::write_stl_ascii(dir / "whole_ascii.stl", box);
  const std::string ascii = test::read_bytes(dir / "whole_ascii.stl");
  test::write_text(dir / "cut_ascii.stl", ascii.substr(0, ascii.size() / 2));
  test::write_off(dir / "whole.off", box);
  const std::string off = test::read_bytes(dir / "whole.off");
  test::write_text(dir / "cut.off", off.substr(0, off.size() / 2));
  test::write_ply_ascii(dir / "whole.ply", box);
  const std::string ply = test::read_bytes(dir / "whole.ply");
  test::write_text(dir / "cut.ply", ply.substr(0, ply.size() - 30));
  test::gzip_file(dir / "whole.off", dir / "whole.off.gz");
  const std::string gz = test::read_bytes(dir / "whole.off.gz");
  test::write_text(dir / "cut.off.gz", gz.substr(0, gz.size() / 2));
  test::write_text(dir / "empty.obj", "");
  test::write_text(dir / "garbage.ply", "this is not a mesh\n");
  test::write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  test::write_text(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  test::write_text(dir / "huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n");
  test::write_text(dir / "point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
  // OBJ cut short in its last statement: a vertex with no coordinates, or with one (it was read as
  // the whole file before), and a face with none.
  const std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
  test::write_text(dir / "cut_bare_v.obj", faces + "v ");
  test::write_text(dir / "cut_v.obj", faces + "v");
  test::write_text(dir / "cut_one_coordinate.obj", faces + "v 0.5");
  test::write_text(dir / "cut_f.obj", faces + "f");
  test::write_text(dir / "model.xyz", "1 2 3\n");
  std::filesystem::create_directory(dir / "folder.obj");

  expect_input_error(dir / "missing.obj", "no such file");
  expect_input_error(dir / "folder.obj", "folder");
  expect_input_error(dir / "model.xyz", "unknown mesh format");
  expect_input_error(dir / "empty.obj", "empty file");
  expect_input_error(dir / "cut.stl", "truncated");
  expect_input_error(dir / "cut_ascii.stl", "truncated");
  expect_input_error(dir / "cut.off", "truncated");
  expect_input_error(dir / "cut.ply", "truncated");
  expect_input_error(dir / "cut.off.gz", "truncated or corrupt gzip");
  for (const char* cut : {"cut_bare_v.obj", "cut_v.obj", "cut_one_coordinate.obj"})
    expect_input_error(dir / cut, "truncated or malformed");
  expect_input_error(dir / "cut_f.obj", "a face needs three or more corners");
  expect_input_error(dir / "garbage.ply", "not a PLY file");
  expect_input_error(dir / "points.obj", "no faces");
  expect_input_error(dir / "nan.obj", "not a finite number");
  expect_input_error(dir / "huge.obj", "not a finite number");
  expect_input_error(dir / "point.obj", "zero extent");
}

// Headers OpenMesh trusted: each of these crashed it, looped, printed without end or allocated
// without bound (issue 24's fuzzing); now each is one line naming the file and what is wrong.
TEST(MeshIo, MalformedHeadersAreRefusedBeforeTheReaderSeesThem) {
  const TempDir dir;
  test::write_text(dir / "property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
  test::write_text(dir / "no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  test::write_text(dir / "odd_type.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty fancy w\nend_header\n"
                   "0 0\n1 0\n0 1\n");
  test::write_text(dir / "huge_count.ply",
                   "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n0123456789ab");
  test::write_text(dir / "o.off", "O");
  test::write_text(dir / "negative.off", "OFF\n-1 2 0\n");
  test::write_text(dir / "huge.off", "OFF\n100000000000000000000 1 0\n0 0 0\n");
  // Found by tools/fuzz.py's hour in a mutated res_armadillo.off ("3 22407 18977 373" lost a blank):
  // OpenMesh read 3,022,407 corners past the file's end for over a minute.
  test::write_text(dir / "huge_face.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3022407 1 3\n");
  test::write_text(dir / "word_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\nthree 0 1 2\n");
  test::write_text(dir / "out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\nf 1 2 3\n");
  test::write_text(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  // Found by tools/fuzz.py in a mutated arch_church.obj: OpenMesh's reader aborted on the corner.
  test::write_text(dir / "four_parts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1 2/2/2/8 3/3/3\n");
  test::write_text(dir / "two_corners.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n");
  test::write_text(dir / "nan.stl",
                   "solid x\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                   "endloop\nendfacet\nendsolid x\n");
  TriangleMesh box = test::box({0, 0, 0}, {1, 2, 3});
  box.positions[0].x = std::numeric_limits<double>::infinity();
  test::write_stl_binary(dir / "inf.stl", box);

  expect_input_error(dir / "property_first.ply", "a property before any element");
  expect_input_error(dir / "no_end.ply", "no end_header");
  expect_input_error(dir / "odd_type.ply", "unsupported property type 'fancy'");
  expect_input_error(dir / "huge_count.ply", "truncated");
  expect_input_error(dir / "huge_face.off", "line 8: a face of 3022407 corners lists 2 numbers");
  expect_input_error(dir / "word_face.off", "line 6: a face starts with its corner count");
  expect_input_error(dir / "o.off", "not an OFF file");
  expect_input_error(dir / "negative.off", "counts -1 vertices");
  expect_input_error(dir / "huge.off", "no vertex and face counts");
  expect_input_error(dir / "out_of_range.obj", "1 faces name a vertex the file does not have");
  expect_input_error(dir / "flat.obj", "no area");
  expect_input_error(dir / "four_parts.obj", "line 4: a face needs three or more corners");
  expect_input_error(dir / "two_corners.obj", "line 4: a face needs three or more corners");
  expect_input_error(dir / "nan.stl", "line 4: a vertex needs three finite numbers");
  expect_input_error(dir / "inf.stl", "not finite");
}

// A gzip file may hold several members one after another (`cat a.gz b.gz`), read as one stream: its
// footer gives the last member's size alone. Here both unpack to as many bytes (a comment pads the
// shorter), so the first member alone fills the room the footer makes: it is read whole all the
// same, by the stream.
TEST(MeshIo, AGzipFileOfTwoMembersIsReadWhole) {
  const TempDir dir;
  const TriangleMesh box = test::box({0, 0, 0}, {1, 2, 3});
  test::write_obj(dir / "box.obj", box);
  const std::string text = test::read_bytes(dir / "box.obj");
  const std::size_t half = text.find("\nf ") + 1;  // the vertices, then the faces
  std::string vertices = text.substr(0, half), faces = text.substr(half);
  std::string& shorter = vertices.size() < faces.size() ? vertices : faces;
  const std::size_t pad = std::max(vertices.size(), faces.size()) - shorter.size();
  ASSERT_GE(pad, 2u);
  shorter.append(1, '#').append(pad - 2, ' ').append(1, '\n');
  ASSERT_EQ(vertices.size(), faces.size());
  test::write_text(dir / "vertices.txt", vertices);
  test::write_text(dir / "faces.txt", faces);
  test::gzip_file(dir / "vertices.txt", dir / "vertices.gz");
  test::gzip_file(dir / "faces.txt", dir / "faces.gz");
  std::string both;
  for (const char* part : {"vertices.gz", "faces.gz"}) both += test::read_bytes(dir / part);
  test::write_text(dir / "box.obj.gz", both);
  const LoadedMesh plain = load_mesh(dir / "box.obj"), gzipped = load_mesh(dir / "box.obj.gz");
  EXPECT_EQ(gzipped.mesh.triangles.size(), 12u);
  EXPECT_EQ(gzipped.mesh.positions, plain.mesh.positions);
  EXPECT_EQ(gzipped.mesh.triangles, plain.mesh.triangles);
}

// A gzip file whose footer gives another size than its data unpack to is corrupt, whether read at
// once or by the stream.
TEST(MeshIo, AGzipFileWhoseFooterLiesIsRefused) {
  const TempDir dir;
  test::write_obj(dir / "box.obj", test::box({0, 0, 0}, {1, 2, 3}));
  test::gzip_file(dir / "box.obj", dir / "box.obj.gz");
  std::string gz = test::read_bytes(dir / "box.obj.gz");
  gz[gz.size() - 4] = static_cast<char>(gz[gz.size() - 4] ^ 1);  // a size one off from what it holds
  test::write_text(dir / "box.obj.gz", gz);
  expect_input_error(dir / "box.obj.gz", "truncated or corrupt gzip");
}

// A gzip stream is read only up to 256 MiB: a small file that unpacks to more is refused there.
TEST(MeshIo, AGzipStreamUnpackingPast256MiBIsRefused) {
  const TempDir dir;
  {
    std::ofstream out(dir / "bomb.obj", std::ios::binary);
    out << "v 0 0 0\n";
    const std::string spaces(1 << 20, ' ');
    for (int i = 0; i < 257; ++i) out << spaces;
  }
  test::gzip_file(dir / "bomb.obj", dir / "bomb.obj.gz");
  std::filesystem::remove(dir / "bomb.obj");
  EXPECT_LT(std::filesystem::file_size(dir / "bomb.obj.gz"), 2u << 20);
  expect_input_error(dir / "bomb.obj.gz", "unpacks to more than 256 MiB");
}

// A face with a corner repeated has no area: it is passed over, and counted.
TEST(MeshIo, FacesWithARepeatedCornerAreCountedAsDropped) {
  const TempDir dir;
  test::write_text(dir / "repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\nf 1 2 3\nf 3 3 1\n");
  const LoadedMesh loaded = load_mesh(dir / "repeat.obj");
  EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
  EXPECT_EQ(loaded.faces_dropped, 2u);
}

// A material library is never opened: here one that would never end.
TEST(MeshIo, MaterialLibrariesAreNotRead) {
  const TempDir dir;
  test::write_text(dir / "zero.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const LoadedMesh loaded = load_mesh(dir / "zero.obj");
  EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
}

TEST(MeshIo, FormatIsTakenFromTheNameCaseInsensitively) {
  EXPECT_EQ(mesh_format_of("a/b/Model.OBJ"), "obj");
  EXPECT_EQ(mesh_format_of("dragon.ply.gz"), "ply");
  EXPECT_EQ(mesh_format_of("part.STL.GZ"), "stl");
  EXPECT_EQ(mesh_format_of("scene.gltf"), "");
  EXPECT_EQ(mesh_format_of("archive.gz"), "");
}

// Every real model loads whole: all of its triangles, with their many parts, holes, duplicate and
// non-manifold faces (MANIFEST.tsv counts them independently).
TEST(MeshIo, EveryRealModelLoadsAllItsTriangles) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const auto entries = test::manifest();
  ASSERT_GE(entries.size(), 20u);
  for (const auto& entry : entries) {
    SCOPED_TRACE(entry.file);
    const LoadedMesh loaded = load_mesh(test::models_dir() / entry.file);
    EXPECT_EQ(loaded.mesh.triangles.size(), entry.triangles);
    EXPECT_EQ(loaded.mesh.corner_normals.size(), 3 * entry.triangles);
    EXPECT_EQ(loaded.format, mesh_format_of(entry.file));
  }
}

}  // namespace
}  // namespace origamic
