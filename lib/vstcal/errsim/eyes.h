// The two eyes of the VST chain, in the order every per-eye quantity follows: θ's per-eye terms
// (schema.h), the per-eye outputs (outputs.h) and the files' "left"/"right" keys. A header of its
// own so that the output table and the pages need not include the camera model.
#pragma once

#include <array>
#include <string_view>

namespace vstcal {

inline constexpr int kNumEyes = 2;
inline constexpr std::array<std::string_view, kNumEyes> kEyeNames = {"left", "right"};

}  // namespace vstcal
