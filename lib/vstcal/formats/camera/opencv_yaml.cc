#include "vstcal/formats/camera/opencv_yaml.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <regex>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

constexpr std::string_view kCameraMatrix = "camera_matrix";
constexpr std::string_view kDistortion = "distortion_coefficients";
// cv::FileStorage files have no standard key for the lens model: vstcal writes and reads
// `distortion_model: fisheye` (ROS's key; OpenCV's own word for cv::fisheye) for a file of
// cv::fisheye's four coefficients (docs/formats.md#opencv-yaml).
constexpr std::string_view kDistortionModel = "distortion_model", kFisheye = "fisheye";

// A FileNode and the field path it is reported under.
struct Field {
  cv::FileNode node;
  std::string path;
  const std::string* file;

  [[noreturn]] void Fail(std::string_view reason, std::string_view fix) const { FailField(*file, path, reason, fix); }

  Field Member(std::string_view key) const { return {node[std::string(key)], path + "." + std::string(key), file}; }

  std::string Describe() const {
    if (node.isNone()) return "nothing";
    if (node.isMap()) return "a map";
    if (node.isSeq()) return "a sequence of " + std::to_string(node.size());
    if (node.isString()) return "the string \"" + node.string() + "\"";
    if (node.isInt()) return "the integer " + std::to_string(static_cast<int>(node));
    // cv::FileStorage reads 1e999 as ∞ (libFuzzer): named, not formatted for a file.
    const double v = node.real();
    return std::isfinite(v) ? "the number " + ShortestDecimal(v) : "a number beyond the doubles (" + MessageNumber(v) + ")";
  }

  double Number() const {
    if (!node.isInt() && !node.isReal()) Fail("expected a number, got " + Describe(), "write a finite number");
    const double v = node.isInt() ? static_cast<int>(node) : node.real();
    if (!std::isfinite(v)) Fail("the number is not finite", "write a finite number");
    return v;
  }

  int Integer(std::string_view fix) const {
    const double v = Number();
    if (v != std::floor(v) || std::abs(v) > 2147483647.0) Fail("expected an integer, got " + ShortestDecimal(v), fix);
    return static_cast<int>(v);
  }
};

// OpenCV's parse errors carry "<file>(<line>): <what>" in cv::Exception::func.
[[noreturn]] void FailParse(const std::string& name, const cv::Exception& e) {
  static const std::regex kLineAndWhat(R"(\((\d+)\): (.*)$)");
  std::smatch m;
  if (std::regex_search(e.func, m, kLineAndWhat)) {
    FailField(name, "line " + m[1].str(), "not valid OpenCV YAML (" + m[2].str() + ")", "fix the syntax there");
  }
  FailField(name, "", "cv::FileStorage cannot read it (" + e.err + ")",
            "give a file written by cv::FileStorage, starting with \"%YAML:1.0\"");
}

// cv::FileStorage parses YAML by recursion, one call per level: 50,000 levels overflow the stack.
// This bounds the depth from above without parsing, and refuses the text before OpenCV sees it.
// A block collection nests deeper than its parent only by indenting further or after an indicator
// ("- ", "? ", ": ") on the same line, and a sequence written at its key's indentation is followed
// by deeper indentation, so the depth at any point of a line is at most
//   2 · (indentation + indicators so far on the line) + open flow brackets ([, {) + 1.
// Quotes and comments are not skipped: brackets inside them only make the bound larger.
void CheckNesting(const std::string& text, const std::string& name) {
  int flow = 0, indent = 0, indicators = 0;
  bool line_start = true;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      line_start = true;
      indent = indicators = 0;
      continue;
    }
    if (line_start && (c == ' ' || c == '\t')) {
      ++indent;
    } else {
      line_start = false;
      const char next = i + 1 < text.size() ? text[i + 1] : '\n';
      const bool blank_follows = next == ' ' || next == '\t' || next == '\n' || next == '\r';
      if ((c == '-' || c == '?' || c == ':') && blank_follows) ++indicators;
      if (c == '[' || c == '{') ++flow;
      if ((c == ']' || c == '}') && flow > 0) --flow;
    }
    if (2 * (indent + indicators) + flow + 1 > limits::kMaxNesting) {
      FailSyntax(name, text, i,
                 "nested too deeply for OpenCV's parser (indentation, indicators and brackets allow more than " +
                     std::to_string(limits::kMaxNesting) + " levels)",
                 "an OpenCV camera file needs 3 levels; check that this is the right file");
    }
  }
}

// cv::FileStorage reads a plain integer with (int)strtol: 10000000000 becomes 1410065408 and
// 4294967936 becomes 640, silently. Integers beyond 32 bits are refused here, before OpenCV sees
// them; quoted strings and comments are skipped, and a number with a '.', 'e' or 'E' is a real.
void CheckIntegers(const std::string& text, const std::string& name) {
  char quote = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote || c == '\n') quote = 0;
      continue;
    }
    const char prev = i > 0 ? text[i - 1] : '\n';
    const bool token_start = prev == ' ' || prev == '\t' || prev == '\n' || prev == '[' || prev == '{' || prev == ',' ||
                             prev == ':';
    if (c == '#' && (prev == ' ' || prev == '\t' || prev == '\n')) {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    if ((c == '"' || c == '\'') && token_start) {
      quote = c;
      continue;
    }
    if (!token_start) continue;
    size_t end = i + (c == '-' || c == '+');
    const size_t digits = end;
    while (end < text.size() && text[end] >= '0' && text[end] <= '9') ++end;
    if (end == digits) continue;
    const char after = end < text.size() ? text[end] : '\n';
    if (after == '.' || after == 'e' || after == 'E' || after == 'x' || after == 'X') continue;
    const std::string literal = text.substr(i, end - i);
    if (std::abs(std::strtod(literal.c_str(), nullptr)) > 2147483647.0) {
      FailSyntax(name, text, i,
                 "the integer " + literal + " is beyond the 32-bit integers cv::FileStorage reads (it would wrap around)",
                 "write a whole number from -2147483647 to 2147483647 (an image side: at most " +
                     std::to_string(limits::kMaxImageSide) + ")");
    }
    i = end - 1;
  }
}

// Two defects of cv::FileStorage (4.6) that libFuzzer found, refused here before it parses:
// - it loops forever when the first collection ends before the end of the text: it then steps 3
//   bytes ahead, as if over "..." or "---", and can land past the line it holds (16 bytes:
//   "%YAML:1.0\n -a\n:\n-"). A collection ends early only at a line indented less than its first
//   one, or at "..."; so the first content line must start in the first column, as cv::FileStorage
//   writes it, and the text must hold one document (a closing "..." is fine: OpenCV steps over it);
// - an indented line that starts with ':' (an empty key) makes it build a string of negative
//   length: std::length_error, not its own parse error.
void CheckLinesOpenCvMishandles(const std::string& text, const std::string& name) {
  enum class At { kBeforeFields, kInFields, kAfterEnd } at = At::kBeforeFields;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + start, end - start);
    const size_t first = line.find_first_not_of(" \r");
    const bool skip = first == std::string_view::npos || line[first] == '#' ||
                      (at == At::kBeforeFields && line.starts_with('%'));
    if (!skip) {
      if (line[first] == ':') {
        FailSyntax(name, text, start + first, "an empty key (the line starts with ':')", "write the field's name before the ':'");
      }
      const bool starts_document = line.starts_with("---"), ends_document = line.starts_with("...");
      if (at == At::kAfterEnd) {
        FailSyntax(name, text, start + first, "text after the document's end (\"...\" on an earlier line)",
                   "a camera file is one document: delete the \"...\" or what follows it");
      }
      if ((starts_document && at == At::kInFields) || (ends_document && at == At::kBeforeFields)) {
        FailSyntax(name, text, start, "a second YAML document (\"" + std::string(line.substr(0, 3)) + "\")",
                   "a camera file is one document: keep its fields in the first and delete the rest");
      }
      if (starts_document || ends_document) {
        const size_t after = line.find_first_not_of(" \r", 3);
        if (after != std::string_view::npos && line[after] != '#') {
          FailSyntax(name, text, start + after, "text after \"" + std::string(line.substr(0, 3)) + "\" on its line",
                     "put the fields on the lines after it, in the first column, as cv::FileStorage writes them");
        }
        if (ends_document) at = At::kAfterEnd;
      } else if (at == At::kBeforeFields) {
        if (first != 0) {
          FailSyntax(name, text, start + first, "the top level is indented",
                     "start its fields in the first column, as cv::FileStorage writes them");
        }
        at = At::kInFields;
      }
    }
    start = end + 1;
  }
}

cv::FileStorage Open(const std::string& text, const std::string& name) {
  if (IsBlank(text)) throw InputError(name + ": the file is empty; expected OpenCV FileStorage YAML");
  if (text.size() > limits::kMaxOpenCvYamlBytes) {
    throw InputError(name + ": larger than the " + std::to_string(limits::kMaxOpenCvYamlBytes >> 20) +
                     " MiB vstcal reads as OpenCV YAML (docs/reliability.md#limits); check that it is a camera file");
  }
  CheckNesting(text, name);
  CheckIntegers(text, name);
  CheckLinesOpenCvMishandles(text, name);
  try {
    cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened() || !fs.root().isMap()) {
      FailField(name, "", "the top level is not a map of named fields", "write fields as \"name: value\" lines");
    }
    return fs;
  } catch (const cv::Exception& e) {
    if (e.code == cv::Error::StsParseError) FailParse(name, e);
    // OpenCV recognises its formats by their first bytes ("%YAML", "<?xml", "{").
    FailField(name, "", "not an OpenCV FileStorage file",
              "it must start with \"%YAML:1.0\", as cv::FileStorage writes it");
  } catch (const InputError&) {
    throw;
  } catch (const std::length_error& e) {
    // Another of its defects on malformed text, like the empty key refused above.
    FailField(name, "", std::string("cv::FileStorage fails on it (") + e.what() + ")",
              "give a file written by cv::FileStorage");
  }
}

// Each field read once: a second copy would be silently ignored by OpenCV's fs["name"].
void RefuseDuplicates(const cv::FileNode& root, const std::string& name) {
  for (const std::string_view key :
       {kCameraMatrix, kDistortion, std::string_view("image_width"), std::string_view("image_height")}) {
    int count = 0;
    for (auto it = root.begin(); it != root.end(); ++it) count += (*it).name() == key;
    if (count > 1) FailField(name, key, "appears " + std::to_string(count) + " times", "keep one");
  }
}

// An !!opencv-matrix: {rows, cols, dt, data}, read row by row.
Eigen::MatrixXd ReadCvMatrix(const Field& f) {
  if (!f.node.isMap()) {
    f.Fail("expected an !!opencv-matrix (rows, cols, dt, data), got " + f.Describe(), "write it with cv::FileStorage");
  }
  const Field rows_field = f.Member("rows"), cols_field = f.Member("cols"), dt = f.Member("dt"),
              data = f.Member("data");
  for (const Field* m : {&rows_field, &cols_field, &dt, &data}) {
    if (m->node.isNone()) m->Fail("missing field", "an !!opencv-matrix has rows, cols, dt and data");
  }
  const int rows = rows_field.Integer("give the number of rows"),
            cols = cols_field.Integer("give the number of columns");
  if (rows < 0 || cols < 0) {
    f.Fail("negative size " + std::to_string(rows) + "×" + std::to_string(cols), "give rows, cols ≥ 0");
  }
  if (!dt.node.isString() || (dt.node.string() != "d" && dt.node.string() != "f")) {
    dt.Fail("expected \"d\" (double) or \"f\" (float), got " + dt.Describe(),
            "write the matrix as one channel of doubles: dt: d");
  }
  if (!data.node.isSeq()) data.Fail("expected a sequence [ ... ], got " + data.Describe(), "write data: [ ... ]");
  if (static_cast<long>(data.node.size()) != static_cast<long>(rows) * cols) {
    data.Fail(
        "has " + std::to_string(data.node.size()) + " values for " + std::to_string(rows) + "×" + std::to_string(cols),
        "give rows × cols values, row by row");
  }
  // OpenCV reads a "f" matrix into floats: the camera is what OpenCV users get from the file.
  const bool single = dt.node.string() == "f";
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows * cols; ++i) {
    const Field item{data.node[i], data.path + "[" + std::to_string(i) + "]", f.file};
    const double v = item.Number();
    if (single && std::abs(v) > std::numeric_limits<float>::max()) {
      item.Fail("too large for a float (dt: f)", "write dt: d");
    }
    m(i / cols, i % cols) = single ? static_cast<float>(v) : v;
  }
  return m;
}

Eigen::Matrix3d ReadCameraMatrix(const Field& f, std::vector<std::string>* notes) {
  if (f.node.isNone()) {
    f.Fail("missing field", "add the 3×3 camera matrix [fx, 0, cx, 0, fy, cy, 0, 0, 1] as an !!opencv-matrix");
  }
  const Eigen::MatrixXd m = ReadCvMatrix(f);
  if (m.rows() != 3 || m.cols() != 3) {
    f.Fail("expected a 3×3 matrix, got " + std::to_string(m.rows()) + "×" + std::to_string(m.cols()),
           "write rows: 3, cols: 3 and nine values");
  }
  const Eigen::Matrix3d K = m;
  if (const auto problem = CameraMatrixProblem(K)) f.Fail(problem->reason, problem->fix);
  if (K(0, 1) != 0) {
    notes->push_back(*f.file + ": " + f.path + ": K[0][1] (skew) = " + ShortestDecimal(K(0, 1)) +
                     " is kept: vstcal projects with it, although OpenCV's own functions ignore it");
  }
  return K;
}

// cv::fisheye's k1…k4 (distortion_model: fisheye): exactly four.
std::vector<double> ReadFisheyeDistortion(const Field& f) {
  if (f.node.isNone()) f.Fail("missing field", "add cv::fisheye's four coefficients k1, k2, k3, k4 (the D of cv::fisheye::calibrate)");
  const Eigen::MatrixXd m = ReadCvMatrix(f);
  if ((m.rows() > 1 && m.cols() > 1) || m.size() != 4) {
    f.Fail("distortion_model fisheye takes 4 coefficients (k1, k2, k3, k4), got a " + std::to_string(m.rows()) + "×" +
               std::to_string(m.cols()) + " matrix",
           "write cv::fisheye's D as a 4×1 matrix, or delete distortion_model if these are calibrateCamera's coefficients");
  }
  return std::vector<double>(m.data(), m.data() + 4);
}

std::vector<double> ReadCvDistortion(const Field& f, std::vector<std::string>* notes) {
  if (f.node.isNone()) {
    notes->push_back(*f.file + ": " + f.path + ": absent, read as no distortion (model \"none\")");
    return {};
  }
  const Eigen::MatrixXd m = ReadCvMatrix(f);
  if (m.rows() > 1 && m.cols() > 1) {
    f.Fail("expected N×1 or 1×N, got " + std::to_string(m.rows()) + "×" + std::to_string(m.cols()),
           "write the coefficients as one column (k1, k2, p1, p2[, k3[, k4, k5, k6]])");
  }
  const int n = static_cast<int>(m.size());
  if (n == 12 || n == 14) {
    f.Fail(std::to_string(n) + " coefficients are OpenCV's " +
               (n == 12 ? "thin-prism model (CALIB_THIN_PRISM_MODEL)" : "tilted-sensor model (CALIB_TILTED_MODEL)") +
               ", which vstcal does not support",
           "calibrate with CALIB_RATIONAL_MODEL alone (8 coefficients) or with the default model (5)");
  }
  if (!LensModelForOpenCvLength(n)) {
    f.Fail("expected 4, 5 or 8 coefficients (k1, k2, p1, p2[, k3[, k4, k5, k6]]), got " + std::to_string(n),
           "write the vector OpenCV's calibrateCamera returned");
  }
  if (n == 4) {
    notes->push_back(*f.file + ": " + f.path + ": 4 coefficients without distortion_model: read as calibrateCamera's "
                     "(k1, k2, p1, p2); a cv::fisheye file says distortion_model: fisheye");
  }
  return std::vector<double>(m.data(), m.data() + n);
}

int ReadImageDimension(const Field& f, std::string_view what) {
  if (f.node.isNone()) {
    f.Fail("missing field",
           "add image_width and image_height: the size in pixels of the images the camera was calibrated with");
  }
  const double v = f.Number();
  if (const auto problem = ImageSideProblem(v, what)) f.Fail(problem->reason, problem->fix);
  return static_cast<int>(v);
}

}  // namespace

ImportedCamera OpenCvYamlFromText(const std::string& text, const std::string& name, LengthUnit length_unit) {
  const cv::FileStorage fs = Open(text, name);
  const cv::FileNode root = fs.root();
  RefuseDuplicates(root, name);
  auto field = [&](std::string_view key) { return Field{root[std::string(key)], std::string(key), &name}; };
  ImportedCamera out;
  const Eigen::Matrix3d K = ReadCameraMatrix(field(kCameraMatrix), &out.notes);
  const Field model = field(kDistortionModel);
  bool fisheye = false;
  if (!model.node.isNone()) {
    if (!model.node.isString() || model.node.string() != kFisheye) {
      model.Fail("expected \"fisheye\", got " + model.Describe(),
                 "write distortion_model: fisheye for cv::fisheye's k1, k2, k3, k4, or delete the key for calibrateCamera's "
                 "coefficients");
    }
    fisheye = true;
  }
  const std::vector<double> distortion =
      fisheye ? ReadFisheyeDistortion(field(kDistortion)) : ReadCvDistortion(field(kDistortion), &out.notes);
  const ImageSize size{ReadImageDimension(field("image_width"), "width"),
                       ReadImageDimension(field("image_height"), "height")};
  out.camera.camera =
      fisheye ? Camera::FromK(K, size, KannalaBrandtModel{}, distortion) : CameraFromOpenCv(K, size, distortion);
  out.camera.length_unit = length_unit;
  out.camera.method = "opencv";
  return out;
}

ImportedCamera ReadOpenCvYaml(const std::filesystem::path& path, LengthUnit length_unit) {
  return OpenCvYamlFromText(ReadInputFile(path, "an OpenCV YAML file", limits::kMaxOpenCvYamlBytes, "OpenCV YAML"), path.string(), length_unit);
}

ExportedCamera OpenCvYamlText(const CalibratedCamera& camera, std::string_view source, const Provenance& provenance) {
  const Camera& c = camera.camera;
  RefuseSkew(c, source, "OpenCV");
  ExportedCamera out;
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs.writeComment(ProvenanceComment(provenance));
  fs << "image_width" << c.image_size.width << "image_height" << c.image_size.height;
  const Eigen::Matrix3d K = c.K();
  cv::Mat camera_matrix(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) camera_matrix.at<double>(r, col) = K(r, col);
  }
  fs << std::string(kCameraMatrix) << camera_matrix;
  const std::vector<double> distortion(c.distortion().begin(), c.distortion().end());
  // An absent node reads as an empty vector, which every OpenCV function takes as no distortion.
  if (!distortion.empty()) fs << std::string(kDistortion) << cv::Mat(distortion, true);
  if (!HasOpenCvDistortion(c)) fs << std::string(kDistortionModel) << std::string(kFisheye);  // cv::fisheye's D
  out.text = fs.releaseAndGetString();
  NoteUnwrittenName(camera, source, &out.notes);
  if (camera.camera_from_world) {
    out.notes.push_back(std::string(source) +
                        ": camera_from_world: not written: OpenCV's calibration file holds no extrinsics");
  }
  return out;
}

}  // namespace vstcal
