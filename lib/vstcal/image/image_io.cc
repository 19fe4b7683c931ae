#include "vstcal/image/image_io.h"

#include "vstcal/files/input_protection.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

#include <opencv2/core/mat.hpp>

#include "vstcal/image/codecs.h"

namespace vstcal {
namespace {

struct Size {
  long width, height;
};

uint32_t BigEndian32(const std::string& b, size_t at) {
  return (static_cast<uint32_t>(static_cast<uint8_t>(b[at])) << 24) | (static_cast<uint32_t>(static_cast<uint8_t>(b[at + 1])) << 16) |
         (static_cast<uint32_t>(static_cast<uint8_t>(b[at + 2])) << 8) | static_cast<uint8_t>(b[at + 3]);
}
uint32_t BigEndian16(const std::string& b, size_t at) {
  return (static_cast<uint32_t>(static_cast<uint8_t>(b[at])) << 8) | static_cast<uint8_t>(b[at + 1]);
}

bool IsPng(const std::string& b) { return b.size() >= 8 && b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0; }
bool IsJpeg(const std::string& b) { return b.size() >= 3 && b.compare(0, 3, "\xFF\xD8\xFF") == 0; }

// The header's size, or a problem.
// The IHDR chunk's size, from the first 33 bytes.
std::optional<Size> PngHeaderSize(const std::string& b) {
  if (b.size() < 33 || b.compare(12, 4, "IHDR") != 0) return std::nullopt;
  return Size{BigEndian32(b, 16), BigEndian32(b, 20)};
}

std::optional<Size> PngSize(const std::string& b, std::string* problem) {
  const std::optional<Size> size = PngHeaderSize(b);
  if (!size) {
    *problem = "truncated PNG (no complete IHDR header)";
    return std::nullopt;
  }
  // The last chunk of a complete PNG is IEND: length 0, "IEND", CRC.
  if (b.size() < 45 || b.compare(b.size() - 8, 4, "IEND") != 0) {
    *problem = "truncated PNG (it does not end with the IEND chunk)";
    return std::nullopt;
  }
  return size;
}

// The first start-of-frame's size (SOF0 … SOF15 but DHT C4, JPG C8, DAC CC), walking the markers
// of `b` (the file or its beginning); nullopt when none is reached.
std::optional<Size> JpegFrameSize(const std::string& b) {
  size_t at = 2;
  while (at + 9 < b.size()) {
    if (static_cast<uint8_t>(b[at]) != 0xFF) break;
    const uint8_t marker = static_cast<uint8_t>(b[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    const size_t length = BigEndian16(b, at + 2);
    if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
      return Size{static_cast<long>(BigEndian16(b, at + 7)), static_cast<long>(BigEndian16(b, at + 5))};
    }
    if (length < 2) break;
    at += 2 + length;
  }
  return std::nullopt;
}

std::optional<Size> JpegSize(const std::string& b, std::string* problem) {
  // A complete JPEG ends with EOI (FF D9); some cameras pad after it, so look at the last 4 KiB.
  const size_t tail = b.size() > 4096 ? b.size() - 4096 : 2;
  if (b.find("\xFF\xD9", tail) == std::string::npos) {
    *problem = "truncated JPEG (no end-of-image marker FF D9 at the end)";
    return std::nullopt;
  }
  const std::optional<Size> size = JpegFrameSize(b);
  if (!size) *problem = "corrupt JPEG (no frame header before the image data)";
  return size;
}

uint64_t Fnv1a(const std::string& bytes) {
  uint64_t h = 1469598103934665603ull;
  for (const char c : bytes) {
    h ^= static_cast<uint8_t>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

LoadedImage DecodeImage(const std::string& bytes) {
  LoadedImage out;
  out.digest = Fnv1a(bytes);
  if (bytes.empty()) {
    out.problem = "the file is empty (0 bytes)";
    return out;
  }
  std::optional<Size> size;
  if (IsPng(bytes)) {
    size = PngSize(bytes, &out.problem);
  } else if (IsJpeg(bytes)) {
    size = JpegSize(bytes, &out.problem);
  }
  if (!out.problem.empty()) return out;
  if (size && (size->width <= 0 || size->height <= 0 || static_cast<double>(size->width) * size->height > kMaxImageMegapixels * 1e6)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "its header says %ld × %ld pixels, outside 1 … %.0f megapixels", size->width, size->height,
                  kMaxImageMegapixels);
    out.problem = buf;
    return out;
  }
  const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
  const cv::Mat gray = DecodeGrayImage(raw);
  if (gray.empty() || gray.type() != CV_8U) {
    out.problem = "not an image OpenCV can decode (PNG, JPEG, BMP, TIFF, PGM …) or corrupt";
    return out;
  }
  if (static_cast<double>(gray.cols) * gray.rows > kMaxImageMegapixels * 1e6) {
    out.problem = "more than " + std::to_string(static_cast<int>(kMaxImageMegapixels)) + " megapixels";
    return out;
  }
  out.image = GrayImage(gray.cols, gray.rows);
  for (int v = 0; v < gray.rows; ++v) std::memcpy(&out.image.at(0, v), gray.ptr<uint8_t>(v), gray.cols);
  return out;
}

LoadedImage LoadImageFile(const std::filesystem::path& path) {
  std::error_code ec;
  LoadedImage out;
  switch (KindOfPath(path)) {
    case PathKind::kMissing: out.problem = "no such file"; return out;
    case PathKind::kDirectory: out.problem = "a directory, not an image"; return out;
    case PathKind::kSpecial: out.problem = "not a regular file (a device, a pipe or a socket), not an image"; return out;
    case PathKind::kRegularFile:
    case PathKind::kUnknown: break;
  }
  NoteInputFile(path);  // an output of this run may not replace an image it read
  const auto bytes_on_disk = std::filesystem::file_size(path, ec);
  if (!ec && bytes_on_disk > 1024ull * 1024 * 1024) {
    out.problem = "larger than 1 GiB: not a camera image";
    return out;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    out.problem = std::string("cannot open (") + std::strerror(errno) + ")";
    return out;
  }
  // One copy of the bytes (a string stream would hold two while a 100 MP file is decoded).
  std::string bytes(ec ? 0 : static_cast<size_t>(bytes_on_disk), '\0');
  if (ec) {
    std::ostringstream buffer;
    buffer << in.rdbuf();
    bytes = buffer.str();
  } else if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())) || in.peek() != std::char_traits<char>::eof()) {
    out.problem = "the file changed while it was read";
    return out;
  }
  return DecodeImage(bytes);
}

std::optional<std::pair<int, int>> ReadImageHeaderSize(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  // A PNG's size is in its first 33 bytes; a JPEG's frame header follows its metadata (EXIF with
  // a thumbnail, an ICC profile: tens of KiB), so up to 256 KiB are read where 16 KiB do not reach it.
  std::string head;
  std::optional<Size> size;
  for (const size_t reach : {size_t{16 * 1024}, size_t{256 * 1024}}) {
    const size_t had = head.size();
    head.resize(reach);
    in.read(head.data() + had, static_cast<std::streamsize>(reach - had));
    head.resize(had + static_cast<size_t>(in.gcount()));
    if (IsPng(head)) size = PngHeaderSize(head);
    if (IsJpeg(head)) size = JpegFrameSize(head);
    if (size || head.size() < reach || !IsJpeg(head)) break;
  }
  if (!size || size->width <= 0 || size->height <= 0 || size->width > INT32_MAX || size->height > INT32_MAX) return std::nullopt;
  return std::pair<int, int>(static_cast<int>(size->width), static_cast<int>(size->height));
}

}  // namespace vstcal
