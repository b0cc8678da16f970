// SPDX-License-Identifier: GPL-3.0-or-later
// The real executable, as a user runs it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "helpers.hpp"

namespace origamic {
namespace {

struct CommandRun {
  int status = -1;
  std::string output;  // stdout and stderr
};

CommandRun run(const std::string& arguments) {
  const std::string command = std::string(ORIGAMIC_EXE) + " " + arguments + " 2>&1";
  CommandRun result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// A shell command other than origamic, with its status and output.
CommandRun run_shell(const std::string& command) {
  const test::CommandResult r = test::shell(command + " 2>&1");
  return {r.status, r.output};
}

std::string quoted(const std::filesystem::path& p) {
  std::string text = p.string();
  text.insert(text.begin(), '\'');
  text.push_back('\'');  // one + chain here trips GCC 12's false -Wrestrict
  return text;
}

TEST(Cli, HelpAndVersion) {
  const CommandRun help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("design"), std::string::npos);
  const CommandRun design_help = run("design --help");
  EXPECT_EQ(design_help.status, 0);
  for (const char* option : {"--card", "--up", "--rotate", "--scale", "--offset", "--margin", "--px-per-mm",
                             "--dump-maps", "--out", "--fold-style", "--perf", "--fold-inset", "--paper"})
    EXPECT_NE(design_help.output.find(option), std::string::npos) << option;
  const CommandRun version = run("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output.rfind("origamic ", 0), 0u) << version.output;
  EXPECT_EQ(run("-V").output, version.output);
  const CommandRun help_word = run("help");
  EXPECT_EQ(help_word.status, 0);
  EXPECT_EQ(help_word.output, help.output);
}

// What a user mistyped is named, with the nearest right word and the help that lists it.
TEST(Cli, MistakesAreNamedWithTheNearestRightWord) {
  const std::string house = quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj");
  const struct {
    std::string arguments, message;
  } cases[] = {
      {"desgin " + house,
       "origamic: unknown command 'desgin'; did you mean design? (the commands are design, "
       "validate and fold; see origamic --help)\n"},
      {"design " + house + " --colour craft",
       "origamic: --colour: no such option of origamic design; did you mean --colours? (see origamic design "
       "--help)\n"},
      {"fold plan.dxf --out a.obj --angle abc",
       "origamic: --angle: 'abc' is not a number (see origamic fold --help)\n"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.arguments);
    const CommandRun r = run(c.arguments);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.output, c.message);
  }
}

TEST(Cli, DesignWritesTheReportAndTheMaps) {
  const test::TempDir dir;
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") + " --out " +
                    quoted(dir / "out") + " --dump-maps " + quoted(dir / "maps"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : {"D.png", "F.png", "T.png", "N.png", "kind.png", "S.png", "SS.png", "faces.png",
                           "plan_preview.png", "E.png", "narrow.png"}) {
    std::ifstream png(dir / "maps" / name, std::ios::binary);
    std::array<char, 8> magic{};
    png.read(magic.data(), 8);
    EXPECT_EQ(std::string(magic.data() + 1, 3), "PNG") << name;
  }
  std::ifstream in(dir / "out" / "house.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["units"], "mm");
  EXPECT_EQ(report["sheet"]["width_mm"], 210.0);
  EXPECT_EQ(report["raster"]["cols"], 840);
  EXPECT_GT(report["raster"]["model_pixels"].get<int>(), 10000);
  EXPECT_EQ(report["placement"]["oa_bbox_mm"]["min_xhd"][1], 0.0);  // standing on the floor
  EXPECT_EQ(report["placement"]["oa_bbox_mm"]["min_xhd"][2], 0.0);  // against the back plane
  EXPECT_TRUE(report["time_ms"].contains("raster"));
  EXPECT_TRUE(report["time_ms"].contains("slice"));
  // The house: back, floor and at least its wall and roof slices; every model face at least W wide.
  const auto& plan = report["raster_plan"];
  EXPECT_EQ(plan["min_strip_mm"], 3.0);
  EXPECT_GE(plan["face_count"].get<int>(), 4);
  EXPECT_EQ(plan["faces"].size(), plan["face_count"].get<std::size_t>());
  EXPECT_EQ(plan["faces"][0]["orientation"], "V");
  EXPECT_EQ(plan["faces"][1]["orientation"], "H");
  double area = 0;
  for (const auto& face : plan["faces"]) area += face["area_mm2"].get<double>();
  EXPECT_NEAR(area, 210.0 * 297.0, 1e-6);  // the faces tile the sheet
  EXPECT_LE(report["likeness"]["sliced"]["p95_W"].get<double>(), 2.0);
  // The exact plan: files beside the report, and the verdict with every face's status.
  for (const char* name : {"house.dxf", "house.svg", "house.png", "house.pdf"})
    EXPECT_GT(std::filesystem::file_size(dir / "out" / name), 100u) << name;
  const auto& exact = report["plan"];
  EXPECT_TRUE(exact["exact_checks"]["arrangement_valid"].get<bool>());
  EXPECT_TRUE(exact["exact_checks"]["faces_tile_sheet"].get<bool>());
  EXPECT_EQ(exact["faces"].size(), plan["faces"].size());
  // Every face has one status; loose pieces of the back plane or the floor count as well.
  int statuses = 0;
  for (const char* status : {"valid", "indirect", "floating", "dangling", "invalid", "removed"})
    statuses += exact["counts"][status].get<int>();
  EXPECT_EQ(statuses, exact["counts"]["faces"].get<int>() + exact["counts"]["loose_card_pieces"].get<int>());
  EXPECT_NE(r.output.find("plan "), std::string::npos) << "the one-line verdict";
}

TEST(Cli, AFailingOutputLeavesNoFileBehind) {
  const test::TempDir dir;
  std::filesystem::create_directories(dir / "out" / "house.png");  // a folder where the preview goes
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --out " + quoted(dir / "out") + " --dump-maps " + quoted(dir / "maps"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(std::ranges::count(r.output, '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("house.png"), std::string::npos) << r.output;
  for (const char* name : {"house.json", "house.dxf", "house.svg", "house.pdf"})
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / name)) << name;
  EXPECT_FALSE(std::filesystem::exists(dir / "maps" / "D.png"));
  std::size_t left = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out"))
    left += entry.path().filename() != "house.png";
  EXPECT_EQ(left, 0u) << "temporary files left behind";
}

TEST(Cli, CardOffThePixelLatticeStillGivesAnExactPlan) {
  const test::TempDir dir;
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --card 210.3x297.2 --px-per-mm 3.3 --out " + quoted(dir.path));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir / "house.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_TRUE(report["plan"]["exact_checks"]["faces_tile_sheet"].get<bool>());
  EXPECT_EQ(report["plan"]["exact_checks"]["lost_faces"], 0);
}

TEST(Cli, StrictExitsThreeForAnInvalidPlanAfterWritingIt) {
  const test::TempDir dir;
  test::write_obj(dir / "floating.obj", test::box({0, 1, -1}, {2, 2, 0}));  // Y-up: in mid-air
  const CommandRun r = run("design " + quoted(dir / "floating.obj") +
                           " --scale 30 --offset 60,0,50 --no-supports --strict --out " + quoted(dir / "out"));
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("INVALID"), std::string::npos) << r.output;
  for (const char* name : {"floating.json", "floating.dxf", "floating.svg", "floating.png", "floating.pdf"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / name)) << name;

  // The same box with its supports stands.
  const CommandRun supported = run("design " + quoted(dir / "floating.obj") +
                                   " --scale 30 --offset 60,0,50 --strict --out " + quoted(dir / "supported"));
  EXPECT_EQ(supported.status, 0) << supported.output;
  test::write_obj(dir / "box.obj", test::box({0, 0, -1}, {2, 1, 0}));  // on the floor, against the back
  const CommandRun valid = run("design " + quoted(dir / "box.obj") + " --strict --out " + quoted(dir / "out"));
  EXPECT_EQ(valid.status, 0) << valid.output;
  EXPECT_NE(valid.output.find("VALID"), std::string::npos) << valid.output;
}

// Every bad input: one line naming the file or option and the problem, status 2, no output file.
void expect_rejected(const std::string& arguments, const std::string& names, const std::string& problem) {
  SCOPED_TRACE(arguments);
  const test::TempDir out;
  const CommandRun r =
      run("design " + arguments + " --out " + quoted(out / "report") + " --dump-maps " + quoted(out / "maps"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(std::ranges::count(r.output, '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(problem), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out / "report")) << "partial output";
  EXPECT_FALSE(std::filesystem::exists(out / "maps")) << "partial output";
}

TEST(Cli, BadInputFilesExitWithStatusTwo) {
  const test::TempDir dir;
  test::write_text(dir / "empty.stl", "");
  test::write_text(dir / "garbage.off", "OFF\nnot numbers\n");
  test::write_text(dir / "noface.obj", "v 0 0 0\nv 1 0 0\n");
  test::write_text(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  test::write_text(dir / "point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
  // ASCII STL: a vertex line with a word that is no number, and one with two numbers.
  const auto ascii_stl = [](const std::string& third_vertex) {
    return "solid t\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n\tvertex 1 0 0\r\n  vertex " + third_vertex +
           "\n endloop\nendfacet\nendsolid t\n";
  };
  test::write_text(dir / "nan.stl", ascii_stl("0 nan 0"));
  test::write_text(dir / "short.stl", ascii_stl("0 1"));
  test::write_text(dir / "model.3ds", "x");
  test::write_stl_binary(dir / "whole.stl", test::box({0, 0, 0}, {1, 1, 1}));
  std::filesystem::resize_file(dir / "whole.stl", 300);
  // A binary STL whose header begins with "solid", as some exporters write, cut short.
  test::write_stl_binary(dir / "solid.stl", test::box({0, 0, 0}, {1, 1, 1}));
  {
    std::fstream header(dir / "solid.stl", std::ios::in | std::ios::out | std::ios::binary);
    header.write("solid box", 9);
  }
  std::filesystem::resize_file(dir / "solid.stl", 300);
  test::write_text(dir / "bad.obj.gz", "not gzip data at all, but named .gz");
  expect_rejected(quoted(dir / "missing.obj"), "missing.obj", "no such file");
  expect_rejected(quoted(dir / "empty.stl"), "empty.stl", "empty");
  expect_rejected(quoted(dir / "garbage.off"), "garbage.off", "");
  expect_rejected(quoted(dir / "noface.obj"), "noface.obj", "no faces");
  expect_rejected(quoted(dir / "nan.obj"), "nan.obj", "finite");
  expect_rejected(quoted(dir / "point.obj"), "point.obj", "zero extent");
  expect_rejected(quoted(dir / "nan.stl"), "nan.stl", "line 6: a vertex needs three finite numbers");
  expect_rejected(quoted(dir / "short.stl"), "short.stl", "line 6: a vertex needs three finite numbers");
  expect_rejected(quoted(dir / "model.3ds"), "model.3ds", "unknown mesh format");
  expect_rejected(quoted(dir / "whole.stl"), "whole.stl", "truncated");
  expect_rejected(quoted(dir / "solid.stl"), "solid.stl", "truncated or corrupt binary STL (header says 12 triangles");
  expect_rejected(quoted(dir / "bad.obj.gz"), "bad.obj.gz", "no faces");
}

TEST(Cli, AbsurdOptionsExitWithStatusTwo) {
  const std::string house = quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj");
  expect_rejected(house + " --card 210", "--card", "WIDTHxHEIGHT");
  expect_rejected(house + " --card 0x297", "--card", "positive");
  expect_rejected(house + " --px-per-mm 0", "--px-per-mm", "positive");
  expect_rejected(house + " --px-per-mm 500", "--px-per-mm", "Mpx");
  expect_rejected(house + " --scale -3", "--scale", "positive");
  expect_rejected(house + " --scale 1000", "--scale", "leaves the");
  // A scale past any card: the projection's extent in powers of ten, not 300 digits each.
  expect_rejected(house + " --scale 1e300", "--scale", "(X -3.3e+300 to 3.3e+300, Y -5.8e+300 to 6.2e+300 mm)");
  expect_rejected(house + " --scale 10 --offset 300,0,0", "--scale/--offset", "leaves the");
  expect_rejected(house + " --offset 1,2", "--offset", "X,H,D");
  expect_rejected(house + " --margin 200", "--margin", "no room");
  expect_rejected(house + " --min-strip 0", "--min-strip", "at least one pixel");
  expect_rejected(house + " --min-strip nan", "--min-strip", "");
  expect_rejected(house + " --up x", "--up", "");
  expect_rejected(house + " --rotate abc", "--rotate", "");
  expect_rejected(house + " --bogus", "--bogus", "");
  expect_rejected(house + " --renders --render-size 4x4", "--render-size", "8 to 8192");
  expect_rejected(house + " --fold-model --thickness -1", "--thickness", "between 0 and 10");
  expect_rejected(house + " --card 1e308x1e308", "--card", "longer than 5000 mm");
  expect_rejected(house + " --px-per-mm 1e308", "--px-per-mm", "inf Mpx");
  expect_rejected(house + " --min-strip 1e9", "--min-strip", "a quarter of the card");
  expect_rejected(house + " --rotate 1e308", "--rotate", "from -360 to 360");
  expect_rejected(house + " --scale 1e-308", "house.obj", "leaves no face on the card");
  // A rod 1 mm thick lying on the floor against the back plane: its front and top are thin across
  // their length, which no widening along X mends.
  const test::TempDir dir;
  test::write_obj(dir / "rod.obj", test::box({0, 0, -1}, {60, 1, 0}));
  expect_rejected(quoted(dir / "rod.obj") + " --scale 1", "rod.obj",
                  "is narrower than the strip width W (3 mm) across");
}

// Out of memory is a clean failure: one line, exit 2, nothing written (mimalloc's own operator new
// aborted the process instead).
TEST(Cli, RunningOutOfMemoryExitsTwoWithOneLine) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the Debug build's AddressSanitizer needs more address space than the limit";
#endif
  const test::TempDir dir;
  const test::CommandResult r =
      test::shell("ulimit -v 600000; " + std::string(ORIGAMIC_EXE) + " design " +
                  quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") + " --px-per-mm 30 --out " +
                  quoted(dir / "out") + " 2>&1");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(r.output, "origamic: out of memory\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "house.dxf"));
}

TEST(Cli, FoldModelAndRendersNeedAnOutputFolder) {
  const CommandRun r =
      run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") + " --renders");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--renders: needs --out"), std::string::npos) << r.output;
}

// The width and height a PNG's IHDR or a GIF's logical screen states.
std::pair<int, int> picture_size(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 24> b{};
  in.read(reinterpret_cast<char*>(b.data()), b.size());
  if (std::string(reinterpret_cast<const char*>(b.data()) + 1, 3) == "PNG")
    return {(b[16] << 24) | (b[17] << 16) | (b[18] << 8) | b[19], (b[20] << 24) | (b[21] << 16) | (b[22] << 8) | b[23]};
  if (std::string(reinterpret_cast<const char*>(b.data()), 6) == "GIF89a")
    return {b[6] | (b[7] << 8), b[8] | (b[9] << 8)};
  return {0, 0};
}

TEST(Cli, DesignWritesTheFoldedModelAndItsPictures) {
  const test::TempDir dir;
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --fold-model --renders --render-size 160x120 --out " + quoted(dir.path));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(picture_size(dir / "house_popup.png"), std::pair(160, 120));
  EXPECT_EQ(picture_size(dir / "house_model.png"), std::pair(160, 120));
  EXPECT_EQ(picture_size(dir / "house_opening.gif"), std::pair(80, 60));
  // The OBJ: at least a triangle for each face of the plan, and its materials beside it.
  std::ifstream obj(dir / "house_popup.obj");
  std::size_t faces = 0;
  std::string mtllib;
  for (std::string line; std::getline(obj, line);) {
    faces += line.rfind("f ", 0) == 0;
    if (line.rfind("mtllib ", 0) == 0) mtllib = line.substr(7);
  }
  std::ifstream in(dir / "house.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_GE(faces, report["plan"]["faces"].size());
  EXPECT_EQ(mtllib, "house_popup.mtl");
  EXPECT_TRUE(std::filesystem::exists(dir / "house_popup.mtl"));
}

TEST(Cli, BadFabricationOptionsExitWithStatusTwo) {
  const std::string house = quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj");
  expect_rejected(house + " --fold-style crease", "--fold-style", "crease");
  expect_rejected(house + " --fold-style perforated --perf 1", "--perf", "CUT,GAP");
  expect_rejected(house + " --perf 1,x", "--perf", "CUT,GAP");
  expect_rejected(house + " --perf 0,1", "--perf", "between 0.1 and 50 mm");
  expect_rejected(house + " --perf 1,-2", "--perf", "between 0.1 and 50 mm");
  expect_rejected(house + " --perf 1,inf", "--perf", "");
  expect_rejected(house + " --fold-inset -1", "--fold-inset", "between 0 and 50 mm");
  expect_rejected(house + " --fold-inset nan", "--fold-inset", "");
  expect_rejected(house + " --fold-inset wide", "--fold-inset", "");
  expect_rejected(house + " --paper a3", "--paper", "a3");
  expect_rejected(house + " --paper letter", "--paper", "does not fit");
  expect_rejected(house + " --card 300x200 --paper a4", "--paper", "does not fit");
  for (const char* date : {"yesterday", "-1", "1.5", "1e9", "99999999999999999999", "253402300800"}) {
    ASSERT_EQ(setenv("SOURCE_DATE_EPOCH", date, 1), 0);
    expect_rejected(house, "SOURCE_DATE_EPOCH", date);
  }
  unsetenv("SOURCE_DATE_EPOCH");
}

// SOURCE_DATE_EPOCH dates the PDF (the reproducible-builds convention): two runs, the same bytes.
TEST(Cli, SourceDateEpochDatesThePdfAndTwoRunsGiveTheSameBytes) {
  const test::TempDir dir;
  const std::string house = quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj");
  ASSERT_EQ(setenv("SOURCE_DATE_EPOCH", "1700000000", 1), 0);
  const CommandRun first = run("design " + house + " --out " + quoted(dir / "first"));
  const CommandRun second = run("design " + house + " --out " + quoted(dir / "second"));
  unsetenv("SOURCE_DATE_EPOCH");
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(test::read_bytes(dir / "first" / "house.pdf"), test::read_bytes(dir / "second" / "house.pdf"));
  const CommandRun info = run_shell("TZ=UTC pdfinfo -isodates " + quoted(dir / "first" / "house.pdf"));
  EXPECT_NE(info.output.find("2023-11-14T22:13:20"), std::string::npos) << info.output;
}

TEST(Cli, FabricationOptionsReachTheFiles) {
  const test::TempDir dir;
  const CommandRun r =
      run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
          " --card 180x240 --fold-style perforated --perf 1.5,0.5 --fold-inset 0.7 --paper letter --out " +
          quoted(dir.path));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("house.{dxf,svg,png,pdf}"), std::string::npos) << r.output;
  const CommandRun info = run_shell("pdfinfo " + quoted(dir / "house.pdf"));
  EXPECT_NE(info.output.find("612 x 792 pts (letter)"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("fold style perforated (cut 1.5 mm, gap 0.5 mm, inset 0.7 mm)"), std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find("card 180x240 mm, W 3 mm"), std::string::npos) << info.output;
  const std::string text = test::read_bytes(dir / "house.dxf");
  EXPECT_NE(text.find("PERF_MOUNTAIN"), std::string::npos);
  EXPECT_EQ(text.find("\nMOUNTAIN\n"), std::string::npos) << "no score layer when perforating";
}

// Reads the vertices of an OBJ file.
std::vector<std::array<double, 3>> obj_vertices(const std::filesystem::path& file) {
  std::vector<std::array<double, 3>> vertices;
  std::ifstream in(file);
  std::string tag;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::array<double, 3> v{};
    if (words >> tag && tag == "v" && words >> v[0] >> v[1] >> v[2]) vertices.push_back(v);
  }
  return vertices;
}

TEST(Cli, FoldTurnsAnyPlanIntoItsPopUpFlatAt180AndStandingAt90) {
  const test::TempDir dir;
  test::write_obj(dir / "box.obj", test::box({0, 0, -1}, {2, 1, 0}));
  ASSERT_EQ(run("design " + quoted(dir / "box.obj") + " --out " + quoted(dir / "plan")).status, 0);
  const CommandRun flat =
      run("fold " + quoted(dir / "plan" / "box.dxf") + " --angle 180 -o " + quoted(dir / "flat.obj"));
  ASSERT_EQ(flat.status, 0) << flat.output;
  const auto flat_vertices = obj_vertices(dir / "flat.obj");
  ASSERT_GT(flat_vertices.size(), 8u);
  for (const auto& v : flat_vertices) EXPECT_NEAR(v[1], 0.0, 1e-3) << "at 180 degrees the card lies flat";
  const CommandRun standing = run("fold " + quoted(dir / "plan" / "box.dxf") + " -o " + quoted(dir / "standing.ply"));
  ASSERT_EQ(standing.status, 0) << standing.output;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "standing.ply"));
  const CommandRun up = run("fold " + quoted(dir / "plan" / "box.dxf") + " --angle 90 -o " + quoted(dir / "up.obj"));
  ASSERT_EQ(up.status, 0) << up.output;
  double highest = 0;
  for (const auto& v : obj_vertices(dir / "up.obj")) highest = std::max(highest, v[1]);
  EXPECT_NEAR(highest, 148.5, 1e-3) << "the back half stands up to the sheet's top edge";

  for (const char* name : {"up.gltf", "up.glb"}) {
    const CommandRun gltf = run("fold " + quoted(dir / "plan" / "box.dxf") + " -o " + quoted(dir / name));
    ASSERT_EQ(gltf.status, 0) << gltf.output;
    std::ifstream in(dir / name, std::ios::binary);
    std::string magic(4, '\0');
    in.read(magic.data(), 4);
    EXPECT_EQ(magic == "glTF", std::string(name) == "up.glb") << name << ": binary only as .glb";
  }

  const CommandRun bad = run("fold " + quoted(dir / "plan" / "box.dxf") + " -o " + quoted(dir / "box.stl"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("--out: expected a .obj, .ply, .gltf or .glb file"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "box.stl"));
  const CommandRun angle = run("fold " + quoted(dir / "plan" / "box.dxf") + " --angle 200 -o " + quoted(dir / "a.obj"));
  EXPECT_EQ(angle.status, 2) << angle.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.obj"));
}

// One plan, one pop-up: the design's --fold-model and `fold` of its DXF give the same mesh, faces cut
// out of the sheet left out of both (they were pink panels floating in the design's). The chapel
// has faces cut out.
TEST(Cli, TheDesignsPopUpIsTheFoldOfItsPlan) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const test::TempDir dir;
  const CommandRun designed = run("design " + quoted(test::models_dir() / "seedlike/chapel.stl") +
                                  " --up z --fold-model --out " + quoted(dir.path));
  ASSERT_EQ(designed.status, 0) << designed.output;
  const auto report = nlohmann::json::parse(std::ifstream(dir / "chapel.json"));
  ASSERT_GT(report["plan"]["counts"]["removed"].get<int>(), 0) << "the case needs faces cut out";
  const CommandRun folded = run("fold " + quoted(dir / "chapel.dxf") + " --out " + quoted(dir / "folded.obj"));
  ASSERT_EQ(folded.status, 0) << folded.output;
  const auto faces_of = [](const std::filesystem::path& obj) {
    std::ifstream in(obj);
    int faces = 0;
    for (std::string line; std::getline(in, line);) faces += line.rfind("f ", 0) == 0;
    return faces;
  };
  EXPECT_GT(faces_of(dir / "folded.obj"), 0);
  EXPECT_EQ(faces_of(dir / "chapel_popup.obj"), faces_of(dir / "folded.obj"));
}

TEST(Cli, MergeThinSlicesReachesTheSlicingAndTheReport) {
  const test::TempDir dir;
  test::write_obj(dir / "ball.obj", test::sphere({0, 0, 0}, 1, 96, 48));
  std::array<nlohmann::json, 2> plans;
  for (const bool merge : {false, true}) {
    const CommandRun r = run("design " + quoted(dir / "ball.obj") + " --no-supports --out " +
                             quoted(dir / (merge ? "merged" : "kept")) + (merge ? " --merge-thin-slices" : ""));
    ASSERT_EQ(r.status, 0) << r.output;
    plans[merge] = nlohmann::json::parse(std::ifstream(dir / (merge ? "merged" : "kept") / "ball.json"))["raster_plan"];
  }
  EXPECT_EQ(plans[0]["merge_thin_slices"], false);
  EXPECT_EQ(plans[1]["merge_thin_slices"], true);
  // The crescents where the ball turns sideways join their neighbours.
  EXPECT_LT(plans[1]["subsegments"].get<int>(), plans[0]["subsegments"].get<int>());
}

// The report says which frames the supports were chosen in: the house's cost it under the bounds,
// one frame; the water tower's first choice, refit, costs it over 1 W of p95, so both were tried.
// The chapel's first choice costs 1.98 W as supported, 1.02 W over its slices, under 1 W once its
// planes are refit: one frame.
TEST(Cli, TheReportSaysWhichFramesTheSupportsWereChosenIn) {
  const test::TempDir dir;
  const CommandRun house = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                               " --out " + quoted(dir.path));
  ASSERT_EQ(house.status, 0) << house.output;
  const auto report = nlohmann::json::parse(std::ifstream(dir / "house.json"))["supports"];
  EXPECT_EQ(report["frames"], 1);
  EXPECT_TRUE(report["mirror_image"].is_boolean());
  EXPECT_EQ(report["drawn_in_mirror_image"], false);
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const CommandRun tower =
      run("design " + quoted(test::models_dir() / "arch_water_tower.obj") + " --up y --out " + quoted(dir.path));
  ASSERT_EQ(tower.status, 0) << tower.output;
  EXPECT_GE(nlohmann::json::parse(std::ifstream(dir / "arch_water_tower.json"))["supports"]["frames"], 2);
  const CommandRun chapel =
      run("design " + quoted(test::models_dir() / "seedlike/chapel.stl") + " --up z --out " + quoted(dir.path));
  ASSERT_EQ(chapel.status, 0) << chapel.output;
  const auto chapel_report = nlohmann::json::parse(std::ifstream(dir / "chapel.json"));
  EXPECT_EQ(chapel_report["supports"]["frames"], 1);
  EXPECT_LE(chapel_report["likeness"]["finished"]["p95_W"].get<double>(),
            chapel_report["likeness"]["sliced"]["p95_W"].get<double>() + 1);
}

// A run killed while it wrote left NAME.partPID files: the next run into the folder removes those
// of processes that are gone, and keeps another live run's.
TEST(Cli, TemporaryFilesOfAKilledRunAreRemovedByTheNext) {
  const test::TempDir dir;
  std::filesystem::create_directories(dir / "out");
  const std::filesystem::path stale = dir / "out" / "house.dxf.part999999999", live = dir / "out" / "house.svg.part1";
  test::write_text(stale, "half a plan");
  test::write_text(live, "another run's");
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --out " + quoted(dir / "out"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(live)) << "process 1 is alive";
}

// A full disk says so, and leaves nothing. Needs a small tmpfs: skipped where mounting is not allowed.
TEST(Cli, AFullDiskIsNamedAndLeavesNoFile) {
  const test::TempDir dir;
  std::filesystem::create_directories(dir / "small");
  if (test::shell("mount -t tmpfs -o size=64k tmpfs " + quoted(dir / "small") + " 2>/dev/null").status != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here";
  const CommandRun r = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --out " + quoted(dir / "small" / "out"));
  std::size_t left = 0;
  std::error_code none;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "small" / "out", none))
    left += !entry.path().empty();
  test::shell("umount " + quoted(dir / "small"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(std::ranges::count(r.output, '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
  EXPECT_EQ(left, 0u);
}

// On a terminal the stage is shown on one line of stderr and cleared at the end; through a pipe
// (every other test here) nothing but the summary. `script` gives the run a terminal.
TEST(Cli, ATerminalShowsTheStageAndTheLineIsClearedAtTheEnd) {
  if (test::shell("command -v script >/dev/null").status != 0) GTEST_SKIP() << "no script(1) here";
  const test::TempDir dir;
  const std::string design = std::string(ORIGAMIC_EXE) + " design " +
                             quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") + " --out " +
                             quoted(dir / "out") + " >/dev/null";
  const test::CommandResult r = test::shell("script -qec \"" + design + "\" /dev/null");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\r\033[Korigamic: slicing..."), std::string::npos) << r.output;
  EXPECT_EQ(r.output.substr(r.output.size() - 4), "\r\033[K") << r.output;
  // With stdout on the terminal too, the line is cleared before the summary is printed.
  const std::string both = std::string(ORIGAMIC_EXE) + " design " +
                           quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") + " --out " +
                           quoted(dir / "both");
  const test::CommandResult shown = test::shell("script -qec \"" + both + "\" /dev/null");
  EXPECT_NE(shown.output.find("\r\033[Khouse.obj: "), std::string::npos) << shown.output;
  const CommandRun piped = run("design " + quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                               " --out " + quoted(dir / "piped"));
  EXPECT_EQ(piped.output.find("slicing"), std::string::npos) << piped.output;
}

// No triangle of the pop-up's mesh, as written, has zero area (the capitol's had two: paper edges
// where the sheet's two sides meet).
TEST(Cli, ThePopUpMeshHasNoTriangleWithoutArea) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const test::TempDir dir;
  const CommandRun designed = run("design " + quoted(test::models_dir() / "seedlike/capitol.stl") +
                                  " --up z --fold-model --out " + quoted(dir.path));
  ASSERT_EQ(designed.status, 0) << designed.output;
  std::ifstream in(dir / "capitol_popup.obj");
  std::vector<glm::dvec3> vertices;
  int triangles = 0, flat = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line.substr(std::min<std::size_t>(2, line.size())));
    if (line.rfind("v ", 0) == 0) {
      glm::dvec3 v;
      words >> v.x >> v.y >> v.z;
      vertices.push_back(v);
    } else if (line.rfind("f ", 0) == 0) {
      std::array<glm::dvec3, 3> corner;
      for (glm::dvec3& c : corner) {
        std::string token;
        words >> token;
        c = vertices.at(std::stoul(token.substr(0, token.find('/'))) - 1);
      }
      ++triangles;
      flat += glm::cross(corner[1] - corner[0], corner[2] - corner[0]) == glm::dvec3(0);
    }
  }
  // A smoke check that the whole card is there (984 triangles since cuts lost their notches at fold
  // ends); the assertion is that none is flat.
  EXPECT_GT(triangles, 900) << "the whole card's faces";
  EXPECT_EQ(flat, 0);
}

}  // namespace
}  // namespace origamic
