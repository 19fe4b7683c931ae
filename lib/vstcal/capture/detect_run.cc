#include "vstcal/capture/detect_run.h"
#include "vstcal/files/input_protection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <opencv2/core/utility.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "vstcal/image/codecs.h"
#include "vstcal/image/image_io.h"
#include "vstcal/core/error.h"
#include "vstcal/core/parallel.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

constexpr size_t kMaxImages = 100000;

// OpenCV's own threads would compete with ours (one image per core): one thread inside OpenCV
// while the capture runs, restored afterwards.
class OpenCvSingleThreaded {
 public:
  OpenCvSingleThreaded() : saved_(cv::getNumThreads()) { cv::setNumThreads(1); }
  ~OpenCvSingleThreaded() { cv::setNumThreads(saved_); }
  OpenCvSingleThreaded(const OpenCvSingleThreaded&) = delete;
  OpenCvSingleThreaded& operator=(const OpenCvSingleThreaded&) = delete;

 private:
  int saved_;
};

// Calls `progress` from one thread at a time with the fraction done.
class SharedProgress {
 public:
  SharedProgress(Progress progress, size_t total) : progress_(std::move(progress)), total_(std::max<size_t>(total, 1)) {}
  void Tick() {
    if (!progress_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    progress_(static_cast<double>(++done_) / total_);
  }

 private:
  Progress progress_;
  size_t total_, done_ = 0;
  std::mutex mutex_;
};

// Memory of a capture at any thread count: an image holds its decoded pixels twice while it is
// decoded (OpenCV's matrix and the GrayImage), and the finders work on a copy of at most 1 MP
// (search_image.h) with their own buffers, under kFinderBytes. Images start only while the
// bytes reserved stay under kBytesInFlight (one image alone always may: a 100 MP image takes
// about 300 MB), so a capture stays under 1 GB whatever the thread count.
constexpr double kBytesInFlight = 768e6;
constexpr double kFinderBytes = 48e6;

class MemoryGate {
 public:
  // Holds `bytes` of the gate from construction (waiting until they fit, or until nothing else
  // is in flight) to destruction.
  class Pass {
   public:
    Pass(MemoryGate& gate, double bytes) : gate_(gate), bytes_(bytes) { gate_.Enter(bytes_); }
    ~Pass() { gate_.Leave(bytes_); }
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;

   private:
    MemoryGate& gate_;
    double bytes_;
  };

 private:
  void Enter(double bytes) {
    std::unique_lock<std::mutex> lock(mutex_);
    freed_.wait(lock, [&] { return in_flight_ == 0 || in_flight_ + bytes <= kBytesInFlight; });
    in_flight_ += bytes;
  }
  void Leave(double bytes) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      in_flight_ -= bytes;
    }
    freed_.notify_all();
  }

  std::mutex mutex_;
  std::condition_variable freed_;
  double in_flight_ = 0;
};

// What an image of `pixels` reserves (kMaxImageMegapixels when its header gave no size).
double ImageBytes(std::optional<double> pixels) { return 2 * pixels.value_or(kMaxImageMegapixels * 1e6) + kFinderBytes; }

std::string TargetName(const DetectRequest& r) { return r.target_file.empty() ? "the target" : r.target_file; }

std::string Size(int w, int h) { return std::to_string(w) + "×" + std::to_string(h); }

// The view names of image files: each file name without its extension, or the whole path as
// given when two images share a file name.
std::vector<std::string> ViewNames(const std::vector<ImageRecord>& records) {
  std::map<std::string, int> count;
  std::vector<std::string> stems;
  for (const ImageRecord& r : records) {
    stems.push_back(std::filesystem::path(r.image).stem().string());
    ++count[stems.back()];
  }
  for (size_t k = 0; k < records.size(); ++k) {
    if (count[stems[k]] > 1 || stems[k].empty()) stems[k] = records[k].image;
  }
  return stems;
}

bool SameBytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  std::ostringstream sa, sb;
  sa << fa.rdbuf();
  sb << fb.rdbuf();
  return sa.str() == sb.str();
}

// Everything after the detections: the checks on the capture as a whole and the views.
// `times`: each record's time (s, the video's clock), or empty (image files have none).
CaptureResult Finish(std::vector<ImageRecord> records, std::vector<Detection> detections, const std::vector<std::optional<double>>& offsets,
                     const std::vector<std::string>& names, const DetectRequest& request, ImageSize size,
                     const std::vector<double>& times = {}) {
  CaptureResult out;
  Correspondences& c = out.correspondences;
  c.camera = request.camera_name;
  c.image_size = size;
  c.length_unit = request.target.length_unit;
  c.rig = request.rig;
  std::set<double> planes;
  for (size_t k = 0; k < records.size(); ++k) {
    if (records[k].status != DetectionStatus::kFound) continue;
    View view;
    view.name = records[k].view = names[k];
    view.image = records[k].image;
    if (!times.empty()) view.time = times[k];
    if (request.rig == Rig::kVolume) {
      view.plane_offset = offsets[k];
      planes.insert(*offsets[k]);
    }
    for (const DetectedCorner& corner : detections[k].corners) {
      const Eigen::Vector2d xy = CornerPosition(request.target, corner.id);
      view.observations.push_back({Eigen::Vector3d(xy.x(), xy.y(), request.rig == Rig::kVolume ? *offsets[k] : 0.0), corner.pixel});
    }
    c.views.push_back(std::move(view));
  }
  const std::string counts = DescribeCounts(records);
  if (c.views.empty()) {
    // A ChArUco board in the other of OpenCV's two patterns: the fix is the target's legacy field.
    for (const ImageRecord& r : records) {
      if (r.status == DetectionStatus::kRejected && r.reason.starts_with("pattern mismatch")) {
        throw InputError(TargetName(request) + ": no image shows the " + DescribeTarget(request.target) + " (" + counts + "); " + r.image +
                         ": " + r.reason);
      }
    }
    // Found in every image, and rejected for its quality: the target file is right, the images are not.
    const ImageRecord* rejected = nullptr;
    bool missed = false;
    for (const ImageRecord& r : records) {
      missed = missed || r.status == DetectionStatus::kNotFound ||
               (r.status == DetectionStatus::kRejected && (r.reason.starts_with("layout mismatch") || r.reason.starts_with("unreadable")));
      if (!rejected && r.status == DetectionStatus::kRejected) rejected = &r;
    }
    if (!missed && rejected) {
      throw InputError(TargetName(request) + ": no usable image of the " + DescribeTarget(request.target) + " (" + counts +
                       "): the board was found and rejected (" + rejected->image + ": " + rejected->reason + "); " +
                       (rejected->reason.starts_with("blurred") ? "take sharper images (focus, steady the camera, a shorter exposure) or raise the blur limit (max_blur_px)"
                                                                : "take images the reason does not apply to"));
    }
    throw InputError(TargetName(request) + ": no image shows the " + DescribeTarget(request.target) + " (" + counts +
                     "); check the target file's type, rows and cols against the board, and that the images show it whole");
  }
  if (static_cast<int>(c.views.size()) < request.min_views) {
    throw DegenerateError("too few usable images: " + counts + "; a calibration needs at least " + std::to_string(request.min_views) +
                          " (" VSTCAL_OPT("min_views") "): capture more views of the target");
  }
  if (request.rig == Rig::kVolume && planes.size() < 2) {
    char offset[32];
    std::snprintf(offset, sizeof offset, "%g", *planes.begin());
    throw DegenerateError(std::string("every usable image shows the template at plane_offset ") + offset +
                          ": a calibration volume needs at least two template positions (" + counts + ")");
  }
  out.images = std::move(records);
  out.detections = std::move(detections);
  return out;
}

ImageRecord Record(const std::string& image, const Detection& d, int w, int h) {
  ImageRecord r;
  r.image = image;
  r.status = d.status;
  r.reason = d.reason;
  r.corners = d.status == DetectionStatus::kFound ? static_cast<int>(d.corners.size()) : 0;
  r.blur_px = d.blur_px;
  r.width = w;
  r.height = h;
  return r;
}

}  // namespace

std::string DescribeCounts(const std::vector<ImageRecord>& images) {
  int found = 0, not_found = 0, rejected = 0;
  std::map<std::string, int> why;
  for (const ImageRecord& r : images) {
    if (r.status == DetectionStatus::kFound) ++found;
    if (r.status == DetectionStatus::kNotFound) ++not_found;
    if (r.status == DetectionStatus::kRejected) {
      ++rejected;
      ++why[r.reason.substr(0, r.reason.find(':'))];
    }
  }
  std::string out = std::to_string(images.size()) + (images.size() == 1 ? " image: " : " images: ") + std::to_string(found) +
                    " found, " + std::to_string(not_found) + " not found, " + std::to_string(rejected) + " rejected";
  if (!why.empty()) {
    out += " (";
    for (auto it = why.begin(); it != why.end(); ++it) out += (it == why.begin() ? "" : ", ") + std::to_string(it->second) + " " + it->first;
    out += ")";
  }
  return out;
}

CaptureResult DetectInFiles(const std::vector<CaptureInput>& inputs, const DetectRequest& request, const Progress& progress) {
  if (inputs.empty()) throw InputError("no images given; list image files, folders or globs");
  if (inputs.size() > kMaxImages) throw InputError(std::to_string(inputs.size()) + " images, more than 100000; split the capture");
  std::map<std::filesystem::path, size_t> seen;
  for (size_t k = 0; k < inputs.size(); ++k) {
    if (request.rig == Rig::kVolume && !inputs[k].plane_offset) {
      throw InputError(inputs[k].image + ": no plane_offset for this image; a volume needs each image's template position");
    }
    std::error_code ec;
    std::filesystem::path key = std::filesystem::weakly_canonical(inputs[k].path, ec);
    if (ec) key = inputs[k].path.lexically_normal();
    const auto [it, inserted] = seen.emplace(key, k);
    if (!inserted) throw InputError(inputs[k].image + ": listed twice (also as " + inputs[it->second].image + "); list each image once");
  }

  // Sizes from the headers first: images of mixed sizes are refused before any is searched.
  std::vector<std::optional<std::pair<int, int>>> header_sizes(inputs.size());
  std::optional<size_t> first_sized;
  for (size_t k = 0; k < inputs.size(); ++k) {
    header_sizes[k] = ReadImageHeaderSize(inputs[k].path);
    if (!header_sizes[k]) continue;
    if (!first_sized) first_sized = k;
    const auto [w, h] = *header_sizes[k];
    const auto [rw, rh] = *header_sizes[*first_sized];
    if (w != rw || h != rh) {
      throw InputError(inputs[k].image + ": " + Size(w, h) + " pixels, but " + inputs[*first_sized].image + " has " + Size(rw, rh) +
                       "; one calibration takes images of one camera at one size");
    }
  }

  struct Slot {
    std::string problem;
    uint64_t digest = 0;
    int width = 0, height = 0;
    Detection detection;
  };
  std::vector<Slot> slots(inputs.size());
  {
    const OpenCvSingleThreaded single;
    SharedProgress shared(progress, inputs.size());
    MemoryGate gate;
    ParallelFor(inputs.size(), request.threads, [&](size_t k) {
      std::optional<double> pixels;
      if (header_sizes[k]) pixels = static_cast<double>(header_sizes[k]->first) * header_sizes[k]->second;
      const MemoryGate::Pass pass(gate, ImageBytes(pixels));
      LoadedImage loaded = LoadImageFile(inputs[k].path);
      Slot& s = slots[k];
      s.problem = std::move(loaded.problem);
      s.digest = loaded.digest;
      s.width = loaded.image.width;
      s.height = loaded.image.height;
      if (s.problem.empty()) s.detection = DetectTarget(loaded.image, request.target, request.detector);
      shared.Tick();
    });
  }

  std::vector<ImageRecord> records;
  std::vector<Detection> detections;
  std::vector<std::optional<double>> offsets;
  std::optional<size_t> reference;  // the first readable image: its size is the capture's
  std::map<uint64_t, size_t> digests;
  for (size_t k = 0; k < inputs.size(); ++k) {
    Slot& s = slots[k];
    if (!s.problem.empty()) {
      if (!request.skip_unreadable) {
        throw InputError(inputs[k].image + ": " + s.problem + "; copy the image again or remove it (" VSTCAL_OPT("skip_unreadable") " lists it as rejected)");
      }
      s.detection = Detection{DetectionStatus::kRejected, "unreadable: " + s.problem, {}, std::nan("")};
    } else {
      if (!reference) reference = k;
      const Slot& ref = slots[*reference];
      if (s.width != ref.width || s.height != ref.height) {
        throw InputError(inputs[k].image + ": " + Size(s.width, s.height) + " pixels, but " + inputs[*reference].image + " has " +
                         Size(ref.width, ref.height) + "; one calibration takes images of one camera at one size");
      }
      const auto [it, inserted] = digests.emplace(s.digest, k);
      if (!inserted && SameBytes(inputs[it->second].path, inputs[k].path)) {
        throw InputError(inputs[k].image + ": the same image as " + inputs[it->second].image + " (identical bytes); remove the copy");
      }
    }
    records.push_back(Record(inputs[k].image, s.detection, s.width, s.height));
    detections.push_back(std::move(s.detection));
    offsets.push_back(inputs[k].plane_offset);
  }
  if (!reference) throw InputError("no image could be read (" + DescribeCounts(records) + ")");
  const std::vector<std::string> names = ViewNames(records);
  return Finish(std::move(records), std::move(detections), offsets, names, request, {slots[*reference].width, slots[*reference].height});
}

CaptureResult DetectInVideo(const VideoRequest& video, const DetectRequest& request, const Progress& progress) {
  if (request.rig != Rig::kPlanarViews) {
    throw InputError(VSTCAL_OPT("video") "/" VSTCAL_OPT("camera_index") ": frames have no template positions; a volume needs images with " VSTCAL_OPT("manifest") " or " VSTCAL_OPT("offset_from_name"));
  }
  if (video.every < 1) throw InputError(VSTCAL_OPT("every") ": must be a whole number ≥ 1");
  const bool live = video.camera_index >= 0;
  if (live && video.max_frames < 1) throw InputError(VSTCAL_OPT("frames") ": required with " VSTCAL_OPT("camera_index") " (how many frames to keep)");
  const std::string source = live ? "camera" + std::to_string(video.camera_index) : video.file;
  // OpenCV's video backends log their own failures (GStreamer, FFmpeg) on stderr; the tool's one
  // line says what went wrong instead. FFmpeg logs through av_log, which OpenCV's FFmpeg backend
  // quiets only when OPENCV_FFMPEG_LOGLEVEL is set when it loads (-8: AV_LOG_QUIET); a value the
  // user set is kept.
  ::setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);
  struct QuietOpenCv {
    cv::utils::logging::LogLevel saved = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    ~QuietOpenCv() { cv::utils::logging::setLogLevel(saved); }
  } quiet;
  VideoSource capture;
  if (live) {
    capture.OpenCamera(video.camera_index);
  } else {
    std::error_code ec;
    if (!std::filesystem::exists(video.file, ec)) throw InputError(video.file + ": no such file; check the path");
    if (std::filesystem::is_directory(video.file, ec)) throw InputError(video.file + ": is a directory, not a video; give the video file");
    NoteInputFile(video.file);
    // The file backends only, in OpenCV's own order: CAP_ANY also offers the name to libgphoto2,
    // which enumerates the USB bus for a camera of that name (and leaks what it enumerated).
    for (const int api : {cv::CAP_FFMPEG, cv::CAP_GSTREAMER, cv::CAP_OPENCV_MJPEG}) {
      if (capture.OpenFile(video.file, api)) break;
    }
  }
  if (!capture.IsOpened()) {
    throw InputError(source + (live ? ": cannot open the camera; check the index (0 is the first camera) and that no other program uses it"
                                    : ": cannot open as a video (OpenCV's video I/O does not read it); check that it is a video file "
                                      "(e.g. an MJPG AVI, or a format FFmpeg reads) and not truncated"));
  }
  const size_t limit = video.max_frames > 0 ? static_cast<size_t>(video.max_frames) : kMaxImages;
  const unsigned threads = ResolveThreads(request.threads);
  std::vector<ImageRecord> records;
  std::vector<Detection> detections;
  std::vector<double> times;
  int width = 0, height = 0;
  const OpenCvSingleThreaded single;
  SharedProgress shared(video.max_frames > 0 ? progress : Progress{}, limit);
  for (long frame = 0; records.size() < limit;) {
    // A batch of frames read in order, then searched in parallel.
    std::vector<std::pair<long, GrayImage>> batch;
    std::vector<double> batch_times;
    // Up to 4 frames a thread, fewer where their pixels would pass the memory bound (MemoryGate).
    size_t max_batch = 4 * threads;
    if (width > 0) {
      const double frame_bytes = static_cast<double>(width) * height + kFinderBytes;
      max_batch = std::clamp<size_t>(static_cast<size_t>(kBytesInFlight / frame_bytes), 1, max_batch);
    }
    for (; batch.size() < max_batch && records.size() + batch.size() < limit; ++frame) {
      if (frame % video.every != 0) {
        if (!capture.Grab()) break;
        continue;
      }
      cv::Mat bgr, gray;
      if (!capture.Read(&bgr) || bgr.empty()) break;
      // The frame's time on the video's clock, for hand-eye calibration (views[i].time): the
      // container's timestamp where the backend gives one, else the frame's index over its rate.
      const double msec = capture.Get(cv::CAP_PROP_POS_MSEC), fps = capture.Get(cv::CAP_PROP_FPS);
      batch_times.push_back(std::isfinite(msec) && msec > 0 ? msec / 1000 : (fps > 0 ? static_cast<double>(frame) / fps : 0.0));
      if (bgr.channels() == 1) {
        gray = bgr;
      } else {
        cv::cvtColor(bgr, gray, bgr.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
      }
      if (gray.depth() != CV_8U) gray.convertTo(gray, CV_8U);
      if (width == 0) width = gray.cols, height = gray.rows;
      GrayImage image(gray.cols, gray.rows);
      for (int v = 0; v < gray.rows; ++v) std::copy(gray.ptr<uint8_t>(v), gray.ptr<uint8_t>(v) + gray.cols, &image.at(0, v));
      batch.emplace_back(frame, std::move(image));
    }
    if (batch.empty()) break;
    std::vector<Detection> found(batch.size());
    ParallelFor(batch.size(), threads, [&](size_t k) {
      found[k] = DetectTarget(batch[k].second, request.target, request.detector);
      shared.Tick();
    });
    for (size_t k = 0; k < batch.size(); ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "#%ld", batch[k].first);
      records.push_back(Record(source + name, found[k], batch[k].second.width, batch[k].second.height));
      times.push_back(batch_times[k]);
      detections.push_back(std::move(found[k]));
    }
  }
  if (records.empty()) throw InputError(source + ": no frame could be read; check that the video is not empty or truncated");
  std::vector<std::string> names;
  for (const ImageRecord& r : records) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%06ld", std::stol(r.image.substr(r.image.rfind('#') + 1)));
    names.push_back(name);
  }
  return Finish(std::move(records), std::move(detections), std::vector<std::optional<double>>(names.size()), names, request,
                {width, height}, times);
}

}  // namespace vstcal
