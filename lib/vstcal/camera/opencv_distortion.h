// OpenCV's distortion vector ↔ vstcal's lens models (docs/conventions.md#distortion).
//
// OpenCV picks its model by the vector's length, (k1, k2, p1, p2[, k3[, k4, k5, k6[, s1, s2, s3,
// s4[, τx, τy]]]]) with n ∈ {0, 4, 5, 8, 12, 14}; mrcal's LENSMODEL_OPENCV4/5/8/12 hold the same
// vectors. vstcal keeps OpenCV's coefficient order, so every model's coefficients are a prefix of
// OpenCV's vector: converting appends zeros one way and drops trailing zeros the other. Nothing
// here names a model: a model in AnyLensModel whose distortion terms are a prefix of
// kOpenCvDistortionNames is mapped by its coefficient count alone; others (the fisheye
// "kannala-brandt", OpenCV's separate cv::fisheye) never are.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"

namespace vstcal {

// The lengths OpenCV accepts, ascending.
inline constexpr int kOpenCvDistortionLengths[] = {0, 4, 5, 8, 12, 14};

// OpenCV's coefficient names in its order, as far as vstcal's models go.
inline constexpr std::string_view kOpenCvDistortionNames[] = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};

// The vstcal model for an OpenCV vector of n coefficients: the smallest model in OpenCV's order
// (its distortion terms a prefix of kOpenCvDistortionNames) that holds n
// (0 → "none", 4 or 5 → "radial-tangential", 8 → "rational"). nullopt when OpenCV has no vector
// of that length, or no vstcal model holds it (12: thin prism, 14: tilted sensor).
std::optional<AnyLensModel> LensModelForOpenCvLength(int n);

// A camera from K, the image size and an OpenCV vector whose length LensModelForOpenCvLength
// accepts. The model's coefficients past the vector are 0 (four coefficients: k3 = 0).
Camera CameraFromOpenCv(const Eigen::Matrix3d& K, ImageSize image_size, std::span<const double> coefficients);

// True when the camera's distortion terms are a prefix of OpenCV's vector (the Brown–Conrady
// models); false for "kannala-brandt", whose k1…k4 are cv::fisheye's, not the plumb-bob k1, k2,
// p1, p2. The functions below take only such cameras.
bool HasOpenCvDistortion(const Camera& camera);

// Throws InputError "<source>: model: ..." for a camera without an OpenCV distortion vector, saying
// that `peer` has no equivalent model and what to do (`fix`).
void RefuseNonOpenCvModel(const Camera& camera, std::string_view source, std::string_view peer, std::string_view fix);

// Index, in the camera's distortion, of the first non-zero coefficient that a vector of n cannot
// hold; nullopt when the camera fits in n coefficients exactly.
std::optional<int> FirstCoefficientBeyond(const Camera& camera, int n);

// The camera's distortion as an OpenCV vector of n coefficients, zeros appended past the model's
// own. The camera must fit (FirstCoefficientBeyond is nullopt).
std::vector<double> OpenCvDistortion(const Camera& camera, int n);

// The shortest OpenCV length that reads back as the camera's own model and holds every non-zero
// coefficient: "radial-tangential" with k3 = 0 gives 4, otherwise the model's own count.
int ShortestOpenCvLength(const Camera& camera);

// OpenCV's and mrcal's projections have no skew term: a camera with K[0][1] ≠ 0 would project
// differently there. Throws InputError "<source>: K[0][1]: ..." saying by how many pixels at most
// (|s|·|v − cy|/fy over the image rows) and what to do; `peer` names the other tool.
void RefuseSkew(const Camera& camera, std::string_view source, std::string_view peer);

}  // namespace vstcal
