#include "vstcal/capture/target.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"

namespace vstcal {
namespace {

// OpenCV 4.6's cv::aruco::PREDEFINED_DICTIONARY_NAME in enum order (the index is the enum value).
constexpr std::array<MarkerFamily, 21> kAruco = {{
    {"DICT_4X4_50", 4, 50},        {"DICT_4X4_100", 4, 100},       {"DICT_4X4_250", 4, 250},
    {"DICT_4X4_1000", 4, 1000},    {"DICT_5X5_50", 5, 50},         {"DICT_5X5_100", 5, 100},
    {"DICT_5X5_250", 5, 250},      {"DICT_5X5_1000", 5, 1000},     {"DICT_6X6_50", 6, 50},
    {"DICT_6X6_100", 6, 100},      {"DICT_6X6_250", 6, 250},       {"DICT_6X6_1000", 6, 1000},
    {"DICT_7X7_50", 7, 50},        {"DICT_7X7_100", 7, 100},       {"DICT_7X7_250", 7, 250},
    {"DICT_7X7_1000", 7, 1000},    {"DICT_ARUCO_ORIGINAL", 5, 1024}, {"DICT_APRILTAG_16h5", 4, 30},
    {"DICT_APRILTAG_25h9", 5, 35}, {"DICT_APRILTAG_36h10", 6, 2320}, {"DICT_APRILTAG_36h11", 6, 587},
}};

// libapriltag's classic families: a 1-bit black border around `bits` × `bits` data cells, inside
// a 1-bit white ring (width_at_border = bits + 2, total_width = bits + 4).
constexpr std::array<MarkerFamily, 4> kAprilTag = {{
    {"tag36h11", 6, 587}, {"tag36h10", 6, 2320}, {"tag25h9", 5, 35}, {"tag16h5", 4, 30}}};

constexpr int kMaxCorners = 10000;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string Names(std::span<const MarkerFamily> families) {
  std::string out;
  for (const MarkerFamily& f : families) out += (out.empty() ? "" : ", ") + std::string(f.name);
  return out;
}

std::optional<TargetProblem> Positive(std::string_view field, double v) {
  if (std::isfinite(v) && v > 0) return std::nullopt;
  return TargetProblem{std::string(field), "must be a positive length, got " + Num(v), "give the printed size"};
}

// A board's side is at most limits::kMaxSyntheticScale in its length unit, as every synthetic
// scene's lengths: beyond it the sheet's size, the corners' coordinates and what the solvers square
// leave double precision (a square_size of 1e308 made a sheet of infinite width).
std::optional<TargetProblem> TooLarge(std::string_view field, double size, double cells, std::string_view unit) {
  const double side = size * cells;
  if (!(side > limits::kMaxSyntheticScale)) return std::nullopt;  // NaN and ≤ 0: Positive says what is wrong
  return TargetProblem{std::string(field),
                       Num(size) + " makes a board " + (std::isfinite(side) ? Num(side) : std::string("beyond 1e308")) + " " +
                           std::string(unit) + " wide, more than the " +
                           Num(limits::kMaxSyntheticScale) + " " + std::string(unit) + " vstcal computes with",
                       "give the printed size in the target's length unit (at most " + Num(limits::kMaxSyntheticScale / cells) + ")"};
}

}  // namespace

std::string_view TargetTypeName(TargetType type) {
  return NameOf(kTargetTypeNames, type);
}

std::optional<TargetType> TargetTypeFromName(std::string_view name) {
  return FromName(kTargetTypeNames, name);
}

std::span<const MarkerFamily> ArucoDictionaries() { return kAruco; }
std::span<const MarkerFamily> AprilTagFamilies() { return kAprilTag; }

const MarkerFamily* FindMarkerFamily(std::span<const MarkerFamily> families, std::string_view name) {
  for (const MarkerFamily& f : families) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

namespace {

// Kalibr's aprilgrid: tag36h11 only (Kalibr's detector reads no other family), ids 0 … N − 1.
std::optional<TargetProblem> CheckAprilGrid(const Target& t) {
  if (auto p = Positive("tag_size", t.tag_size)) return p;
  // Kalibr's generator takes a spacing in (0, 1]; below a tenth (one tag cell) the gaps blur shut.
  if (!(std::isfinite(t.tag_spacing) && t.tag_spacing >= 0.1 && t.tag_spacing <= 1)) {
    return TargetProblem{"tag_spacing", "must be a fraction of the tag size from 0.1 to 1 (Kalibr's tagSpacing), got " + Num(t.tag_spacing),
                         "measure the gap between two tags and divide by the tag's side (Kalibr's default is 0.3)"};
  }
  const MarkerFamily* f = FindMarkerFamily(kAprilTag, "tag36h11");
  if (t.rows * t.cols > f->num_codes) {
    return TargetProblem{"rows", "an aprilgrid of " + std::to_string(t.rows * t.cols) + " tags needs more than the " +
                                     std::to_string(f->num_codes) + " codes of tag36h11",
                         "use fewer tags"};
  }
  return std::nullopt;
}

}  // namespace

std::optional<TargetProblem> CheckTarget(const Target& t) {
  const bool tags = t.type == TargetType::kAprilTagGrid || t.type == TargetType::kAprilGrid;
  const int min_count = tags ? 1 : 2;
  const std::string what = tags ? "tags" : "inner corners";
  for (const auto& [field, n] : {std::pair<const char*, int>{"rows", t.rows}, {"cols", t.cols}}) {
    if (n < min_count || n > 1000) {
      return TargetProblem{field, "must be " + std::to_string(min_count) + " to 1000 " + what + ", got " + std::to_string(n),
                           tags ? "count the tags along each side" : "count the inner corners (where four squares meet) along each side"};
    }
  }
  if (!tags && t.rows * t.cols < 6) {
    return TargetProblem{"cols", "a board of " + std::to_string(t.rows * t.cols) + " inner corners is too small",
                         "use at least 2 × 3 inner corners (a view needs 6 corners)"};
  }
  if (NumCorners(t) > kMaxCorners) {
    return TargetProblem{"rows", std::to_string(NumCorners(t)) + " corners is more than " + std::to_string(kMaxCorners),
                         "use a smaller board"};
  }
  if (tags && t.rows * t.cols < 2) return TargetProblem{"cols", "a grid of one tag", "use at least 2 tags"};
  // The squares or tags before the margin, which defaults to one of them.
  const std::string_view unit = LengthUnitName(t.length_unit);
  if (auto p = tags ? TooLarge("tag_size", t.tag_size, 2.0 * std::max(t.rows, t.cols), unit)
                    : TooLarge("square_size", t.square_size, std::max(t.rows, t.cols) + 1.0, unit)) {
    return p;
  }
  if (!(std::isfinite(t.margin) && t.margin >= 0)) {
    return TargetProblem{"margin", "must be a length ≥ 0, got " + Num(t.margin), "give the white border's width"};
  }
  if (auto p = TooLarge("margin", t.margin, 2, unit)) return p;
  if (t.type == TargetType::kChessboard || t.type == TargetType::kCharuco) {
    if (auto p = Positive("square_size", t.square_size)) return p;
    if (t.margin < 0.5 * t.square_size) {
      return TargetProblem{"margin", "the white border (" + Num(t.margin) + ") is narrower than half a square (" +
                                         Num(0.5 * t.square_size) + "); the detectors need white around the board",
                           "give a margin of at least half a square (one square is best)"};
    }
  }
  if (t.type == TargetType::kCharuco) {
    const MarkerFamily* f = FindMarkerFamily(kAruco, t.dictionary);
    if (!f) return TargetProblem{"dictionary", "unknown ArUco dictionary \"" + t.dictionary + "\"", "use one of " + Names(kAruco)};
    if (auto p = Positive("marker_size", t.marker_size)) return p;
    // Any marker OpenCV's CharucoBoard can hold: smaller than its square, so that the black
    // squares' corners (the X-junctions) stay clear. OpenCV draws and reads markers up to 0.9 of
    // the square and more; a white gap under one marker cell only makes the markers harder to find.
    if (!(t.marker_size < t.square_size)) {
      return TargetProblem{"marker_size", Num(t.marker_size) + " fills a square of " + Num(t.square_size) +
                                              ": a ChArUco marker sits inside a white square, with white around it",
                           "give a marker_size < square_size (0.7 × square_size is usual)"};
    }
    const int markers = (t.rows + 1) * (t.cols + 1) / 2;
    if (t.first_id < 0 || static_cast<long>(t.first_id) + markers > f->num_codes) {
      if (t.first_id != 0) {
        return TargetProblem{"first_id", "markers " + std::to_string(t.first_id) + " … " + std::to_string(t.first_id + markers - 1) +
                                             " are not all in " + t.dictionary + " (ids 0 … " + std::to_string(f->num_codes - 1) + ")",
                             "use a smaller first_id, a larger dictionary or a smaller board"};
      }
    }
    if (markers > f->num_codes) {
      return TargetProblem{"dictionary", t.dictionary + " has " + std::to_string(f->num_codes) + " markers, the board needs " +
                                             std::to_string(markers),
                           "use a larger dictionary (e.g. DICT_5X5_1000) or a smaller board"};
    }
  }
  if (t.legacy && t.type != TargetType::kCharuco) {
    return TargetProblem{"legacy", "only a ChArUco board has OpenCV's legacy pattern, not a " + std::string(TargetTypeName(t.type)),
                         "remove it"};
  }
  if (t.type == TargetType::kAprilGrid) return CheckAprilGrid(t);
  if (tags) {
    const MarkerFamily* f = FindMarkerFamily(kAprilTag, t.family);
    if (!f) return TargetProblem{"family", "unknown AprilTag family \"" + t.family + "\"", "use one of " + Names(kAprilTag)};
    if (auto p = Positive("tag_size", t.tag_size)) return p;
    const double cell = t.tag_size / (f->bits + 2);
    if (!(std::isfinite(t.tag_gap) && t.tag_gap >= 2 * cell)) {
      return TargetProblem{"tag_gap", "the white between tags (" + Num(t.tag_gap) + ") is less than two tag cells (" +
                                          Num(2 * cell) + "): each tag needs its own white ring to be detected",
                           "give a tag_gap ≥ " + Num(2 * cell) + " (tag_size / 4 for tag36h11)"};
    }
    if (t.margin < cell) {
      return TargetProblem{"margin", "the white border (" + Num(t.margin) + ") is less than one tag cell (" + Num(cell) + ")",
                           "give a margin ≥ " + Num(cell)};
    }
    if (t.first_id < 0 || static_cast<long>(t.first_id) + static_cast<long>(t.rows) * t.cols > f->num_codes) {
      return TargetProblem{"first_id", "tags " + std::to_string(t.first_id) + " … " + std::to_string(t.first_id + t.rows * t.cols - 1) +
                                           " are not all in " + t.family + " (ids 0 … " + std::to_string(f->num_codes - 1) + ")",
                           "use a smaller first_id or fewer tags"};
    }
  }
  return std::nullopt;
}

int ArucoDictionaryIndex(std::string_view name) {
  for (size_t i = 0; i < kAruco.size(); ++i) {
    if (kAruco[i].name == name) return static_cast<int>(i);
  }
  VSTCAL_CHECK(false, "unknown ArUco dictionary " + std::string(name));
}

std::string DescribeTarget(const Target& t) {
  const std::string unit(LengthUnitName(t.length_unit));
  const std::string grid = std::to_string(t.cols) + "×" + std::to_string(t.rows);
  switch (t.type) {
    case TargetType::kChessboard: return "chessboard of " + grid + " inner corners, " + Num(t.square_size) + " " + unit + " squares";
    case TargetType::kCharuco:
      return "ChArUco board of " + grid + " inner corners, " + Num(t.square_size) + " " + unit + " squares, " + Num(t.marker_size) +
             " " + unit + " " + t.dictionary + " markers" + (t.legacy ? " (OpenCV's legacy pattern)" : "");
    case TargetType::kAprilTagGrid:
      return "AprilTag grid of " + grid + " " + t.family + " tags (ids from " + std::to_string(t.first_id) + "), " +
             Num(t.tag_size) + " " + unit + " tags";
    case TargetType::kAprilGrid:
      return "Kalibr aprilgrid of " + grid + " tag36h11 tags, " + Num(t.tag_size) + " " + unit + " tags, spacing " + Num(t.tag_spacing);
  }
  return "?";
}

int NumCorners(const Target& t) {
  const bool tags = t.type == TargetType::kAprilTagGrid || t.type == TargetType::kAprilGrid;
  const long n = static_cast<long>(std::max(t.rows, 0)) * std::max(t.cols, 0) * (tags ? 4 : 1);
  return static_cast<int>(std::min<long>(n, 1L << 30));
}

Eigen::Vector2d CornerPosition(const Target& t, int id) {
  VSTCAL_CHECK(id >= 0 && id < NumCorners(t), "corner id out of range");
  if (t.type == TargetType::kAprilGrid) {
    // Kalibr's grid of 2·rows × 2·cols corners, counted from the bottom-left with y up (target.h).
    const int r = id / (2 * t.cols), c = id % (2 * t.cols);
    const double pitch = (1 + t.tag_spacing) * t.tag_size;
    return Eigen::Vector2d((c / 2) * pitch + (c % 2) * t.tag_size, -((r / 2) * pitch + (r % 2) * t.tag_size));
  }
  if (t.type != TargetType::kAprilTagGrid) return Eigen::Vector2d((id % t.cols) * t.square_size, (id / t.cols) * t.square_size);
  const int tag = id / 4, k = id % 4;
  const double pitch = t.tag_size + t.tag_gap, s = t.tag_size;
  const Eigen::Vector2d origin((tag % t.cols) * pitch, (tag / t.cols) * pitch);
  constexpr std::array<std::array<int, 2>, 4> kCorner = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  return origin + s * Eigen::Vector2d(kCorner[k][0], kCorner[k][1]);
}

std::vector<TargetCorner> TargetCorners(const Target& t) {
  std::vector<TargetCorner> corners(NumCorners(t));
  for (int id = 0; id < NumCorners(t); ++id) corners[id] = {id, CornerPosition(t, id)};
  return corners;
}

std::vector<Quad> MarkerQuads(const Target& t) {
  std::vector<Quad> quads;
  auto square = [&](double x0, double y0, double side) {
    quads.push_back({Eigen::Vector2d(x0, y0), Eigen::Vector2d(x0 + side, y0), Eigen::Vector2d(x0 + side, y0 + side),
                     Eigen::Vector2d(x0, y0 + side)});
  };
  if (t.type == TargetType::kCharuco) {
    // The white squares row by row, as OpenCV numbers its markers.
    const double S = t.square_size, inset = 0.5 * (t.square_size - t.marker_size);
    for (int j = 0; j <= t.rows; ++j) {
      for (int i = 0; i <= t.cols; ++i) {
        if (!IsBlackSquare(t, i, j)) square((i - 1) * S + inset, (j - 1) * S + inset, t.marker_size);
      }
    }
  } else if (t.type == TargetType::kAprilTagGrid) {
    const double pitch = t.tag_size + t.tag_gap;
    for (int r = 0; r < t.rows; ++r) {
      for (int c = 0; c < t.cols; ++c) square(c * pitch, r * pitch, t.tag_size);
    }
  } else if (t.type == TargetType::kAprilGrid) {
    // Tag id = tr·cols + tc from the bottom-left; its top edge is at Y = −(tr·pitch + s).
    const double pitch = (1 + t.tag_spacing) * t.tag_size;
    for (int id = 0; id < t.rows * t.cols; ++id) square((id % t.cols) * pitch, -((id / t.cols) * pitch + t.tag_size), t.tag_size);
  }
  return quads;
}

std::vector<Rect> AprilGridJunctionSquares(const Target& t) {
  std::vector<Rect> squares;
  if (t.type != TargetType::kAprilGrid) return squares;
  // Between tags i − 1 and i along X the gap is [i·pitch − g, i·pitch]; likewise along Kalibr's y.
  const double pitch = (1 + t.tag_spacing) * t.tag_size, g = t.tag_spacing * t.tag_size;
  for (int j = 0; j <= t.rows; ++j) {
    for (int i = 0; i <= t.cols; ++i) squares.push_back(Rect{i * pitch - g, -(j * pitch), i * pitch, -(j * pitch - g)});
  }
  return squares;
}

Rect PatternExtent(const Target& t) {
  if (t.type == TargetType::kAprilGrid) {
    // The tags and the junction squares around them, which reach a gap beyond the outer tags.
    const double pitch = (1 + t.tag_spacing) * t.tag_size, g = t.tag_spacing * t.tag_size;
    return Rect{-g, -(t.rows * pitch), t.cols * pitch, g};
  }
  if (t.type != TargetType::kAprilTagGrid) {
    return Rect{-t.square_size, -t.square_size, t.cols * t.square_size, t.rows * t.square_size};
  }
  const double pitch = t.tag_size + t.tag_gap;
  return Rect{0, 0, (t.cols - 1) * pitch + t.tag_size, (t.rows - 1) * pitch + t.tag_size};
}

Rect SheetExtent(const Target& t) {
  const Rect p = PatternExtent(t);
  return Rect{p.x0 - t.margin, p.y0 - t.margin, p.x1 + t.margin, p.y1 + t.margin};
}

bool IsBlackSquare(const Target& t, int i, int j) {
  const bool swapped = t.type == TargetType::kCharuco && t.legacy && (t.rows + 1) % 2 == 0;
  return ((i + j) % 2 == 0) != swapped;
}

bool IsHalfTurnSymmetric(const Target& t) { return t.type == TargetType::kChessboard && (t.rows + t.cols) % 2 == 0; }

}  // namespace vstcal
