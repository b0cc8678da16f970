// SPDX-License-Identifier: GPL-3.0-or-later
// The plan files read back by independent readers: ezdxf and the standard library's XML parser
// (tests/read_plan.py), poppler's pdfinfo, pdftotext and pdftoppm, and PNG chunks parsed here.
#include "origamic/plan_export.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "helpers.hpp"
#include "origamic/design.hpp"
#include "origamic/error.hpp"
#include "origamic/output.hpp"

namespace origamic {
namespace {

Plan plan_of_oa_mesh(TriangleMesh oa_mesh, const Sheet& sheet) {
  const RayScene scene(std::move(oa_mesh));
  const RasterMaps maps = raster(scene, sheet, RasterOptions{});
  const Segmentation segmentation = segment(maps, SegmentOptions{});
  const RasterPlan raster_plan = slice(maps, segmentation, SliceOptions{});
  return build_plan(maps, raster_plan, sheet, PlanOptions{});
}

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

nlohmann::json read_back(const std::filesystem::path& dxf, const std::filesystem::path& svg) {
  const test::CommandResult r = test::shell("/usr/bin/python3 " + std::string(ORIGAMIC_TESTS_DIR) + "/read_plan.py " +
                                            quoted(dxf) + " " + quoted(svg));
  if (r.status != 0) return nullptr;
  return nlohmann::json::parse(r.output);
}

// pdfinfo's "Page size: W x H pts", in mm.
std::pair<double, double> pdfinfo_page_mm(const std::filesystem::path& pdf) {
  const test::CommandResult r = test::shell("pdfinfo " + quoted(pdf));
  EXPECT_EQ(r.status, 0) << r.output;
  std::smatch m;
  if (!std::regex_search(r.output, m, std::regex(R"(Page size:\s+([0-9.]+) x ([0-9.]+) pts)"))) {
    ADD_FAILURE() << "no page size in: " << r.output;
    return {0, 0};
  }
  return {std::stod(m[1]) * 25.4 / 72, std::stod(m[2]) * 25.4 / 72};
}

// pdfinfo's value of one field ("Title", "Subject", ...).
std::string pdfinfo_field(const std::filesystem::path& pdf, const std::string& field) {
  const test::CommandResult r = test::shell("pdfinfo " + quoted(pdf));
  std::smatch m;
  return std::regex_search(r.output, m, std::regex(field + R"(:\s+([^\n]*))")) ? m[1].str() : "";
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* at(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  double darkness(int x, int y) const {  // 0 white .. 1 black
    const std::uint8_t* p = at(x, y);
    return 1 - (p[0] + p[1] + p[2]) / (3 * 255.0);
  }
};

struct Crop {
  int x = 0, y = 0, w = 0, h = 0;  // pixels at the rendering's resolution; w = 0: the whole page
};

// The PDF's first page (or a crop of it) rendered by poppler at `dpi` as a binary PPM (P6).
Image render(const std::filesystem::path& pdf, int dpi, const test::TempDir& dir, const Crop& crop = {}) {
  const std::string area = crop.w ? " -x " + std::to_string(crop.x) + " -y " + std::to_string(crop.y) + " -W " +
                                        std::to_string(crop.w) + " -H " + std::to_string(crop.h)
                                  : "";
  const test::CommandResult r = test::shell("pdftoppm -r " + std::to_string(dpi) + area + " -f 1 -l 1 -singlefile " +
                                            quoted(pdf) + " " + quoted(dir / "page"));
  EXPECT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir / "page.ppm", std::ios::binary);
  std::string magic;
  int maxval = 0;
  Image image;
  in >> magic >> image.width >> image.height >> maxval;
  in.get();
  EXPECT_EQ(magic, "P6");
  EXPECT_EQ(maxval, 255);
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  in.read(reinterpret_cast<char*>(image.rgb.data()), static_cast<std::streamsize>(image.rgb.size()));
  EXPECT_TRUE(in.good());
  return image;
}

struct Bar {
  int row_lo = -1, row_hi = -1;  // pixel rows of the bar
  int col_lo = -1, col_hi = -1;  // its dark run on the first row, half-open
};

// The scale bar: the one dark run 5-20 mm long that repeats, same ends to a pixel, on 8 or more
// consecutive rows (the plan's lines are single pixels thick at 254 dpi).
Bar find_scale_bar(const Image& image, double px_per_mm) {
  std::vector<Bar> bars;
  int lo = -1, hi = -1, first_row = -1;
  for (int y = 0; y <= image.height; ++y) {
    int run_lo = -1, run_hi = -1;
    if (y < image.height)
      for (int x = 0; x < image.width;) {
        if (image.darkness(x, y) < 0.5) {
          ++x;
          continue;
        }
        int end = x;
        while (end < image.width && image.darkness(end, y) >= 0.5) ++end;
        if (end - x >= 5 * px_per_mm && end - x <= 20 * px_per_mm) run_lo = x, run_hi = end;
        x = end;
      }
    if (run_lo >= 0 && first_row >= 0 && std::abs(run_lo - lo) <= 1 && std::abs(run_hi - hi) <= 1) continue;
    if (first_row >= 0 && y - first_row >= 8) bars.push_back({first_row, y - 1, lo, hi});
    first_row = run_lo >= 0 ? y : -1, lo = run_lo, hi = run_hi;
  }
  EXPECT_EQ(bars.size(), 1u) << "exactly one scale bar";
  return bars.size() == 1 ? bars[0] : Bar{};
}

// The length in mm of the dark run through the middle of a bar found at 254 dpi, rendered again
// at 2540 dpi (0.01 mm a pixel; poppler snaps filled rectangles to whole pixels).
double bar_length_mm(const std::filesystem::path& pdf, const Bar& bar, const test::TempDir& dir) {
  const int fine = 10;  // 2540 dpi / 254 dpi
  const Image image = render(
      pdf, 2540, dir,
      {(bar.col_lo - 20) * fine, (bar.row_lo + bar.row_hi) / 2 * fine, (bar.col_hi - bar.col_lo + 40) * fine, 1});
  int lo = -1, hi = -1;
  for (int x = 0; x < image.width; ++x)
    if (image.darkness(x, 0) >= 0.5) (lo < 0 ? lo : hi) = x, hi = x;
  // The run must be one piece: every pixel between its ends dark.
  for (int x = lo; x <= hi; ++x) EXPECT_GE(image.darkness(x, 0), 0.5) << "gap in the bar at pixel " << x;
  return (hi - lo + 1) / 100.0;
}

struct Seg {
  double x1, y1, x2, y2;
};

double point_to_segment(double px, double py, const Seg& s) {
  const double dx = s.x2 - s.x1, dy = s.y2 - s.y1, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((px - s.x1) * dx + (py - s.y1) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(s.x1 + t * dx - px, s.y1 + t * dy - py);
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// The distance between two segments: zero if they cross, else the least endpoint-to-segment distance.
double segment_distance(const Seg& a, const Seg& b) {
  const double d1 = cross(a.x2 - a.x1, a.y2 - a.y1, b.x1 - a.x1, b.y1 - a.y1);
  const double d2 = cross(a.x2 - a.x1, a.y2 - a.y1, b.x2 - a.x1, b.y2 - a.y1);
  const double d3 = cross(b.x2 - b.x1, b.y2 - b.y1, a.x1 - b.x1, a.y1 - b.y1);
  const double d4 = cross(b.x2 - b.x1, b.y2 - b.y1, a.x2 - b.x1, a.y2 - b.y1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0;
  return std::min({point_to_segment(a.x1, a.y1, b), point_to_segment(a.x2, a.y2, b), point_to_segment(b.x1, b.y1, a),
                   point_to_segment(b.x2, b.y2, a)});
}

// Segments as read back, in plan coordinates: a DXF's Y starts at the sheet's bottom edge, `Y_shift`
// (half the sheet) below the main fold.
std::vector<Seg> segs(const nlohmann::json& list, double Y_shift = 0) {
  std::vector<Seg> out;
  for (const auto& s : list)
    out.push_back({s[0].get<double>(), s[1].get<double>() - Y_shift, s[2].get<double>(), s[3].get<double>() - Y_shift});
  return out;
}

double length(const Seg& s) { return std::hypot(s.x2 - s.x1, s.y2 - s.y1); }

// Every fold polyline of a plan, which must be one horizontal run.
struct Fold {
  LineKind kind;
  double Y, lo, hi;
};
std::vector<Fold> folds_of(const Plan& plan) {
  std::vector<Fold> folds;
  for (const PlanPolyline& line : plan.lines) {
    if (line.kind != LineKind::Mountain && line.kind != LineKind::Valley) continue;
    Fold f{line.kind, line.points.front().Y, 1e300, -1e300};
    for (const PlanPoint& p : line.points) {
      EXPECT_EQ(p.Y, f.Y);
      f.lo = std::min(f.lo, p.X), f.hi = std::max(f.hi, p.X);
    }
    folds.push_back(f);
  }
  return folds;
}

std::vector<Seg> cut_segments(const Plan& plan) {
  std::vector<Seg> cuts;
  for (const PlanPolyline& line : plan.lines)
    if (line.kind == LineKind::Cut || line.kind == LineKind::Outline)
      for (std::size_t i = 1; i < line.points.size(); ++i)
        cuts.push_back({line.points[i - 1].X, line.points[i - 1].Y, line.points[i].X, line.points[i].Y});
  return cuts;
}

// The designed house, shared by the tests that need a real plan (designed once: 0.5 s).
class HousePlan : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    house_ = new Plan(design(std::filesystem::path(ORIGAMIC_FIXTURES_DIR) / "house.obj", DesignOptions{}).plan);
  }
  static void TearDownTestSuite() {
    delete house_;
    house_ = nullptr;
  }
  static const Plan& house() { return *house_; }
  static ExportOptions exports(FoldStyle style) {
    ExportOptions options;
    options.model = "house.obj";
    options.settings = "card 210x297 mm, W 3 mm";
    options.folds.style = style;
    return options;
  }

 private:
  static Plan* house_;
};
Plan* HousePlan::house_ = nullptr;

TEST(PlanExport, PdfPageIsTheSheetOrTheChosenPaperReadBackByPdfinfo) {
  const test::TempDir dir;
  struct Case {
    Paper paper;
    double width_mm, height_mm;
  };
  const Plan a4_sheet = plan_of_oa_mesh(test::box({60, 0, 0}, {150, 40, 30}), Sheet{});
  const Plan small = plan_of_oa_mesh(test::box({40, 0, 0}, {110, 30, 20}), Sheet{150.5, 201.3});
  const Plan wide = plan_of_oa_mesh(test::box({100, 0, 0}, {180, 30, 20}), Sheet{270, 200});
  const std::vector<std::pair<const Plan*, Case>> cases = {
      {&a4_sheet, {Paper::Sheet, 210, 297}},   {&a4_sheet, {Paper::A4, 210, 297}},
      {&small, {Paper::Sheet, 150.5, 201.3}},  {&small, {Paper::A4, 210, 297}},
      {&small, {Paper::Letter, 215.9, 279.4}}, {&wide, {Paper::A4, 297, 210}},
      {&wide, {Paper::Letter, 279.4, 215.9}},
  };
  for (const auto& [plan, c] : cases) {
    SCOPED_TRACE(std::to_string(plan->sheet.width_mm) + " on paper " + std::to_string(static_cast<int>(c.paper)));
    ExportOptions options;
    options.model = "box.obj";
    options.paper = c.paper;
    write_files({{dir / "plan.pdf", plan_pdf(*plan, options)}});
    const auto [w, h] = pdfinfo_page_mm(dir / "plan.pdf");
    // pdfinfo prints points to 3 decimals: 0.0005 pt = 0.0002 mm.
    EXPECT_NEAR(w, c.width_mm, 0.0005);
    EXPECT_NEAR(h, c.height_mm, 0.0005);
  }
  ExportOptions letter;
  letter.paper = Paper::Letter;
  try {
    plan_pdf(a4_sheet, letter);
    ADD_FAILURE() << "an A4 sheet does not fit on Letter paper";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "ExportOptions::paper") << e.what();
  }
}

TEST(PlanExport, PdfScaleBarMeasuresTenMillimetresAndTheSheetIsCentredOnThePaper) {
  const test::TempDir dir;
  const Plan small = plan_of_oa_mesh(test::box({40, 0, 0}, {110, 30, 20}), Sheet{150, 200});
  const Plan a4_sheet = plan_of_oa_mesh(test::box({60, 0, 0}, {150, 40, 30}), Sheet{});
  const double px_per_mm = 10;  // 254 dpi
  for (const auto& [plan, paper] : {std::pair{&a4_sheet, Paper::Sheet}, std::pair{&small, Paper::Letter}}) {
    SCOPED_TRACE(paper == Paper::Sheet ? "sheet" : "letter");
    ExportOptions options;
    options.model = "box.obj";
    options.paper = paper;
    write_files({{dir / "plan.pdf", plan_pdf(*plan, options)}});
    const Image image = render(dir / "plan.pdf", 254, dir);
    const Bar bar = find_scale_bar(image, px_per_mm);
    ASSERT_GE(bar.row_lo, 0);
    // 0.01 mm pixels: a page scaled by 0.5 % would put the bar 0.05 mm off.
    const double bar_mm = bar_length_mm(dir / "plan.pdf", bar, dir);
    EXPECT_NEAR(bar_mm, 10.0, 0.02);
    std::printf("[ %s ] scale bar %.2f mm\n", paper == Paper::Sheet ? "sheet" : "letter", bar_mm);
    EXPECT_NEAR((bar.row_hi - bar.row_lo + 1) / px_per_mm, 1.2, 0.15);  // its height, to a pixel

    // The sheet outline (laser preset: green #00e000) bounds the sheet, centred on the page: its
    // edges are the rows and columns more than half green (the legend's green sample is 12 mm).
    auto green = [&](int x, int y) {
      const std::uint8_t* p = image.at(x, y);
      return p[1] > 100 && p[0] < 100 && p[2] < 100;
    };
    int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
    for (int y = 0; y < image.height; ++y) {
      int count = 0;
      for (int x = 0; x < image.width; ++x) count += green(x, y);
      if (count > plan->sheet.width_mm * px_per_mm / 2) y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    for (int x = 0; x < image.width; ++x) {
      int count = 0;
      for (int y = 0; y < image.height; ++y) count += green(x, y);
      if (count > plan->sheet.height_mm * px_per_mm / 2) x0 = std::min(x0, x), x1 = std::max(x1, x);
    }
    const PageSize page = pdf_page(plan->sheet, paper);
    const double left = (page.width_mm - plan->sheet.width_mm) / 2, top = (page.height_mm - plan->sheet.height_mm) / 2;
    // A 0.1 mm line centred on the edge, anti-aliased: its pixels lie within 0.15 mm of the edge.
    if (paper != Paper::Sheet) {
      EXPECT_NEAR(x0 / px_per_mm, left, 0.15);
      EXPECT_NEAR(y0 / px_per_mm, top, 0.15);
    }
    EXPECT_NEAR((x1 + 1) / px_per_mm, left + plan->sheet.width_mm, 0.15);
    EXPECT_NEAR((y1 + 1) / px_per_mm, top + plan->sheet.height_mm, 0.15);
    // On Letter the legend sits in the paper's margin, off the sheet; on the sheet, inside it.
    const bool bar_off_sheet = bar.row_lo / px_per_mm > top + plan->sheet.height_mm || bar.row_hi / px_per_mm < top;
    EXPECT_EQ(bar_off_sheet, paper != Paper::Sheet);
  }
}

TEST(PlanExport, PdfLegendGoesToASecondPageWhenNoCornerOfTheSheetIsFree) {
  const test::TempDir dir;
  // A box 2 mm from either side of the sheet, 140 mm high and deep: its lines reach every corner.
  const Plan full = plan_of_oa_mesh(test::box({2, 0, 0}, {208, 140, 140}), Sheet{});
  ExportOptions options;
  options.model = "wide box.obj";
  write_files({{dir / "plan.pdf", plan_pdf(full, options)}});
  EXPECT_EQ(pdfinfo_field(dir / "plan.pdf", "Pages"), "2");
  const test::CommandResult first = test::shell("pdftotext -f 1 -l 1 " + quoted(dir / "plan.pdf") + " -");
  const test::CommandResult second = test::shell("pdftotext -f 2 -l 2 " + quoted(dir / "plan.pdf") + " -");
  EXPECT_EQ(first.output.find("10 mm"), std::string::npos) << "nothing printed over the plan";
  EXPECT_NE(second.output.find("10 mm"), std::string::npos);
  EXPECT_NE(second.output.find("wide box.obj"), std::string::npos);
  const auto [w, h] = pdfinfo_page_mm(dir / "plan.pdf");
  EXPECT_NEAR(w, 210, 0.0005);
  EXPECT_NEAR(h, 297, 0.0005);
}

TEST_F(HousePlan, TheNarrowPlacesPictureIsThePreviewWithEachChordMarkedBlue) {
  const ExportOptions options = exports(FoldStyle::Score);
  // A chord along Y on the sheet's left, and one 0.05 mm long along X in its middle.
  const std::vector<NarrowChord> chords = {{{5, 100}, {5, 102}}, {{105, -50}, {105.05, -50}}};
  const std::vector<std::uint8_t> marked = narrow_places_rgb(house(), options, chords);
  const std::vector<std::uint8_t> plain = narrow_places_rgb(house(), options, {});
  const int w = 840, h = 1188;  // 210 x 297 mm at 4 px/mm
  ASSERT_EQ(marked.size(), 3u * w * h);
  ASSERT_EQ(plain.size(), marked.size());
  const auto blue = [](const std::vector<std::uint8_t>& rgb, int x, int y) {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * 840 + x);
    return rgb[i + 2] > 200 && rgb[i] < 60 && rgb[i + 1] < 110;
  };
  const auto pixel = [&](double X, double Y) {
    return std::pair{static_cast<int>(X * 4), static_cast<int>((148.5 - Y) * 4)};
  };
  for (const auto& [X, Y] : {std::pair{5.0, 101.0}, std::pair{105.025, -50.0}}) {
    const auto [x, y] = pixel(X, Y);
    EXPECT_TRUE(blue(marked, x, y)) << X << ", " << Y;
  }
  // Each chord's square, 11 pixels a side: its left side 5.5 pixels from the chord's middle.
  const auto [mx, my] = pixel(105.025, -50);
  EXPECT_TRUE(blue(marked, mx - 5, my - 3) || blue(marked, mx - 6, my - 3));
  EXPECT_FALSE(blue(marked, mx - 3, my - 3));  // inside the square, off the chord: the plan's
  // Blue only there, and the plan drawn as plan_png draws it everywhere else.
  std::size_t blue_pixels = 0, changed_elsewhere = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      EXPECT_FALSE(blue(plain, x, y));
      const bool near =
          (std::abs(x - 20) <= 7 && std::abs(y - 190) <= 11) || (std::abs(x - 420) <= 7 && std::abs(y - 794) <= 7);
      blue_pixels += blue(marked, x, y);
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * w + x);
      if (!near && (marked[i] != plain[i] || marked[i + 1] != plain[i + 1] || marked[i + 2] != plain[i + 2]))
        ++changed_elsewhere;
    }
  EXPECT_GT(blue_pixels, 60u);
  EXPECT_EQ(changed_elsewhere, 0u);
}

TEST_F(HousePlan, PdfCarriesItsLegendCaptionAndMetadata) {
  const test::TempDir dir;
  ExportOptions options = exports(FoldStyle::Perforated);
  write_files({{dir / "house.pdf", plan_pdf(house(), options)}});
  const test::CommandResult text = test::shell("pdftotext " + quoted(dir / "house.pdf") + " -");
  ASSERT_EQ(text.status, 0);
  for (const char* words : {"cut", "mountain fold (perforated)", "valley fold (perforated)", "10 mm", "house.obj",
                            "W 3 mm", "cut 1 mm, gap 1 mm, inset 0.5 mm"})
    EXPECT_NE(text.output.find(words), std::string::npos) << words << " in\n" << text.output;
  EXPECT_EQ(pdfinfo_field(dir / "house.pdf", "Title"), "origamic plan: house.obj");
  const std::string subject = pdfinfo_field(dir / "house.pdf", "Subject");
  for (const char* words : {"house.obj", "units mm", "W 3 mm", "fold style perforated"})
    EXPECT_NE(subject.find(words), std::string::npos) << words << " in " << subject;
  EXPECT_NE(pdfinfo_field(dir / "house.pdf", "Keywords").find("house.obj"), std::string::npos);
  EXPECT_EQ(pdfinfo_field(dir / "house.pdf", "Creator").rfind("origamic ", 0), 0u);
  EXPECT_EQ(pdfinfo_field(dir / "house.pdf", "Pages"), "1") << "the legend found a free corner";
}

// A dated PDF is dated then, and the same plan gives the same bytes; the environment plays no part.
TEST_F(HousePlan, ADatedPdfIsDatedThenAndByteIdentical) {
  const test::TempDir dir;
  ExportOptions options = exports(FoldStyle::Score);
  options.pdf_date_s = 1700000000;                    // 2023-11-14 22:13:20 UTC
  ASSERT_EQ(setenv("SOURCE_DATE_EPOCH", "1", 1), 0);  // read by the CLI only
  const std::string first = plan_pdf(house(), options);
  unsetenv("SOURCE_DATE_EPOCH");
  const std::string second = plan_pdf(house(), options);
  EXPECT_EQ(first, second);
  write_files({{dir / "house.pdf", first}});
  const test::CommandResult info = test::shell("TZ=UTC pdfinfo -isodates " + quoted(dir / "house.pdf"));
  ASSERT_EQ(info.status, 0);
  EXPECT_NE(info.output.find("2023-11-14T22:13:20"), std::string::npos) << info.output;
}

// Rendered in parallel, the four files are byte for byte the ones each exporter makes alone.
TEST_F(HousePlan, PlanFilesInParallelAreEachExportersOwn) {
  ExportOptions options = exports(FoldStyle::Score);
  options.pdf_date_s = 1700000000;  // one date for both
  const std::vector<OutputFile> files = plan_files(house(), options, "out/house");
  const std::string pdf = plan_pdf(house(), options);
  ASSERT_EQ(files.size(), 4u);
  EXPECT_EQ(files[0].path, "out/house.dxf");
  EXPECT_EQ(files[0].bytes, plan_dxf(house(), options));
  EXPECT_EQ(files[1].path, "out/house.svg");
  EXPECT_EQ(files[1].bytes, plan_svg(house(), options));
  EXPECT_EQ(files[2].path, "out/house.png");
  EXPECT_EQ(files[2].bytes, plan_png(house(), options));
  EXPECT_EQ(files[3].path, "out/house.pdf");
  EXPECT_EQ(files[3].bytes, pdf);
}

// dxflib sets the DIMSTYLE's text style (group 340) only for a style named exactly "Standard"; while
// ours was "standard" it wrote whatever its memory held, and R2000 files differed from run to run.
TEST_F(HousePlan, R2000DxfIsTheSameEveryTimeAndItsDimstyleNamesItsTextStyle) {
  ExportOptions options = exports(FoldStyle::Score);
  options.dxf_version = DxfVersion::R2000;
  const std::string dxf = plan_dxf(house(), options);
  EXPECT_TRUE(plan_dxf(house(), options) == dxf) << "a second write gave other bytes";
  std::map<std::string, unsigned long> style_handles;  // STYLE records: name -> handle (5)
  std::vector<unsigned long> dimstyle_text_styles;     // DIMSTYLE records' 340
  std::istringstream in(dxf);
  std::string type;
  unsigned long handle = 0;
  for (std::string code, value; std::getline(in, code) && std::getline(in, value);) {
    code.erase(0, code.find_first_not_of(' '));
    if (code == "0") type = value;
    if (type == "STYLE" && code == "5") handle = std::stoul(value, nullptr, 16);
    if (type == "STYLE" && code == "2") style_handles[value] = handle;
    if (type == "DIMSTYLE" && code == "340") dimstyle_text_styles.push_back(std::stoul(value, nullptr, 16));
  }
  ASSERT_EQ(dimstyle_text_styles.size(), 1u);
  ASSERT_EQ(style_handles.size(), 1u) << "one text style";
  EXPECT_EQ(dimstyle_text_styles[0], style_handles.begin()->second) << "DIMSTYLE's 340 is the STYLE record's handle";
}

TEST_F(HousePlan, PerforationsKeepClearOfEveryCutAndCutTheirShareOfEachFold) {
  const test::TempDir dir;
  const std::vector<Fold> folds = folds_of(house());
  const std::vector<Seg> cuts = cut_segments(house());
  double fold_mm = 0;
  for (const Fold& f : folds) fold_mm += f.hi - f.lo;
  // Each stretch of a fold between two of its points, left to right; whether the insets block it
  // whole, sampled every 0.01 mm.
  std::vector<Seg> stretches;
  for (const PlanPolyline& line : house().lines)
    if (line.kind == LineKind::Mountain || line.kind == LineKind::Valley)
      for (std::size_t i = 1; i < line.points.size(); ++i) {
        const PlanPoint a = line.points[i - 1], b = line.points[i];
        stretches.push_back({std::min(a.X, b.X), a.Y, std::max(a.X, b.X), b.Y});
      }
  const auto blocked_whole = [&](const Seg& f, double inset) {
    for (double x = f.x1 + 0.005; x < f.x2; x += 0.01)
      if (std::ranges::all_of(cuts, [&](const Seg& c) { return point_to_segment(x, f.y1, c) >= inset; })) return false;
    return true;
  };
  for (const auto& [cut, gap, inset] : {std::tuple{1.0, 1.0, 0.5}, std::tuple{1.5, 0.8, 0.8}}) {
    SCOPED_TRACE("--perf " + std::to_string(cut) + "," + std::to_string(gap) + " --fold-inset " +
                 std::to_string(inset));
    int thirds = 0;
    ExportOptions options = exports(FoldStyle::Perforated);
    options.folds.perf_cut_mm = cut, options.folds.perf_gap_mm = gap, options.folds.inset_mm = inset;
    write_files({{dir / "plan.dxf", plan_dxf(house(), options)}, {dir / "plan.svg", plan_svg(house(), options)}});
    const nlohmann::json back = read_back(dir / "plan.dxf", dir / "plan.svg");
    ASSERT_FALSE(back.is_null()) << "the reader rejected the files";
    EXPECT_FALSE(back["dxf"].contains("MOUNTAIN")) << "no score lines when perforating";
    EXPECT_FALSE(back["dxf"].contains("VALLEY"));
    double perforated = 0;
    int short_cuts = 0;
    for (const auto& [layer, kind] :
         {std::pair{"PERF_MOUNTAIN", LineKind::Mountain}, std::pair{"PERF_VALLEY", LineKind::Valley}}) {
      ASSERT_TRUE(back["dxf"].contains(layer)) << layer;
      EXPECT_EQ(back["dxf_types"][layer], nlohmann::json({{"LINE", back["dxf"][layer].size()}})) << "separate segments";
      EXPECT_EQ(back["svg"][layer].size(), back["dxf"][layer].size()) << layer << " in the SVG";
      for (const Seg& s : segs(back["dxf"][layer], house().sheet.half_height_mm())) {
        // On a fold of its kind, exactly CUT long unless its whole run is shorter.
        EXPECT_TRUE(std::ranges::any_of(folds,
                                        [&](const Fold& f) {
                                          return f.kind == kind && std::abs(s.y1 - f.Y) < 1e-9 &&
                                                 std::abs(s.y2 - f.Y) < 1e-9 && std::min(s.x1, s.x2) >= f.lo - 1e-9 &&
                                                 std::max(s.x1, s.x2) <= f.hi + 1e-9;
                                        }))
            << layer << " segment at Y " << s.y1 << " X " << s.x1;
        EXPECT_LE(length(s), cut + 1e-9);
        // The middle third of a stretch of a fold (between two of its points) that the insets block
        // whole: the one perforation kept there (fold_style.cpp).
        const auto middle_third = [&](const Seg& f) {
          const double third = (f.x2 - f.x1) / 3;
          return std::abs(s.y1 - f.y1) < 1e-9 && std::abs(std::min(s.x1, s.x2) - (f.x1 + third)) < 1e-9 &&
                 std::abs(std::max(s.x1, s.x2) - (f.x2 - third)) < 1e-9 && blocked_whole(f, inset);
        };
        if (length(s) < cut - 1e-9) {
          // A run shorter than a cut: on the house, only on folds shorter than a cut and two insets,
          // or a blocked stretch's middle third, shorter than a cut where the stretch is.
          ++short_cuts;
          EXPECT_TRUE(std::ranges::any_of(folds,
                                          [&](const Fold& f) {
                                            return std::abs(s.y1 - f.Y) < 1e-9 && std::min(s.x1, s.x2) >= f.lo - 1e-9 &&
                                                   std::max(s.x1, s.x2) <= f.hi + 1e-9 &&
                                                   f.hi - f.lo < cut + 2 * inset + 1e-9;
                                          }) ||
                      std::ranges::any_of(stretches, middle_third))
              << "short cut at Y " << s.y1 << " X " << s.x1;
        }
        perforated += length(s);
        double nearest = 1e300;
        for (const Seg& c : cuts) nearest = std::min(nearest, segment_distance(s, c));
        if (nearest >= inset - 1e-9) continue;
        // Nearer a cut only as the middle third of a stretch of a fold (between two of its points)
        // that the insets block whole: a reader parts the faces there all the same.
        ++thirds;
        EXPECT_TRUE(std::ranges::any_of(stretches, middle_third))
            << layer << " segment " << nearest << " mm from a cut at Y " << s.y1 << " X " << s.x1 << " - " << s.x2;
      }
    }
    // The fold length outside the insets, found independently by sampling every 0.01 mm.
    const double step = 0.01;
    double outside = 0;
    for (const Fold& f : folds) {
      std::vector<Seg> near;
      for (const Seg& c : cuts)
        if (std::max(c.x1, c.x2) > f.lo - inset - 1 && std::min(c.x1, c.x2) < f.hi + inset + 1 &&
            std::max(c.y1, c.y2) > f.Y - inset - 1 && std::min(c.y1, c.y2) < f.Y + inset + 1)
          near.push_back(c);
      for (double x = f.lo + step / 2; x < f.hi; x += step)
        if (std::ranges::all_of(near, [&](const Seg& c) { return point_to_segment(x, f.Y, c) >= inset; }))
          outside += step;
    }
    const double removed = fold_mm - outside;
    EXPECT_LT(removed, 0.03 * fold_mm) << "the insets take a small part of the folds";
    EXPECT_GT(removed, 2 * inset * static_cast<double>(folds.size()) * 0.5) << "both ends of most folds meet a cut";
    EXPECT_NEAR(perforated, outside * cut / (cut + gap), 0.01 * outside * cut / (cut + gap));
    std::printf(
        "[ perf %g,%g inset %g ] folds %.1f mm, outside the insets %.1f mm, perforated %.1f mm (%.2f%% of "
        "the expected %.1f mm), %d cuts shorter than CUT, %d middle thirds of stretches blocked whole\n",
        cut, gap, inset, fold_mm, outside, perforated, 100 * perforated / (outside * cut / (cut + gap)),
        outside * cut / (cut + gap), short_cuts, thirds);
  }
}

// Two plan points a rounding apart are one point once the DXF adds half the sheet to Y (and once
// the SVG writes six decimals): a cut between them is a dot a laser would burn, and a vertex twice
// over a zero-length segment. Neither file has them; the rest of the line is kept, and a ring whose
// ends meet in the file is closed there.
TEST_F(HousePlan, NoFileHasALineOrASegmentOfZeroLength) {
  const double Y = -0.001, next_Y = std::nextafter(Y, 0.0);  // 2e-19 mm apart
  ASSERT_NE(Y, next_Y);
  ASSERT_EQ(Y + house().sheet.half_height_mm(), next_Y + house().sheet.half_height_mm());
  Plan plan = house();
  plan.lines.push_back({LineKind::Cut, {{50, Y}, {50, next_Y}}});
  plan.lines.push_back({LineKind::Cut, {{60, Y}, {60, next_Y}, {70, Y}}});
  plan.lines.push_back({LineKind::Cut, {{80, Y}, {90, Y}, {90, Y - 10}, {80, next_Y}}});
  const test::TempDir dir;
  const ExportOptions options = exports(FoldStyle::Score);
  write_files({{dir / "house.dxf", plan_dxf(house(), options)},
               {dir / "house.svg", plan_svg(house(), options)},
               {dir / "plan.dxf", plan_dxf(plan, options)},
               {dir / "plan.svg", plan_svg(plan, options)}});
  const nlohmann::json before = read_back(dir / "house.dxf", dir / "house.svg");
  const nlohmann::json back = read_back(dir / "plan.dxf", dir / "plan.svg");
  ASSERT_FALSE(before.is_null() || back.is_null()) << "the reader rejected the files";
  const auto entities = [](const nlohmann::json& types) {
    int n = 0;
    for (const auto& [type, count] : types.items()) n += count.get<int>();
    return n;
  };
  EXPECT_EQ(entities(back["dxf_types"]["CUT"]), entities(before["dxf_types"]["CUT"]) + 2);
  EXPECT_EQ(back["svg_lines"]["CUT"].size(), before["svg_lines"]["CUT"].size() + 2);
  for (const char* file : {"dxf", "svg"})
    for (const auto& [layer, segments] : back[file].items()) {
      int kept = 0;
      for (const auto& s : segments) {
        const std::vector<double> v = s;
        EXPECT_FALSE(v[0] == v[2] && v[1] == v[3]) << file << " " << layer << " at " << v[0] << ", " << v[1];
        kept += layer == "CUT" && v[0] == 60 && v[2] == 70;
      }
      if (layer == "CUT") {
        EXPECT_EQ(kept, 1) << file << ": the cut from X = 60 to 70";
      }
    }
  // The ring: one closed polyline of three vertices, as ezdxf reads it.
  const test::CommandResult rings =
      test::shell("/usr/bin/python3 -c \"import ezdxf, sys; print(sum(1 for e in ezdxf.readfile(sys.argv[1]).modelspace() "
                  "if e.dxftype() == 'POLYLINE' and e.dxf.layer == 'CUT' and e.is_closed and len(e.vertices) == 3 "
                  "and min(v.dxf.location[0] for v in e.vertices) == 80))\" " +
                  quoted(dir / "plan.dxf"));
  ASSERT_EQ(rings.status, 0) << rings.output;
  EXPECT_EQ(rings.output, "1\n");
}

TEST_F(HousePlan, DashedFoldsCarryTheirPatternInTheDxfAndTheSvg) {
  const test::TempDir dir;
  const ExportOptions options = exports(FoldStyle::Dashed);
  write_files({{dir / "plan.dxf", plan_dxf(house(), options)}, {dir / "plan.svg", plan_svg(house(), options)}});
  const nlohmann::json back = read_back(dir / "plan.dxf", dir / "plan.svg");
  ASSERT_FALSE(back.is_null()) << "the reader rejected the files";
  const std::vector<Fold> folds = folds_of(house());
  for (const auto& [layer, kind] : {std::pair{"MOUNTAIN", LineKind::Mountain}, std::pair{"VALLEY", LineKind::Valley}}) {
    SCOPED_TRACE(layer);
    const bool mountain = kind == LineKind::Mountain;
    const double full = mountain ? 2 + 0.75 + 0.5 + 0.75 + 2 : 2 + 1 + 2;  // a period and a dash, mm
    // DXF: each fold as separate LINE dashes from its start to its end, dash (dot dash)*.
    EXPECT_EQ(back["dxf_types"][layer], nlohmann::json({{"LINE", back["dxf"][layer].size()}}));
    const std::vector<Seg> dashes = segs(back["dxf"][layer], house().sheet.half_height_mm());
    std::size_t matched = 0;
    for (const Fold& f : folds) {
      if (f.kind != kind) continue;
      std::vector<Seg> on;
      for (const Seg& s : dashes)
        if (std::abs(s.y1 - f.Y) < 1e-9 && (s.x1 + s.x2) / 2 > f.lo && (s.x1 + s.x2) / 2 < f.hi)
          on.push_back({std::min(s.x1, s.x2), s.y1, std::max(s.x1, s.x2), s.y2});
      std::ranges::sort(on, {}, &Seg::x1);
      matched += on.size();
      ASSERT_GE(on.size(), 2u) << "fold at Y " << f.Y;
      EXPECT_NEAR(on.front().x1, f.lo, 1e-9);
      EXPECT_NEAR(on.back().x2, f.hi, 1e-9);
      // Unscaled on folds of at least a period and a dash (mountain 6 mm, valley 5), else scaled.
      const double L = f.hi - f.lo, k = L >= full ? 1 : L / full;
      const double gap = on[1].x1 - on[0].x2;
      EXPECT_GE(gap, (mountain ? 0.75 : 1.0) * k - 1e-9);
      for (std::size_t i = 0; i < on.size(); ++i) {
        EXPECT_NEAR(on[i].x2 - on[i].x1, (mountain && i % 2 ? 0.5 : 2.0) * k, 1e-9) << "Y " << f.Y << " piece " << i;
        if (i) {
          EXPECT_NEAR(on[i].x1 - on[i - 1].x2, gap, 1e-9);
        }
      }
      if (mountain) {
        EXPECT_EQ(on.size() % 2, 1u);
      }
    }
    EXPECT_EQ(matched, dashes.size()) << "every dash lies on a fold";
    // SVG: each fold one polyline with its fitted stroke-dasharray, ending on a whole dash.
    ASSERT_EQ(back["svg_lines"][layer].size(), static_cast<std::size_t>(std::ranges::count(folds, kind, &Fold::kind)));
    for (const auto& line : back["svg_lines"][layer]) {
      ASSERT_TRUE(line["dash"].is_array());
      const std::vector<double> dash = line["dash"];
      ASSERT_EQ(dash.size(), mountain ? 4u : 2u);
      const auto& pts = line["points"];
      const double L = std::abs(pts.back()[0].get<double>() - pts.front()[0].get<double>());
      const double k = L >= full ? 1 : L / full;
      EXPECT_NEAR(dash[0], 2.0 * k, 1e-6);
      if (mountain) {
        EXPECT_NEAR(dash[2], 0.5 * k, 1e-6);
        EXPECT_NEAR(dash[1], dash[3], 1e-6);
      }
      double period = 0;
      for (const double v : dash) period += v;
      const double periods = (L - dash[0]) / period;
      EXPECT_NEAR(periods, std::round(periods), 1e-4) << "the pattern ends on a whole dash";
    }
  }
}

TEST_F(HousePlan, EveryFileNamesItsUnitsModelSettingsAndFoldStyle) {
  const test::TempDir dir;
  const ExportOptions options = exports(FoldStyle::Dashed);
  write_files({{dir / "plan.dxf", plan_dxf(house(), options)},
               {dir / "plan.svg", plan_svg(house(), options)},
               {dir / "plan.png", plan_png(house(), options)}});
  const nlohmann::json back = read_back(dir / "plan.dxf", dir / "plan.svg");
  ASSERT_FALSE(back.is_null());
  std::string comments;
  for (const auto& c : back["dxf_comments"]) comments += c.get<std::string>() + "\n";
  const std::string svg_text = back["svg_title"].get<std::string>() + back["svg_desc"].get<std::string>();
  const std::string svg_metadata = back["svg_metadata"];
  // PNG: walk the chunks (length, type, data, CRC) and collect the tEXt keyword/text pairs and pHYs.
  const std::string png = test::read_bytes(dir / "plan.png");
  std::map<std::string, std::string> texts;
  std::string phys;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(png[i])); };
    const std::uint32_t size = byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3);
    const std::string type = png.substr(at + 4, 4), data = png.substr(at + 8, size);
    if (type == "tEXt") texts[data.substr(0, data.find('\0'))] = data.substr(data.find('\0') + 1);
    if (type == "pHYs") phys = data;
    at += 12 + size;
  }
  const std::string png_text = texts["Title"] + texts["Description"];
  for (const char* words : {"house.obj", "units", "mm", "W 3 mm", "fold style dashed"}) {
    EXPECT_NE(comments.find(words), std::string::npos) << words << " in the DXF comments\n" << comments;
    EXPECT_NE(svg_text.find(words), std::string::npos) << words << " in the SVG title and desc";
    EXPECT_NE(svg_metadata.find(words), std::string::npos) << words << " in the SVG metadata";
    EXPECT_NE(png_text.find(words), std::string::npos) << words << " in the PNG text";
  }
  EXPECT_EQ(texts["Software"].rfind("origamic ", 0), 0u);
  ASSERT_EQ(phys.size(), 9u);
  EXPECT_EQ(phys, std::string("\0\0\x0f\xa0\0\0\x0f\xa0\x01", 9)) << "4000 px per metre both ways";
  EXPECT_EQ(back["insunits"], 4);
  EXPECT_EQ(back["svg_size"]["width"], "210mm");
}

}  // namespace
}  // namespace origamic
