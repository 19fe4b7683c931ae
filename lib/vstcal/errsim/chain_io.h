// vstcal/vst-chain@1 reader (docs/formats.md#vst-chain): the nominal chain, both cameras (inline or
// a camera@1 file, with its covariance when asked), display geometry, head motion, test points,
// the seven error sources with their distributions, samples and seed.
#pragma once

#include <filesystem>
#include <string_view>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/json/json_reader.h"

namespace vstcal::errsim {

inline constexpr std::string_view kChainFormat = "vstcal/vst-chain@1";

// Reads and validates every field; InputError "<file>: <field>: <what>; <fix>" otherwise. Camera
// files are resolved relative to the chain file's directory.
ChainModel ReadChain(const std::filesystem::path& path);
ChainModel ChainFromJson(const io::JsonDocument& doc, const std::filesystem::path& directory);

}  // namespace vstcal::errsim
