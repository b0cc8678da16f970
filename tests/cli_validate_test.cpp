// SPDX-License-Identifier: GPL-3.0-or-later
// `origamic validate` as a user runs it.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "helpers.hpp"

namespace origamic {
namespace {

constexpr double kD = 37.3, kH = 61.7, kX0 = 40.2, kX1 = 151.9;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

// The box plan with its front-to-top fold drawn as a valley fold.
std::vector<PlanPolyline> swapped_box() {
  std::vector<PlanPolyline> lines = test::box_plan(kD, kH, kX0, kX1);
  for (PlanPolyline& line : lines)
    if (line.kind == LineKind::Mountain) line.kind = LineKind::Valley;
  return lines;
}

TEST(CliValidate, ValidPlanPrintsItsVerdictAndExitsZero) {
  const test::TempDir dir;
  test::write_text(dir / "box.dxf", test::dxf_text(test::box_plan(kD, kH, kX0, kX1)));
  const test::CommandRun r = test::run_origamic("validate " + test::quoted(dir / "box.dxf"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "plan VALID: 2 faces\n");
}

TEST(CliValidate, InvalidPlanListsEachProblemWithItsPlaceAndExitsThree) {
  const test::TempDir dir;
  test::write_text(dir / "swapped.dxf", test::dxf_text(swapped_box()));
  const test::CommandRun r = test::run_origamic("validate " + test::quoted(dir / "swapped.dxf"));
  EXPECT_EQ(r.status, 3) << r.output;
  const std::vector<std::string> lines = lines_of(r.output);
  ASSERT_EQ(lines.size(), 2u) << r.output;
  EXPECT_EQ(lines[0], "plan INVALID: 2 faces; 1 wrong fold kind");
  EXPECT_EQ(lines[1].rfind("error: wrong_fold_kind: at Y = 24.4 from X = 40.2 to 151.9: valley fold, but ", 0), 0u)
      << lines[1];
}

TEST(CliValidate, JsonReportHasTheVerdictTheProblemsAndTheFaces) {
  const test::TempDir dir;
  test::write_text(dir / "swapped.dxf", test::dxf_text(swapped_box()));
  const test::CommandRun r = test::run_origamic("validate --json " + test::quoted(dir / "swapped.dxf"), true);
  EXPECT_EQ(r.status, 3);
  const nlohmann::json report = nlohmann::json::parse(r.output);
  EXPECT_EQ(report["verdict"], "invalid");
  EXPECT_EQ(report["units"], "mm");
  EXPECT_EQ(report["counts"]["faces"], 2);
  EXPECT_EQ(report["counts"]["valid"], 2);
  EXPECT_EQ(report["counts"]["errors"], 1);
  EXPECT_EQ(report["sheet"]["max_X"], 210.0);
  ASSERT_EQ(report["problems"].size(), 1u);
  const auto& p = report["problems"][0];
  EXPECT_EQ(p["kind"], "wrong_fold_kind");
  EXPECT_EQ(p["severity"], "error");
  EXPECT_EQ(p["from"], nlohmann::json::array({kX0, kH - kD}));
  EXPECT_EQ(p["to"], nlohmann::json::array({kX1, kH - kD}));
  ASSERT_EQ(report["faces"].size(), 4u);
  int placed = 0;
  for (const auto& face : report["faces"]) {
    placed += face["placed"].get<bool>();
    if (face["role"] == "face") {
      EXPECT_EQ(face["depth_mm"], face["orientation"] == "V" ? kD : kH);
    } else {
      EXPECT_EQ(face["orientation"], face["role"] == "back plane" ? "V" : "H");
      EXPECT_EQ(face["depth_mm"], 0.0);
    }
  }
  EXPECT_EQ(placed, 4);

  test::write_text(dir / "box.dxf", test::dxf_text(test::box_plan(kD, kH, kX0, kX1)));
  const test::CommandRun valid = test::run_origamic("validate " + test::quoted(dir / "box.dxf") + " --json", true);
  EXPECT_EQ(valid.status, 0);
  EXPECT_EQ(nlohmann::json::parse(valid.output)["verdict"], "valid");
}

TEST(CliValidate, LayerNamesAndStripWidthAreOptions) {
  const test::TempDir dir;
  test::write_text(dir / "de.dxf", test::dxf_text(test::box_plan(kD, 2.5, kX0, kX1), 4, {"S", "B", "T", "R"}));
  const std::string file = test::quoted(dir / "de.dxf");
  const test::CommandRun unnamed = test::run_origamic("validate " + file);
  EXPECT_EQ(unnamed.status, 2) << unnamed.output;
  EXPECT_NE(unnamed.output.find("no line on the layers CUT, MOUNTAIN or VALLEY"), std::string::npos) << unnamed.output;
  const std::string layers = " --cut-layer S --mountain-layer B --valley-layer T --outline-layer R";
  const test::CommandRun named = test::run_origamic("validate " + file + layers);
  EXPECT_EQ(named.status, 0) << named.output;
  // The front is h = 2.5 mm high on the plan (from -d to h - d): under W = 3 mm.
  const test::CommandRun narrow = test::run_origamic("validate " + file + layers + " --min-strip 3");
  EXPECT_EQ(narrow.status, 3) << narrow.output;
  EXPECT_NE(narrow.output.find("error: narrow_strip: face V(37.3)"), std::string::npos) << narrow.output;
  EXPECT_NE(narrow.output.find("is 2.5 mm wide along Y at X = 40.2 from Y = -37.3 to -34.8"), std::string::npos)
      << narrow.output;
}

TEST(CliValidate, DesignedPlanValidatesWithTheDesignsCounts) {
  const test::TempDir dir;
  const test::CommandRun designed =
      test::run_origamic("design " + test::quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                         " --no-supports --min-strip 3 --out " + test::quoted(dir.path));
  ASSERT_EQ(designed.status, 0) << designed.output;
  std::ifstream in(dir / "house.json");
  const auto design = nlohmann::json::parse(in)["plan"];
  const test::CommandRun r =
      test::run_origamic("validate --json --min-strip 3 " + test::quoted(dir / "house.dxf"), true);
  EXPECT_EQ(r.status, design["verdict"] == "valid" ? 0 : 3);
  const auto report = nlohmann::json::parse(r.output);
  EXPECT_EQ(report["verdict"], design["verdict"]);
  for (const char* count : {"faces", "valid", "indirect", "floating", "dangling", "invalid"})
    EXPECT_EQ(report["counts"][count], design["counts"][count]) << count;
}

// The design reports every place its plan is narrower than W as validate finds them in the DXF it
// wrote, read back: the same places, widths, ends and folds apart, in the same order, to the last
// bit (it measures its lines as the file holds them, Y from the sheet's bottom edge). Measured on
// its lines as computed, seedlike/wedge had 25 places where its DXF had 21: steps of 7e-15 mm
// between a fold on h - d and a support's corner on the pixel lattice, which no file has.
TEST(CliValidate, TheDesignReportsThePlacesValidateFindsNarrowerThanW) {
  std::vector<std::pair<std::filesystem::path, std::string>> models{
      {std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj", "y"}};
  if (!test::models_dir().empty()) models.emplace_back(test::models_dir() / "seedlike/barrel_vault.stl", "z");
  for (const auto& [model, up] : models) {
    SCOPED_TRACE(model.filename().string());
    const test::TempDir dir;
    const test::CommandRun designed = test::run_origamic("design " + test::quoted(model) + " --up " + up +
                                                         " --allow-narrow --out " + test::quoted(dir.path));
    ASSERT_EQ(designed.status, 0) << designed.output;
    const std::string stem = model.stem().string();
    const auto report = nlohmann::json::parse(std::ifstream(dir / (stem + ".json")));
    const auto& narrow = report["narrow_strips"];
    const test::CommandRun r =
        test::run_origamic("validate --json --min-strip 3 " + test::quoted(dir / (stem + ".dxf")), true);
    const auto read_back = nlohmann::json::parse(r.output);
    std::vector<nlohmann::json> found;
    for (const auto& p : read_back["problems"])
      if (p["kind"] == "narrow_strip") found.push_back(p);
    ASSERT_FALSE(found.empty()) << "the house's roof steps and the barrel vault's slices leave strips under 3 mm";
    ASSERT_EQ(narrow.size(), found.size());
    EXPECT_EQ(report["plan"]["narrow_strip_count"], found.size());
    EXPECT_EQ(report["plan"]["narrow_between_folds_count"], read_back["counts"]["narrow_between_folds"]);
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(narrow[i]["width_mm"], found[i]["value_mm"]) << i;
      EXPECT_LT(narrow[i]["width_mm"].get<double>(), 3.0) << i;
      EXPECT_EQ(narrow[i]["from_XY"], found[i]["from"]) << i;
      EXPECT_EQ(narrow[i]["to_XY"], found[i]["to"]) << i;
      EXPECT_EQ(narrow[i].value("folds_apart_mm", 0.0), found[i].value("folds_apart_mm", 0.0)) << i;
      EXPECT_EQ(narrow[i].at("narrow_chords"), found[i].at("narrow_chords")) << i;
      EXPECT_GE(found[i].at("narrow_chords").get<int>(), 1) << i;
    }
    const std::string places = found.size() == 1 ? " place" : " places";
    EXPECT_NE(designed.output.find(std::to_string(found.size()) + places + " narrower than W"), std::string::npos)
        << designed.output;
  }
}

// A ramp off the floor is a staircase of terraces W apart, its lowest W above the floor (slice.cpp):
// no strip under W anywhere, as the design and `validate --min-strip 3` find its DXF.
TEST(CliValidate, TheWedgesStaircaseHasNoPlaceNarrowerThanW) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const test::TempDir dir;
  const test::CommandRun designed = test::run_origamic(
      "design " + test::quoted(test::models_dir() / "seedlike/wedge.stl") + " --up z --out " + test::quoted(dir.path));
  ASSERT_EQ(designed.status, 0) << designed.output;
  EXPECT_NE(designed.output.find("plan VALID"), std::string::npos) << designed.output;
  EXPECT_NE(designed.output.find("; 0 places narrower than W"), std::string::npos) << designed.output;
  const test::CommandRun r =
      test::run_origamic("validate --json --min-strip 3 " + test::quoted(dir / "wedge.dxf"), true);
  const auto read_back = nlohmann::json::parse(r.output);
  int narrow = 0;
  for (const auto& p : read_back["problems"]) narrow += p["kind"] == "narrow_strip";
  EXPECT_EQ(narrow, 0);
  EXPECT_EQ(read_back["counts"]["narrow_between_folds"], 0);
}

// W is the user's promise to their cutter (issue 23): a plan that stands but has places narrower
// than W is not valid, as `validate --min-strip W` finds its DXF, unless --allow-narrow accepts them;
// either way every file is written and the places are listed.
TEST(CliValidate, APlanWithPlacesNarrowerThanWIsInvalidUnlessAllowNarrow) {
  const test::TempDir dir;
  const std::string house = test::quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj");
  const test::CommandRun strict =
      test::run_origamic("design " + house + " --min-strip 3 --strict --out " + test::quoted(dir / "strict"));
  EXPECT_EQ(strict.status, 3) << strict.output;
  EXPECT_NE(strict.output.find("plan INVALID: "), std::string::npos) << strict.output;
  const auto plan = nlohmann::json::parse(std::ifstream(dir / "strict" / "house.json"))["plan"];
  EXPECT_EQ(plan["verdict"], "invalid");
  EXPECT_TRUE(plan["stands"].get<bool>());
  const int narrow = plan["narrow_strip_count"].get<int>(), between = plan["narrow_between_folds_count"].get<int>();
  EXPECT_GT(narrow, 0) << "the house's roof steps leave strips under 3 mm";
  const std::string places = "; " + std::to_string(narrow) + " places narrower than W" +
                             (between > 0 ? ", " + std::to_string(between) + " of them between two folds" : "");
  EXPECT_NE(strict.output.find(places + " (--allow-narrow accepts them)"), std::string::npos) << strict.output;
  EXPECT_FALSE(plan["allow_narrow"].get<bool>());
  for (const char* name : {"house.dxf", "house.svg", "house.pdf", "house.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "strict" / name)) << name;
  const std::string dxf = test::quoted(dir / "strict" / "house.dxf");
  EXPECT_EQ(test::run_origamic("validate --min-strip 3 " + dxf).status, 3);
  // The places between two folds less than W apart, as the DXF read back has them.
  const test::CommandRun read_back = test::run_origamic("validate --json --min-strip 3 " + dxf, true);
  EXPECT_EQ(nlohmann::json::parse(read_back.output)["counts"]["narrow_between_folds"].get<int>(), between)
      << read_back.output;
  EXPECT_EQ(test::run_origamic("validate " + dxf).status, 0) << "it stands";

  const test::CommandRun allowed = test::run_origamic(
      "design " + house + " --min-strip 3 --strict --allow-narrow --out " + test::quoted(dir / "allowed"));
  EXPECT_EQ(allowed.status, 0) << allowed.output;
  EXPECT_NE(allowed.output.find("plan VALID: "), std::string::npos) << allowed.output;
  EXPECT_NE(allowed.output.find(places + " (allowed); "), std::string::npos) << allowed.output;
  const auto allowed_plan = nlohmann::json::parse(std::ifstream(dir / "allowed" / "house.json"))["plan"];
  EXPECT_EQ(allowed_plan["verdict"], "valid");
  EXPECT_EQ(allowed_plan["narrow_strip_count"], narrow);
  EXPECT_TRUE(allowed_plan["allow_narrow"].get<bool>());
}

// Every plan origamic writes validates, whichever way its folds are drawn: the dashes of the printed
// style and the perforations are read as the folds they stand for, to the same faces and lengths.
TEST(CliValidate, EveryFoldStyleValidatesAsTheScoredPlanAndFolds) {
  const test::TempDir dir;
  nlohmann::json scored;
  for (const std::string style : {"score", "perforated", "dashed"}) {
    const test::CommandRun designed =
        test::run_origamic("design " + test::quoted(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj") +
                           " --strict --allow-narrow --fold-style " + style + " --out " + test::quoted(dir / style));
    ASSERT_EQ(designed.status, 0) << designed.output;
    const std::string dxf = test::quoted(dir / style / "house.dxf");
    const test::CommandRun r = test::run_origamic("validate --json " + dxf, true);
    EXPECT_EQ(r.status, 0) << style << ": " << r.output.substr(0, 2000);
    const auto report = nlohmann::json::parse(r.output);
    EXPECT_EQ(report["counts"]["errors"], 0) << style;
    EXPECT_EQ(report["counts"]["warnings"], 0) << style;
    if (style == "score") {
      scored = report;
      continue;
    }
    EXPECT_EQ(report["counts"], scored["counts"]) << style;
    for (const char* kind : {"cut", "mountain", "valley"})
      EXPECT_EQ(report["length_mm"][kind], scored["length_mm"][kind]) << style << " " << kind;
    const test::CommandRun folded =
        test::run_origamic("fold " + dxf + " --angle 90 -o " + test::quoted(dir / (style + ".obj")));
    EXPECT_EQ(folded.status, 0) << folded.output;
    EXPECT_NE(folded.output.find("(0 faces not reached by any fold left out)"), std::string::npos) << folded.output;
  }
}

// The capitol's plan has folds 0.5 mm long between two cuts: perforated, each must still be read as
// a fold, so that validate finds the faces the design drew.
TEST(CliValidate, APerforatedPlanWithFoldsShorterThanTheInsetsValidatesAsDesigned) {
  if (test::models_dir().empty()) GTEST_SKIP() << "../shared/models not found";
  const test::TempDir dir;
  const test::CommandRun designed = test::run_origamic(
      "design " + test::quoted(test::models_dir() / "seedlike/capitol.stl") +
      " --up z --strict --allow-narrow --fold-style perforated --out " + test::quoted(dir.path));
  ASSERT_EQ(designed.status, 0) << designed.output;
  const auto report = nlohmann::json::parse(std::ifstream(dir / "capitol.json"));
  const test::CommandRun r = test::run_origamic("validate --json " + test::quoted(dir / "capitol.dxf"), true);
  EXPECT_EQ(r.status, 0) << r.output.substr(0, 2000);
  const auto read = nlohmann::json::parse(r.output);
  EXPECT_EQ(read["counts"]["errors"], 0);
  EXPECT_EQ(read["counts"]["faces"], report["plan"]["counts"]["faces"]);
}

TEST(CliValidate, BadFilesAndOptionsExitTwoWithOneLineNamingThem) {
  const test::TempDir dir;
  test::write_text(dir / "notes.dxf", "these are my notes, not a drawing\n");
  test::write_text(dir / "box.dxf", test::dxf_text(test::box_plan(kD, kH, kX0, kX1)));
  const struct {
    std::string arguments, names, problem;
  } cases[] = {{test::quoted(dir / "missing.dxf"), "missing.dxf", "no such file"},
               {test::quoted(dir / "notes.dxf"), "notes.dxf", "not a DXF file"},
               {test::quoted(dir.path), dir.path.filename().string(), "folder"},
               {test::quoted(dir / "box.dxf") + " --min-strip -1", "--min-strip", ""},
               {test::quoted(dir / "box.dxf") + " --tolerance 5", "--tolerance", "between 0 and 0.1 mm"},
               {test::quoted(dir / "box.dxf") + " --bogus", "--bogus", ""}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.arguments);
    const test::CommandRun r = test::run_origamic("validate " + c.arguments);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_EQ(std::ranges::count(r.output, '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.problem), std::string::npos) << r.output;
  }
}

// Plans dxflib trusted: a line of 1,024 characters or more made it loop forever, a "nan" it read as
// 0, a vertex count it allocated as it said, and a coordinate near 1e18 crashed `fold`. Each is now
// one line naming the file and the problem, from validate and from fold, and fold writes nothing.
TEST(CliValidate, MalformedPlansAreRefusedByValidateAndFold) {
  const test::TempDir dir;
  const std::string box = test::dxf_text(test::box_plan(kD, kH, kX0, kX1));
  const auto lwpolyline = [](const std::string& layer, const std::string& count, const std::string& y) {
    return "0\nLWPOLYLINE\n8\n" + layer + "\n90\n" + count + "\n10\n0\n20\n" + y + "\n10\n5\n20\n3\n";
  };
  const auto plan = [](const std::string& entities) {
    return "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n";
  };
  std::string nan = box;
  nan.replace(nan.find("\n10\n") + 4, nan.find('\n', nan.find("\n10\n") + 4) - nan.find("\n10\n") - 4, "nan");
  test::write_text(dir / "long.dxf", "999\n" + std::string(1500, 'x') + "\n" + box);
  test::write_text(dir / "nan.dxf", nan);
  test::write_text(dir / "count.dxf", plan(lwpolyline("MOUNTAIN", "2147483647", "1") + lwpolyline("CUT", "2", "0")));
  test::write_text(dir / "far.dxf",
                   plan(lwpolyline("MOUNTAIN", "2", "-1078321467489004135") + lwpolyline("CUT", "2", "0")));
  test::write_text(dir / "layer.dxf", plan("0\nLINE\n8\nA\x0b" "B\n10\n0\n20\n0\n11\n1\n21\n1\n"));
  const struct {
    std::string file, problem;
  } cases[] = {{"long.dxf", "line 2 is longer than 1000 characters"},
               {"nan.dxf", "must hold a finite number"},
               {"count.dxf", "group 90 counts 2147483647 parts"},
               {"far.dxf", "beyond 10,000,000 drawing units"},
               {"layer.dxf", "A\\x0b"}};
  // Groups of these codes that are no counts stay readable: an MLEADER's true colour is negative.
  std::string colour = box;
  colour.insert(colour.rfind("0\nENDSEC"), "0\nMLEADER\n8\nNOTES\n91\n-1056964608\n");
  test::write_text(dir / "colour.dxf", colour);
  const test::CommandRun read = test::run_origamic("validate " + test::quoted(dir / "colour.dxf"));
  EXPECT_EQ(read.status, 0) << read.output;
  for (const auto& c : cases) {
    for (const std::string command : {"validate ", "fold "}) {
      SCOPED_TRACE(command + c.file);
      const std::filesystem::path out = dir / (c.file + ".obj");
      const test::CommandRun r = test::run_origamic(
          command + test::quoted(dir / c.file) + (command == "fold " ? " --out " + test::quoted(out) : ""));
      EXPECT_EQ(r.status, 2) << r.output;
      EXPECT_EQ(std::ranges::count(r.output, '\n'), 1) << r.output;
      EXPECT_NE(r.output.find(c.file), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(c.problem), std::string::npos) << r.output;
      EXPECT_FALSE(std::filesystem::exists(out));
    }
  }
}

TEST(CliValidate, HelpListsTheOptions) {
  const test::CommandRun help = test::run_origamic("validate --help");
  EXPECT_EQ(help.status, 0);
  for (const char* option :
       {"--min-strip", "--json", "--tolerance", "--cut-layer", "--mountain-layer", "--valley-layer", "--outline-layer"})
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  EXPECT_NE(test::run_origamic("--help").output.find("validate"), std::string::npos);
}

}  // namespace
}  // namespace origamic
