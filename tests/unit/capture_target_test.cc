// Targets: corner numbering and positions derived by hand, the tables of marker families checked
// against the libraries that decode them, ChArUco geometry against OpenCV's own CharucoBoard,
// target@1 round trips and refusals, exact pattern areas, and the printable files (SVG size,
// PNG coverage and its pHYs chunk, checked with zlib's CRC).
#include <gtest/gtest.h>
#include <zlib.h>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <regex>

extern "C" {
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h10.h>
#include <apriltag/tag36h11.h>
}

#include "support/capture_scenes.h"
#include "support/error_of.h"
#include "vstcal/capture/paper.h"
#include "vstcal/capture/pattern.h"
#include "vstcal/capture/target_drawing.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

using testing::AprilGrid6x4;
using testing::Charuco7x5;
using testing::Chessboard9x6;

TEST(Target, ChessboardCornersRowByRowFromTheTopLeftInnerCorner) {
  const Target t = Chessboard9x6();
  ASSERT_EQ(NumCorners(t), 54);
  EXPECT_EQ(CornerPosition(t, 0), Eigen::Vector2d(0, 0));
  EXPECT_EQ(CornerPosition(t, 8), Eigen::Vector2d(200, 0));   // end of the first row: 8 squares along X
  EXPECT_EQ(CornerPosition(t, 9), Eigen::Vector2d(0, 25));    // first of the second row: one square down Y
  EXPECT_EQ(CornerPosition(t, 53), Eigen::Vector2d(200, 125));
  const Rect sheet = SheetExtent(t);  // 10 × 7 squares plus a square of margin all round
  EXPECT_DOUBLE_EQ(sheet.width(), 12 * 25.0);
  EXPECT_DOUBLE_EQ(sheet.height(), 9 * 25.0);
  EXPECT_DOUBLE_EQ(sheet.x0, -50);
}

TEST(Target, AprilGridCornersGoRoundEachTagClockwiseFromTopLeft) {
  const Target t = AprilGrid6x4();  // 30 mm tags, 7.5 mm gaps: pitch 37.5
  ASSERT_EQ(NumCorners(t), 96);
  EXPECT_EQ(CornerPosition(t, 0), Eigen::Vector2d(0, 0));
  EXPECT_EQ(CornerPosition(t, 1), Eigen::Vector2d(30, 0));
  EXPECT_EQ(CornerPosition(t, 2), Eigen::Vector2d(30, 30));
  EXPECT_EQ(CornerPosition(t, 3), Eigen::Vector2d(0, 30));
  EXPECT_EQ(CornerPosition(t, 4 * 7 + 0), Eigen::Vector2d(37.5, 37.5));  // tag 7 = row 1, column 1
  const std::vector<Quad> tags = MarkerQuads(t);
  ASSERT_EQ(tags.size(), 24u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(tags[7][k], CornerPosition(t, 28 + k));
}

TEST(Target, HalfTurnSymmetryIsRowsPlusColsEven) {
  Target t = Chessboard9x6();
  EXPECT_FALSE(IsHalfTurnSymmetric(t));
  t.cols = 8;
  EXPECT_TRUE(IsHalfTurnSymmetric(t));
  EXPECT_FALSE(IsHalfTurnSymmetric(Charuco7x5()));  // markers break every symmetry
}

// The dictionary table must say what OpenCV's dictionaries are, entry by entry (the index is
// OpenCV's enum value).
TEST(Target, ArucoTableMatchesOpenCv) {
  const auto table = ArucoDictionaries();
  for (size_t i = 0; i < table.size(); ++i) {
    const auto dict = cv::aruco::getPredefinedDictionary(static_cast<int>(i));
    EXPECT_EQ(dict->markerSize, table[i].bits) << table[i].name;
    EXPECT_EQ(dict->bytesList.rows, table[i].num_codes) << table[i].name;
  }
}

TEST(Target, AprilTagTableMatchesLibapriltag) {
  struct Family {
    apriltag_family_t* (*create)();
    void (*destroy)(apriltag_family_t*);
    const char* name;
  };
  for (const Family& f : {Family{tag36h11_create, tag36h11_destroy, "tag36h11"}, Family{tag36h10_create, tag36h10_destroy, "tag36h10"},
                          Family{tag25h9_create, tag25h9_destroy, "tag25h9"}, Family{tag16h5_create, tag16h5_destroy, "tag16h5"}}) {
    apriltag_family_t* fam = f.create();
    const MarkerFamily* entry = FindMarkerFamily(AprilTagFamilies(), f.name);
    ASSERT_NE(entry, nullptr) << f.name;
    EXPECT_EQ(static_cast<int>(fam->ncodes), entry->num_codes) << f.name;
    EXPECT_EQ(fam->width_at_border, entry->bits + 2) << f.name;
    EXPECT_EQ(fam->total_width, entry->bits + 4) << f.name;  // a white ring outside the black border
    EXPECT_FALSE(fam->reversed_border) << f.name;
    f.destroy(fam);
  }
}

// Peer: OpenCV's CharucoBoard puts its origin at the board's outer top-left corner; vstcal's is the
// first inner corner, one square in. Corner ids and marker ids and corners must agree after that shift.
TEST(Target, CharucoGeometryMatchesOpenCvCharucoBoard) {
  const Target t = Charuco7x5();
  const auto board = cv::aruco::CharucoBoard::create(t.cols + 1, t.rows + 1, static_cast<float>(t.square_size),
                                                     static_cast<float>(t.marker_size),
                                                     cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100));
  ASSERT_EQ(static_cast<int>(board->chessboardCorners.size()), NumCorners(t));
  for (int id = 0; id < NumCorners(t); ++id) {
    const cv::Point3f& p = board->chessboardCorners[id];
    EXPECT_NEAR(CornerPosition(t, id).x(), p.x - t.square_size, 1e-4) << id;
    EXPECT_NEAR(CornerPosition(t, id).y(), p.y - t.square_size, 1e-4) << id;
  }
  const std::vector<Quad> markers = MarkerQuads(t);
  ASSERT_EQ(markers.size(), board->ids.size());
  for (size_t k = 0; k < markers.size(); ++k) {
    const int id = board->ids[k];
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(markers[id][c].x(), board->objPoints[k][c].x - t.square_size, 1e-4) << id << " " << c;
      EXPECT_NEAR(markers[id][c].y(), board->objPoints[k][c].y - t.square_size, 1e-4) << id << " " << c;
    }
  }
}

// ArUco cells as OpenCV draws the marker at one pixel per cell; AprilTag cells from libapriltag's
// rendering: both must have a black border ring.
TEST(Target, MarkerCellsHaveABlackBorder) {
  for (const auto& [m, side] : {std::pair{ArucoMarkerCells("DICT_5X5_100", 3), 7}, std::pair{AprilTagCells("tag36h11", 17), 8}}) {
    ASSERT_EQ(m.side, side);
    ASSERT_EQ(m.black.size(), static_cast<size_t>(side * side));
    for (int i = 0; i < m.side; ++i) {
      EXPECT_TRUE(m.black[i]);                                    // top row
      EXPECT_TRUE(m.black[(m.side - 1) * m.side + i]);            // bottom row
      EXPECT_TRUE(m.black[i * m.side]);                           // left column
      EXPECT_TRUE(m.black[i * m.side + m.side - 1]);              // right column
    }
  }
}

TEST(Target, CheckTargetNamesTheFieldAndTheFix) {
  struct Case {
    std::function<void(Target*)> edit;
    std::string field, phrase;
  };
  const std::vector<Case> cases = {
      {[](Target* t) { t->rows = 1; }, "rows", "must be 2 to 1000 inner corners"},
      {[](Target* t) { t->square_size = -1; }, "square_size", "must be a positive length"},
      {[](Target* t) { t->square_size = std::nan(""); }, "square_size", "must be a positive length"},
      {[](Target* t) { t->margin = 5; }, "margin", "narrower than half a square"},
      {[](Target* t) { t->rows = 200, t->cols = 200; }, "rows", "more than 10000"},
      {[](Target* t) { t->rows = 2, t->cols = 2; }, "cols", "too small"},
  };
  for (const Case& c : cases) {
    Target t = Chessboard9x6();
    c.edit(&t);
    const auto problem = CheckTarget(t);
    ASSERT_TRUE(problem) << c.phrase;
    EXPECT_EQ(problem->field, c.field);
    EXPECT_NE(problem->reason.find(c.phrase), std::string::npos) << problem->reason;
    EXPECT_FALSE(problem->fix.empty());
  }
  Target charuco = Charuco7x5();
  charuco.marker_size = 27;  // 0.9 of the square: OpenCV's boards have such markers
  EXPECT_FALSE(CheckTarget(charuco).has_value());
  charuco.marker_size = 30;  // fills the square: no white square around it
  ASSERT_TRUE(CheckTarget(charuco).has_value());
  EXPECT_EQ(CheckTarget(charuco)->field, "marker_size");
  charuco = Charuco7x5();
  charuco.first_id = 90;  // markers 90 … 113 of DICT_5X5_100's 100
  ASSERT_TRUE(CheckTarget(charuco).has_value());
  EXPECT_EQ(CheckTarget(charuco)->field, "first_id");
  charuco = Charuco7x5();
  charuco.dictionary = "DICT_4X4_50";
  charuco.rows = charuco.cols = 11;  // 144 squares, 72 markers
  EXPECT_EQ(CheckTarget(charuco)->field, "dictionary");
  charuco.dictionary = "DICT_9X9";
  EXPECT_NE(CheckTarget(charuco)->fix.find("DICT_5X5_1000"), std::string::npos);
  Target grid = AprilGrid6x4();
  grid.tag_gap = 5;  // less than two cells of 30/8 = 3.75
  EXPECT_EQ(CheckTarget(grid)->field, "tag_gap");
  grid = AprilGrid6x4();
  grid.first_id = 570;  // 570 + 24 > 587 codes
  EXPECT_EQ(CheckTarget(grid)->field, "first_id");
  grid.first_id = 0;
  grid.family = "tag49h12";
  EXPECT_EQ(CheckTarget(grid)->field, "family");
}

TEST(TargetIo, RoundTripsEveryType) {
  for (const Target& t : {Chessboard9x6(), Charuco7x5(), AprilGrid6x4()}) {
    const std::string text = DumpJson(TargetToJson(t, Provenance{"test", {}, std::nullopt}));
    const Target back = TargetFromJson(JsonDocument::Parse(text, "t.json"));
    EXPECT_EQ(back.type, t.type);
    EXPECT_EQ(back.rows, t.rows);
    EXPECT_EQ(back.cols, t.cols);
    EXPECT_EQ(back.square_size, t.square_size);
    EXPECT_EQ(back.marker_size, t.marker_size);
    EXPECT_EQ(back.dictionary, t.dictionary);
    EXPECT_EQ(back.tag_size, t.tag_size);
    EXPECT_EQ(back.tag_gap, t.tag_gap);
    EXPECT_EQ(back.family, t.family);
    EXPECT_EQ(back.margin, t.margin);
    EXPECT_EQ(DumpJson(TargetToJson(back, Provenance{"test", {}, std::nullopt})), text);
  }
}

TEST(TargetIo, RefusesFieldsOfAnotherTypeAndBadValues) {
  using testing::ErrorOf;
  const std::string head = R"({"format": "vstcal/target@1", "length_unit": "mm", "rows": 6, "cols": 9, )";
  EXPECT_EQ(ErrorOf([&] { TargetFromJson(JsonDocument::Parse(head + R"("type": "chessboard", "square_size": 25, "marker_size": 18})", "t.json")); }),
            "t.json: marker_size: is not a field of a chessboard target; remove it, or set \"type\" to the board's type (charuco has it)");
  EXPECT_EQ(ErrorOf([&] { TargetFromJson(JsonDocument::Parse(head + R"("type": "chessbord", "square_size": 25})", "t.json")); }),
            "t.json: type: unknown value \"chessbord\"; use one of \"chessboard\", \"charuco\", \"apriltag-grid\", \"aprilgrid\"");
  EXPECT_EQ(ErrorOf([&] { TargetFromJson(JsonDocument::Parse(head + R"("type": "charuco", "square_size": 25})", "t.json")); }),
            "t.json: marker_size: missing field; add \"marker_size\"");
  EXPECT_EQ(ErrorOf([&] { TargetFromJson(JsonDocument::Parse(head + R"("type": "chessboard", "square_size": 0})", "t.json")); }),
            "t.json: square_size: must be a positive length, got 0; give the printed size");
  // Without "margin" the default is one square, which CheckTarget accepts.
  EXPECT_EQ(TargetFromJson(JsonDocument::Parse(head + R"("type": "chessboard", "square_size": 25})", "t.json")).margin, 25);
}

// Exact areas: a square centred on a chessboard corner, at any rotation, is half black (the four
// quadrants are point-symmetric about the corner); axis-aligned boxes have areas by hand.
TEST(Pattern, AreasAreExact) {
  const Pattern pattern = TargetPattern(Chessboard9x6());
  for (const double angle : {0.0, 0.1, 0.7, 1.3}) {
    std::array<Eigen::Vector2d, 4> quad;
    for (int k = 0; k < 4; ++k) {
      const double a = angle + k * kPi / 2;
      quad[k] = Eigen::Vector2d(50, 75) + 7.0 * Eigen::Vector2d(std::cos(a), std::sin(a));  // corner (2, 3)
    }
    const double area = std::abs(SignedArea(quad));
    EXPECT_NEAR(pattern.BlackArea(quad), 0.5 * area, 1e-9 * area) << angle;
    EXPECT_NEAR(pattern.SheetArea(quad), area, 1e-9 * area);
  }
  // A box from the middle of square (1, 1) (black: i + j even) into (2, 1) (white): x ∈ [−12.5, 10].
  const std::array<Eigen::Vector2d, 4> box = {Eigen::Vector2d(-12.5, -20), Eigen::Vector2d(10, -20), Eigen::Vector2d(10, -5),
                                              Eigen::Vector2d(-12.5, -5)};
  EXPECT_NEAR(pattern.BlackArea(box), 12.5 * 15, 1e-9);
  // Half off the sheet (x0 = −50): only the part on the sheet counts.
  const std::array<Eigen::Vector2d, 4> edge = {Eigen::Vector2d(-60, 0), Eigen::Vector2d(-40, 0), Eigen::Vector2d(-40, 10),
                                               Eigen::Vector2d(-60, 10)};
  EXPECT_NEAR(pattern.SheetArea(edge), 100, 1e-9);
  EXPECT_NEAR(pattern.BlackArea(edge), 0, 1e-12);  // the margin is white
}

// The SVG's size is the sheet's in millimetres with a matching viewBox, and every black rectangle
// of the pattern is one subpath.
TEST(TargetDrawing, SvgHasThePhysicalSize) {
  Target t = Chessboard9x6();
  t.length_unit = LengthUnit::kCentimetre;
  t.square_size = 2.5;
  t.margin = 2.5;
  const std::string svg = TargetSvg(t);
  EXPECT_NE(svg.find("width=\"300mm\" height=\"225mm\" viewBox=\"0 0 300 225\""), std::string::npos);
  const std::regex subpath("M[0-9.]+ [0-9.]+H");
  EXPECT_EQ(std::distance(std::sregex_iterator(svg.begin(), svg.end(), subpath), std::sregex_iterator()), 35);  // 70 squares, half black
  EXPECT_NE(svg.find("M25 25H50V50H25Z"), std::string::npos);  // square (0, 0) at the margin, black
}

// At 25.4 dpi a pixel is 1 mm: a chessboard of 25 mm squares rasterises to exact 25 px squares.
// At 20 dpi a pixel is 1.27 mm and the pixel straddling a square's edge has its exact coverage.
TEST(TargetDrawing, PngIsTheExactCoverage) {
  const Target t = Chessboard9x6();
  const GrayImage exact = RasterizeTarget(t, 25.4);
  ASSERT_EQ(exact.width, 300);
  ASSERT_EQ(exact.height, 225);
  EXPECT_EQ(exact.at(10, 10), 255);  // margin
  EXPECT_EQ(exact.at(25, 25), 0);    // square (0, 0) spans [25, 50) px
  EXPECT_EQ(exact.at(49, 49), 0);
  EXPECT_EQ(exact.at(50, 25), 255);
  const GrayImage coarse = RasterizeTarget(t, 20);
  // Pixel 19 spans [24.13, 25.4) mm from the sheet's left: 0.4 mm of it is black square (0, 0).
  const double black = (25.4 - 25.0) / 1.27;
  EXPECT_EQ(coarse.at(19, 30), static_cast<int>(std::lround(255 * (1 - black))));
}

// The pHYs chunk states the DPI in pixels per metre; its CRC is checked with zlib's.
TEST(TargetDrawing, PngCarriesItsResolution) {
  const std::string png = EncodePng(GrayImage(4, 3, 128), 300);
  const size_t at = png.find("pHYs");
  ASSERT_NE(at, std::string::npos);
  auto be32 = [&](size_t i) {
    return (uint32_t(uint8_t(png[i])) << 24) | (uint32_t(uint8_t(png[i + 1])) << 16) | (uint32_t(uint8_t(png[i + 2])) << 8) | uint8_t(png[i + 3]);
  };
  EXPECT_EQ(be32(at - 4), 9u);
  EXPECT_EQ(be32(at + 4), 11811u);  // 300 / 0.0254
  EXPECT_EQ(be32(at + 8), 11811u);
  EXPECT_EQ(png[at + 12], 1);
  EXPECT_EQ(be32(at + 13), static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(png.data() + at), 13)));
  const cv::Mat decoded = cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(decoded.cols, 4);
  EXPECT_EQ(decoded.at<uint8_t>(2, 3), 128);
}

// The scale bar: a path "M x y h L" whose L, in the SVG's user units, is the stated length in mm;
// the user units are millimetres (width in mm equals the viewBox's width). 9×6 inner corners of
// 25 mm squares: a 250 mm wide pattern holds a 200 mm bar; 5 mm squares (50 mm pattern): 50 mm.
TEST(TargetDrawing, SvgScaleBarHasItsStatedLengthInMillimetres) {
  for (const auto& [square, bar] : {std::pair{25.0, 200.0}, std::pair{5.0, 50.0}}) {
    Target t = Chessboard9x6();
    t.square_size = t.margin = square;
    const std::string svg = TargetSvg(t);
    std::smatch size, line, stated;
    ASSERT_TRUE(std::regex_search(svg, size, std::regex("width=\"([0-9.]+)mm\" height=\"[0-9.]+mm\" viewBox=\"0 0 ([0-9.]+) ")));
    EXPECT_EQ(std::stod(size[1]), std::stod(size[2]));  // one user unit is one millimetre
    ASSERT_TRUE(std::regex_search(svg, stated, std::regex("id=\"scale-bar\" data-length-mm=\"([0-9.]+)\"")));
    ASSERT_TRUE(std::regex_search(svg, line, std::regex("id=\"scale-bar-line\" d=\"M([0-9.]+) ([0-9.]+)h([0-9.]+)\"")));
    EXPECT_EQ(std::stod(stated[1]), bar);
    EXPECT_EQ(std::stod(line[3]), bar);
    EXPECT_NE(svg.find(">" + std::to_string(static_cast<int>(bar)) + " mm (check with a ruler)</text>"), std::string::npos);
    // In the bottom margin, below the pattern (which ends at margin + 7 squares) and on the sheet.
    EXPECT_GT(std::stod(line[2]), 8 * square);
    EXPECT_LT(std::stod(line[2]), 9 * square);
    EXPECT_EQ(std::stod(line[1]), square);  // starts at the pattern's left edge
    // Eleven ticks, the end ones at the bar's ends.
    std::smatch ticks;
    ASSERT_TRUE(std::regex_search(svg, ticks, std::regex("id=\"scale-bar-ticks\" d=\"([^\"]+)\"")));
    const std::string d = ticks[1];
    EXPECT_EQ(std::count(d.begin(), d.end(), 'M'), 11);
    EXPECT_NE(d.find("M" + line[1].str() + " "), std::string::npos);
    const double end = std::stod(line[1]) + bar;
    char end_text[32];
    std::snprintf(end_text, sizeof end_text, "M%g ", end);
    EXPECT_NE(d.find(end_text), std::string::npos);
  }
}

// Fitting to paper, by hand. 6 × 9 inner corners with the default margin (one square): the sheet
// is (9 + 3)·s across and (6 + 3)·s down. A4 portrait (210 across, 297 down): s ≤ min(210/12,
// 297/9) = 17.5; landscape (297 across, 210 down): s ≤ min(297/12, 210/9) = 23.33… → 23.3 (0.1 mm
// steps): landscape is chosen. Letter landscape: min(279.4/12, 215.9/9) = 23.283 → 23.2.
TEST(Paper, FitsAChessboardToA4AndLetter) {
  Target t = Chessboard9x6();
  t.square_size = 0;
  const std::optional<PaperFit> a4 = FitToPaper(t, {}, *PaperFromName("a4"));
  ASSERT_TRUE(a4);
  EXPECT_EQ(a4->size, 23.3);
  EXPECT_TRUE(a4->landscape);
  EXPECT_NEAR(a4->sheet_width_mm, 12 * 23.3, 1e-9);
  EXPECT_NEAR(a4->sheet_height_mm, 9 * 23.3, 1e-9);
  const std::optional<PaperFit> letter = FitToPaper(t, {}, *PaperFromName("Letter"));
  ASSERT_TRUE(letter);
  EXPECT_EQ(letter->size, 23.2);
  EXPECT_TRUE(letter->landscape);
  // A tall strip, 20 × 2 inner corners: portrait wins: 5·s ≤ 210 → 42 vs 23·s ≤ 297 → 12.91…;
  // landscape: 5·s ≤ 297, 23·s ≤ 210 → 9.13…: portrait, 12.9.
  t.rows = 20;
  t.cols = 2;
  const std::optional<PaperFit> strip = FitToPaper(t, {}, *PaperFromName("a4"));
  ASSERT_TRUE(strip);
  EXPECT_EQ(strip->size, 12.9);
  EXPECT_FALSE(strip->landscape);
}

// A margin given as a length stays fixed: 6 × 9 with a 10 mm margin on A4 landscape:
// 10·s + 20 ≤ 297 → 27.7, 7·s + 20 ≤ 210 → 27.14… → 27.1. A custom 100x100 sheet with 60 mm
// margins leaves no room. AprilTag 6 × 6 with the default gap (tag / 4) and margin (the gap): the
// sheet is 6·t + 5·t/4 + 2·t/4 = 7.75·t square; on A4: 210 / 7.75 = 27.096… → 27.0. In inches
// (0.001 in steps): 210 mm / 25.4 / 7.75 = 1.06680… → 1.066 in.
TEST(Paper, KeepsLengthsGivenOutrightAndFitsTagGrids) {
  Target t = Chessboard9x6();
  const std::optional<PaperFit> fixed = FitToPaper(t, {.margin = 10, .tag_gap = {}, .marker_size = {}}, *PaperFromName("a4"));
  ASSERT_TRUE(fixed);
  EXPECT_EQ(fixed->size, 27.1);
  EXPECT_TRUE(fixed->landscape);
  EXPECT_FALSE(FitToPaper(t, {.margin = 60, .tag_gap = {}, .marker_size = {}}, *PaperFromName("100x100")));
  Target grid = AprilGrid6x4();
  grid.rows = 6;
  const std::optional<PaperFit> tags = FitToPaper(grid, {}, *PaperFromName("A4"));
  ASSERT_TRUE(tags);
  EXPECT_EQ(tags->size, 27.0);
  EXPECT_EQ(WithSize(grid, tags->size, {}).tag_gap, 6.75);
  grid.length_unit = LengthUnit::kInch;
  EXPECT_EQ(FitToPaper(grid, {}, *PaperFromName("A4"))->size, 1.066);
}

TEST(Paper, NamesAndTheSmallestStandardSheet) {
  EXPECT_EQ(PaperFromName("LETTER")->width_mm, 215.9);
  const std::optional<Paper> custom = PaperFromName("350x250");
  ASSERT_TRUE(custom);
  EXPECT_EQ(custom->width_mm, 250);  // portrait: width ≤ height
  EXPECT_EQ(custom->height_mm, 350);
  for (const char* bad : {"a5", "x", "0x10", "10x", "-1x5", "10x10x10", "infx10"}) EXPECT_FALSE(PaperFromName(bad)) << bad;
  EXPECT_EQ(SmallestStandardPaper(300, 225)->name, "A3");   // the docs' old 6 × 9 board of 25 mm squares
  EXPECT_EQ(SmallestStandardPaper(275, 214)->name, "Letter");  // not A4 (210 wide) but Letter
  EXPECT_EQ(SmallestStandardPaper(200, 290)->name, "A4");
  EXPECT_FALSE(SmallestStandardPaper(430, 200));
}

TEST(TargetDrawing, RefusesHugeRasters) {
  EXPECT_THROW(RasterizeTarget(Chessboard9x6(), 20000), InputError);  // 236,000 × 177,000 px
}

}  // namespace
}  // namespace vstcal
