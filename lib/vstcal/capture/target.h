// A calibration target: what is printed, and where each of its corners lies in the board frame
// (docs/formats.md#target, the vstcal/target@1 format).
//
// Board frame (all types): Z = 0 on the printed face, X to the right and Y down as the sheet is
// read, Z into the board (right-handed, as the camera frame: a camera facing the print sees X
// right and Y down). Lengths in the target's length unit.
//  - chessboard, charuco: `rows` × `cols` inner corners; the origin is the top-left inner corner,
//    corner id = r·cols + c at (c·square_size, r·square_size). The (rows + 1) × (cols + 1)
//    squares alternate, the top-left one black (OpenCV's pattern and ChArUco board). A ChArUco
//    board has an ArUco marker (1-bit black border) centred in every white square, ids first_id,
//    first_id + 1, … row by row, exactly OpenCV's cv::aruco::CharucoBoard (origin shifted to the
//    first corner). `legacy`: OpenCV's pattern before 4.6 (CharucoBoard::setLegacyPattern(true)
//    from 4.8 on): with an even number of square rows (rows odd) the colours swap, the top-left
//    square white and holding marker first_id; otherwise the same board (IsBlackSquare).
//  - apriltag-grid: `rows` × `cols` AprilTags (libapriltag's families), tag id first_id +
//    r·cols + c, each a black square of side tag_size (its 1-bit black border included) with
//    tag_gap of white between neighbours. The origin is the top-left corner of the first tag's
//    black square; tag (r, c)'s corners are ids 4·(r·cols + c) + k, k = 0 top-left, 1 top-right,
//    2 bottom-right, 3 bottom-left, at (c·pitch, r·pitch) + {(0,0), (s,0), (s,s), (0,s)},
//    pitch = tag_size + tag_gap.
//  - aprilgrid: Kalibr's aprilgrid (ethz-asl/kalibr, GridCalibrationTargetAprilgrid and
//    kalibr_create_target_pdf): `rows` × `cols` tag36h11 tags of side tag_size with a two-cell
//    black border (10 × 10 cells), tag_spacing · tag_size apart, and a black square of that side
//    at every junction between four tag corners (the outer ones included), so that every tag
//    corner is an X-junction. Kalibr numbers from the bottom-left as the sheet is read, y up: tag
//    id = tr·cols + tc (tr the tag row from the bottom), and the 2·rows × 2·cols tag corners as a
//    grid, id = r·(2·cols) + c (r from the bottom), at Kalibr's (x, y) = ((c/2)·p + (c%2)·s,
//    (r/2)·p + (r%2)·s), p = (1 + tag_spacing)·s, integer division. vstcal keeps these ids and
//    Kalibr's origin (the bottom-left corner of tag 0) and turns Kalibr's frame half a turn about
//    its x axis, so that Y points down the sheet as for every other target:
//    (X, Y, Z) = (x, −y, −z); the board lies at Y ≤ 0. Each tag is printed as OpenCV's
//    DICT_APRILTAG_36h11 marker of that id (drawn with a 2-cell border) turned half a turn, as
//    Kalibr's generator prints its tag36h11 codes.
// `margin` is white paper around the pattern, part of the printed sheet.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/capture/pattern.h"
#include "vstcal/core/units.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class TargetType { kChessboard, kCharuco, kAprilTagGrid, kAprilGrid };
inline constexpr EnumNames<TargetType, 4> kTargetTypeNames = {{{TargetType::kChessboard, "chessboard"},
                                                               {TargetType::kCharuco, "charuco"},
                                                               {TargetType::kAprilTagGrid, "apriltag-grid"},
                                                               {TargetType::kAprilGrid, "aprilgrid"}}};

std::string_view TargetTypeName(TargetType type);  // "chessboard", "charuco", "apriltag-grid", "aprilgrid"
std::optional<TargetType> TargetTypeFromName(std::string_view name);

struct Target {
  TargetType type = TargetType::kChessboard;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  int rows = 0;               // inner corners (chessboard, charuco) or tags (apriltag-grid, aprilgrid) along Y
  int cols = 0;               // … along X
  double square_size = 0;     // chessboard, charuco: side of a square
  double marker_size = 0;     // charuco: side of an ArUco marker (its black border included)
  std::string dictionary;     // charuco: OpenCV's predefined dictionary, e.g. "DICT_5X5_100"
  double tag_size = 0;        // apriltag-grid, aprilgrid: side of a tag's black square
  double tag_gap = 0;         // apriltag-grid: white between neighbouring tags' black squares
  std::string family;         // apriltag-grid: "tag36h11" (aprilgrid: always tag36h11)
  int first_id = 0;           // apriltag-grid: id of tag (0, 0)
  double margin = 0;          // white border of the sheet around the pattern
  double tag_spacing = 0;     // aprilgrid: gap between tags (and side of the junction squares) / tag_size
  bool legacy = false;        // charuco: OpenCV's legacy pattern (boards made before OpenCV 4.6)
};

// Kalibr's aprilgrid tag: its cells across, border included, and its black border's cells.
inline constexpr int kAprilGridCells = 10;    // 6 data cells and a 2-cell black border each side
inline constexpr int kAprilGridBorderCells = 2;

// A dictionary or tag family vstcal can print and detect.
struct MarkerFamily {
  std::string_view name;
  int bits;       // data bits per side (ArUco: marker bits; AprilTag: family's width between borders)
  int num_codes;  // markers (ArUco) or tags (AprilTag) in the family
};
// OpenCV's predefined ArUco dictionaries (cv::aruco::PREDEFINED_DICTIONARY_NAME, same order).
std::span<const MarkerFamily> ArucoDictionaries();
// The libapriltag families with a 1-bit black border inside a white ring (classic layout).
std::span<const MarkerFamily> AprilTagFamilies();
const MarkerFamily* FindMarkerFamily(std::span<const MarkerFamily> families, std::string_view name);
// OpenCV's cv::aruco::PREDEFINED_DICTIONARY_NAME value of a dictionary of ArucoDictionaries().
int ArucoDictionaryIndex(std::string_view name);

// What is wrong with a target: the field (a target@1 key, e.g. "square_size"), the reason and the
// fix. The reader reports it against the file; calib-capture target against the flag --<field>.
struct TargetProblem {
  std::string field;
  std::string reason;
  std::string fix;
};
// nullopt when the target can be printed and detected: sizes positive, at least 2×2 inner corners
// (1×1 tags … well, 2 tags), markers that fit their squares with a white ring, enough codes in
// the dictionary, at most 10,000 corners, and ids within the family.
std::optional<TargetProblem> CheckTarget(const Target& target);

struct TargetCorner {
  int id = 0;
  Eigen::Vector2d xy;  // board frame, length unit (Z = 0)
};
// Every corner of the target, by increasing id.
std::vector<TargetCorner> TargetCorners(const Target& target);
int NumCorners(const Target& target);
// The board-frame position of corner `id` (0 ≤ id < NumCorners).
Eigen::Vector2d CornerPosition(const Target& target, int id);

// The squares of the markers (ChArUco, index = marker id) or tags (AprilTag grid, index =
// r·cols + c; aprilgrid, index = Kalibr's tag id) in the board frame: corners top-left, top-right, bottom-right, bottom-left (the
// marker's black border included). Empty for a chessboard.
using Quad = std::array<Eigen::Vector2d, 4>;
std::vector<Quad> MarkerQuads(const Target& target);

// The printed pattern's extent (squares or tags, no margin) and the sheet (with the margin).
Rect PatternExtent(const Target& target);
Rect SheetExtent(const Target& target);

// One line for messages and summaries: "chessboard of 9×6 inner corners, 25 mm squares".
std::string DescribeTarget(const Target& target);

// Kalibr's aprilgrid: the black squares at the junctions between tag corners ((rows + 1) ×
// (cols + 1) of them, side tag_spacing · tag_size). Empty for the other types.
std::vector<Rect> AprilGridJunctionSquares(const Target& target);

// Whether square (i, j) of a chessboard or ChArUco board is black: i = 0 … cols along X, j = 0 …
// rows along Y, square (i, j) spanning [(i − 1)·S, i·S] × [(j − 1)·S, j·S]. Black where i + j is
// even, except on a legacy ChArUco board with an even number of square rows (rows odd), where the
// colours swap: OpenCV ≥ 4.8's createCharucoBoard with legacyPattern, which reproduces the boards
// OpenCV drew before 4.6 (opencv/opencv#23152). The ChArUco markers sit in the white squares.
bool IsBlackSquare(const Target& target, int i, int j);

// True for a chessboard that looks the same after a half turn (rows + cols even): its corners can
// be numbered from either end, and only the view's geometry can tell which (docs/tools/calib-capture.md#orientation).
bool IsHalfTurnSymmetric(const Target& target);

}  // namespace vstcal
