#include "vstcal/formats/capture/target_io.h"

#include <array>
#include <cstdio>

#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr std::string_view kTargetFormat = "vstcal/target@1";

// The fields of each type beyond format, type, length_unit, rows, cols, margin.
struct TypeFields {
  TargetType type;
  std::array<std::string_view, 5> fields;
};
constexpr std::array<TypeFields, 4> kTypeFields = {{
    {TargetType::kChessboard, {"square_size"}},
    {TargetType::kCharuco, {"square_size", "marker_size", "dictionary", "first_id", "legacy"}},
    {TargetType::kAprilTagGrid, {"tag_size", "tag_gap", "family", "first_id"}},
    {TargetType::kAprilGrid, {"tag_size", "tag_spacing"}},
}};

bool HasField(TargetType type, std::string_view field) {
  for (const TypeFields& t : kTypeFields) {
    if (t.type != type) continue;
    for (std::string_view f : t.fields) {
      if (f == field) return true;
    }
  }
  return false;
}

}  // namespace

Target TargetFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kTargetFormat);
  Target t;
  t.type = *TargetTypeFromName(root.at("type").OneOf({"chessboard", "charuco", "apriltag-grid", "aprilgrid"}));
  // A field of another type means the file describes another board than it says: refuse it
  // rather than print or detect the wrong thing.
  for (const TypeFields& other : kTypeFields) {
    for (std::string_view f : other.fields) {
      if (f.empty() || HasField(t.type, f)) continue;
      if (auto node = root.find(f)) {
        node->Fail("is not a field of a " + std::string(TargetTypeName(t.type)) + " target",
                   "remove it, or set \"type\" to the board's type (" + std::string(TargetTypeName(other.type)) + " has it)");
      }
    }
  }
  t.length_unit = ReadLengthUnit(root.at("length_unit"));
  t.rows = root.at("rows").Integer();
  t.cols = root.at("cols").Integer();
  if (t.type == TargetType::kAprilTagGrid) {
    t.tag_size = root.at("tag_size").Number();
    t.tag_gap = root.at("tag_gap").Number();
    t.family = root.at("family").String();
    t.first_id = root.at("first_id").Integer();
  } else if (t.type == TargetType::kAprilGrid) {
    t.tag_size = root.at("tag_size").Number();
    t.tag_spacing = root.at("tag_spacing").Number();
    t.family = "tag36h11";
  } else {
    t.square_size = root.at("square_size").Number();
  }
  if (t.type == TargetType::kCharuco) {
    t.marker_size = root.at("marker_size").Number();
    t.dictionary = root.at("dictionary").String();
    // Optional: boards OpenCV made carry ids 0, 1, … unless their maker offset them.
    if (const auto first = root.find("first_id")) t.first_id = first->Integer();
    // Optional: boards OpenCV drew before 4.6 (target.h).
    if (const auto legacy = root.find("legacy")) t.legacy = legacy->Boolean();
  }
  const auto margin = root.find("margin");
  t.margin = margin ? margin->Number()
                    : t.type == TargetType::kAprilTagGrid ? t.tag_gap
                    : t.type == TargetType::kAprilGrid    ? t.tag_spacing * t.tag_size
                                                          : t.square_size;
  if (const auto problem = CheckTarget(t)) {
    const std::string field = problem->field == "margin" && !margin ? "" : problem->field;
    (field.empty() ? root : root.at(field)).Fail(problem->reason, problem->fix);
  }
  return t;
}

Target ReadTarget(const std::filesystem::path& path) { return TargetFromJson(JsonDocument::Load(path)); }

OrderedJson TargetToJson(const Target& t, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kTargetFormat;
  j["type"] = TargetTypeName(t.type);
  j["length_unit"] = LengthUnitName(t.length_unit);
  j["rows"] = t.rows;
  j["cols"] = t.cols;
  if (t.type == TargetType::kAprilTagGrid) {
    j["tag_size"] = t.tag_size;
    j["tag_gap"] = t.tag_gap;
    j["family"] = t.family;
    j["first_id"] = t.first_id;
  } else if (t.type == TargetType::kAprilGrid) {
    j["tag_size"] = t.tag_size;
    j["tag_spacing"] = t.tag_spacing;
  } else {
    j["square_size"] = t.square_size;
  }
  if (t.type == TargetType::kCharuco) {
    j["marker_size"] = t.marker_size;
    j["dictionary"] = t.dictionary;
    if (t.first_id != 0) j["first_id"] = t.first_id;
    if (t.legacy) j["legacy"] = true;
  }
  j["margin"] = t.margin;
  const Rect sheet = SheetExtent(t);
  j["sheet"] = {{"width", sheet.width()}, {"height", sheet.height()}};
  j["board_frame"] = t.type == TargetType::kAprilGrid
                         ? "Kalibr's aprilgrid frame turned half a turn about its x axis: origin at the bottom-left corner of tag 0 "
                           "(the bottom-left tag), X right along cols, Y up the sheet negated (the board lies at Y <= 0), Z into the "
                           "board; tag id tr*cols + tc from the bottom-left; corner r*(2*cols) + c of Kalibr's 2*rows x 2*cols "
                           "corner grid (r from the bottom) at (c/2*pitch + c%2*tag_size, -(r/2*pitch + r%2*tag_size)), pitch = "
                           "(1 + tag_spacing)*tag_size"
                     : t.type == TargetType::kAprilTagGrid
                         ? "origin at the top-left corner of tag (0, 0)'s black square; X right along cols, Y down along "
                           "rows, Z into the board; tag (r, c) has id first_id + r*cols + c and corners 4*(r*cols + c) + "
                           "k, k = 0 top-left, 1 top-right, 2 bottom-right, 3 bottom-left"
                     : std::string("origin at the top-left inner corner; X right along cols, Y down along rows, Z into the board; "
                                   "corner (r, c) has id r*cols + c at (c, r) * square_size; the top-left square is ") +
                           (IsBlackSquare(t, 0, 0) ? "black" : "white (OpenCV's legacy ChArUco pattern)");
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
