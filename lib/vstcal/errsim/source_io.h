// The "sources" block of vstcal/vst-chain@1: each source's terms and their distributions
// (docs/formats.md#vst-chain-sources), written into a ChainModel's parameters.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "vstcal/calib/calibrated_camera.h"
#include "vstcal/errsim/chain_model.h"
#include "vstcal/json/json_reader.h"

namespace vstcal::errsim {

// The fiducial layout of virtual_object_alignment's fiducial form (object frame), needed before the
// parameter layout is fixed; empty for the pose form. Fails on a collinear layout.
std::vector<Eigen::Vector3d> ReadFiducialLayout(const io::JsonNode& sources);

// Fills the distributions of `model` (made by ChainModel::WithZeroErrors with the same fiducials)
// from the sources object. `camera_covariance[e]` is eye e's camera-file covariance, if it has one.
void ReadSources(const io::JsonNode& sources, const std::array<std::optional<ParameterCovariance>, kNumEyes>& camera_covariance,
                 ChainModel* model);

}  // namespace vstcal::errsim
