// vstcal/vst-chain@1 reader (docs/formats.md#vst-chain): the nominal chain, both cameras (inline,
// a camera@1 file each, or a stereo@1 rig that also gives the right camera's pose and, when asked,
// its covariance as the right camera's extrinsic error), display geometry, head motion, test points, the
// seven error sources with their distributions (the terms schema.h declares), samples and seed.
// Unknown keys are refused with a did-you-mean: a mistyped error term would otherwise simulate
// nothing. Limits: kMaxTestPoints test points, kMaxFiducials fiducials.
#pragma once

#include <filesystem>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/formats/errsim/chain_spec.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {

inline constexpr size_t kMaxTestPoints = 1000;
inline constexpr size_t kMaxFiducials = 1000;

// Reads and validates every field; InputError "<file>: <field>: <what>; <fix>" otherwise. Camera
// and rig files are resolved relative to the chain file's directory.
ChainSpec ReadChainSpec(const std::filesystem::path& path);
ChainSpec ChainSpecFromJson(const JsonDocument& doc, const std::filesystem::path& directory);

// ReadChainSpec then BuildChainModel.
ChainModel ReadChain(const std::filesystem::path& path);

}  // namespace vstcal
