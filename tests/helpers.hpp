// SPDX-License-Identifier: GPL-3.0-or-later
// Meshes made in code, mesh files written by hand (independently of OpenMesh), temporary folders.
#pragma once

#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "exact_plan.hpp"
#include "origamic/mesh_io.hpp"
#include "origamic/oa.hpp"
#include "origamic/plan.hpp"
#include "origamic/plan_regions.hpp"

namespace origamic::test {

/// Whether two grids hold the same bytes (a NaN equal to itself, unlike ==).
template <class T>
bool same_bytes(const Grid<T>& a, const Grid<T>& b) {
  return a.cols == b.cols && a.rows == b.rows && a.values.size() == b.values.size() &&
         std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(T)) == 0;
}

/// An axis-aligned box from lo to hi, 12 triangles wound outwards.
TriangleMesh box(const glm::dvec3& lo, const glm::dvec3& hi);

/// An OBJ text of the box from the origin to `size`, its quads wound outwards (inwards with
/// `inward`). With `corner_normals`, a normal per vertex from the centre through it, as a low-poly
/// model's per-vertex normals are (55 degrees off every face of a cube).
std::string box_obj(const glm::dvec3& size, bool corner_normals, bool inward = false);

/// Both meshes in one (b's vertices after a's).
TriangleMesh merged(const TriangleMesh& a, const TriangleMesh& b);

/// A floor polygon of OA points (x, d), counter-clockwise seen from above.
using Floor = std::vector<std::array<double, 2>>;

/// A prism over a floor polygon from height h0 to h1, wound outwards: OA points (x, h, d) as model
/// points (x, y, z), read with up y at scale 1 and offset 0.
TriangleMesh prism(const Floor& floor, double h0, double h1);

/// A UV sphere of the given segments around and rings from pole to pole.
TriangleMesh sphere(const glm::dvec3& centre, double radius, int segments, int rings);

/// The plan of a box pop-up as regions, derived by hand from its folds: the box spans x0..x1, stands
/// h high and d deep against the back plane. Back plane V(0) (the box cut out of it: 0..h), floor H(0)
/// (cut out: -d..0), the front V(d) on -d..h-d and the top H(h) on h-d..h. Rings counter-clockwise.
std::vector<PlanRegion> box_popup_regions(const Sheet& sheet, double x0, double x1, double h, double d);

/// A box floating in mid-air, its sides off the pixel lattice: front V(47.1) from h 41.3 to 77.9,
/// top H(77.9) from d 18.6 to 47.1. Rastered and sliced at the default options, with its exact plan.
struct FloatingBoxPlan {
  FloatingBoxPlan();
  Sheet sheet;
  RasterMaps maps;
  RasterPlan raster_plan;
  ExactPlan exact_plan;
  std::int32_t front = 2, top = 3;  // the faces' ids
};

/// Maps made by hand on `grid`: every pixel of `kind`, at depth and height 0, facing the viewer (+d),
/// with the picture's break grids traced and empty (NaN).
RasterMaps blank_maps(const PixelGrid& grid, HitKind kind);

/// Twice the signed area of a ring (positive counter-clockwise), by the shoelace formula.
double twice_signed_area(const std::vector<PlanPoint>& ring);

/// A fresh empty folder under the system's temporary folder, removed at destruction.
struct TempDir {
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path path;
  std::filesystem::path operator/(const std::string& name) const { return path / name; }
};

void write_text(const std::filesystem::path& file, const std::string& text);
/// The file's bytes, as they are. \throws std::runtime_error if it cannot be opened.
std::string read_bytes(const std::filesystem::path& file);
void write_obj(const std::filesystem::path& file, const TriangleMesh& mesh);
void write_off(const std::filesystem::path& file, const TriangleMesh& mesh);
void write_ply_ascii(const std::filesystem::path& file, const TriangleMesh& mesh);
void write_ply_binary(const std::filesystem::path& file, const TriangleMesh& mesh);
void write_stl_ascii(const std::filesystem::path& file, const TriangleMesh& mesh);
void write_stl_binary(const std::filesystem::path& file, const TriangleMesh& mesh);
void gzip_file(const std::filesystem::path& from, const std::filesystem::path& to);

/// Runs a shell command; its status (-1 if it did not exit normally) and its standard output.
struct CommandResult {
  int status = -1;
  std::string output;
};
CommandResult shell(const std::string& command);

/// The folder of real models, or "" when it is not beside the project.
std::filesystem::path models_dir();

/// Rows of MANIFEST.tsv: file name and triangle count.
struct ManifestEntry {
  std::string file;
  std::size_t triangles = 0;
  std::string up_axis;
};
std::vector<ManifestEntry> manifest();

/// The origamic executable run with these arguments (a shell command line), its exit status and
/// its output (stdout and stderr together; stderr alone with stdout_only).
struct CommandRun {
  int status = -1;
  std::string output;
};
CommandRun run_origamic(const std::string& arguments, bool stdout_only = false);

/// A path in single quotes for a shell command line.
std::string quoted(const std::filesystem::path& path);

/// The layer names a hand-written DXF puts each kind of line on.
struct DxfLayers {
  std::string cut = "CUT", mountain = "MOUNTAIN", valley = "VALLEY", outline = "OUTLINE", cut_out = "CUTOUT";
};

/// The plan of a box against the back plane drawn by hand on the default sheet (210 x 297 mm): the
/// outline, the main fold beside the box, cuts at X = x0 and x1 from -d to h, and folds across the
/// box: floor to front V(d) on Y = -d (valley), front to top H(h) on h - d (mountain), top to back
/// plane on h (valley).
std::vector<PlanPolyline> box_plan(double d, double h, double x0, double x1);

/// A minimal ASCII DXF written by hand (not by dxflib): a HEADER with $INSUNITS, then one LINE per
/// two-point polyline and one R12 POLYLINE with VERTEXes per longer one (closed flag set when the
/// last point repeats the first), coordinates with 17 significant digits.
std::string dxf_text(const std::vector<PlanPolyline>& lines, int insunits = 4, const DxfLayers& layers = {});

}  // namespace origamic::test
