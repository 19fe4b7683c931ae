#include "vstcal/formats/capture/kalibr_target.h"

#include <cmath>

#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

constexpr std::string_view kWhat = "a Kalibr target YAML";

// A count, required: `fix` says what to write.
int Count(const YamlField& f, std::string_view fix) {
  f.Require(fix);
  return f.Integer(fix);
}

// Kalibr's key of each target field CheckTarget may name.
std::string KalibrKey(TargetType type, const std::string& field) {
  const bool grid = type == TargetType::kAprilGrid;
  if (field == "rows") return grid ? "tagRows" : "targetRows";
  if (field == "cols") return grid ? "tagCols" : "targetCols";
  if (field == "tag_size") return "tagSize";
  if (field == "tag_spacing") return "tagSpacing";
  if (field == "square_size") return "rowSpacingMeters";
  return "";  // margin: vstcal's default, not in the file
}

}  // namespace

Target KalibrTargetFromText(const std::string& text, const std::string& name) {
  const YamlNode root = ParseYamlMap(text, name, kWhat);
  const YamlField top = RootField(root, name);
  const YamlField type = top.Member("target_type");
  type.Require("add target_type: 'aprilgrid' (or 'checkerboard')");
  const std::string kind = type.String();
  Target t;
  t.length_unit = LengthUnit::kMetre;
  if (kind == "aprilgrid") {
    t.type = TargetType::kAprilGrid;
    t.family = "tag36h11";
    t.cols = Count(top.Member("tagCols"), "add tagCols: the number of tags across the board (x)");
    t.rows = Count(top.Member("tagRows"), "add tagRows: the number of tags up the board (y)");
    const YamlField size = top.Member("tagSize"), spacing = top.Member("tagSpacing");
    size.Require("add tagSize: the side of a tag's black square in metres");
    spacing.Require("add tagSpacing: the gap between tags as a fraction of tagSize (e.g. 0.3)");
    t.tag_size = size.Number();
    t.tag_spacing = spacing.Number();
    t.margin = std::isfinite(t.tag_size * t.tag_spacing) ? t.tag_size * t.tag_spacing : 0;
  } else if (kind == "checkerboard") {
    t.type = TargetType::kChessboard;
    t.cols = Count(top.Member("targetCols"), "add targetCols: the number of inner corners across the board");
    t.rows = Count(top.Member("targetRows"), "add targetRows: the number of inner corners down the board");
    const YamlField row = top.Member("rowSpacingMeters"), col = top.Member("colSpacingMeters");
    row.Require("add rowSpacingMeters: the side of a square in metres");
    col.Require("add colSpacingMeters: the side of a square in metres");
    t.square_size = row.Number();
    if (col.Number() != t.square_size) {
      col.Fail("differs from rowSpacingMeters: vstcal's chessboard has square squares",
               "measure the squares; give both spacings the same side");
    }
    t.margin = std::isfinite(t.square_size) ? t.square_size : 0;
  } else if (kind == "circlegrid") {
    type.Fail("vstcal has no circle grid target", "print a chessboard, ChArUco board or aprilgrid (calib-capture target)");
  } else {
    type.Fail("unknown Kalibr target type \"" + kind + "\"", "write aprilgrid or checkerboard");
  }
  if (const auto problem = CheckTarget(t)) {
    const std::string key = KalibrKey(t.type, problem->field);
    (key.empty() ? top : top.Member(key)).Fail(problem->reason, problem->fix);
  }
  return t;
}

Target ReadKalibrTarget(const std::filesystem::path& path) {
  return KalibrTargetFromText(ReadInputFile(path, kWhat, limits::kMaxOpenCvYamlBytes, "Kalibr target YAML"), path.string());
}

}  // namespace vstcal
