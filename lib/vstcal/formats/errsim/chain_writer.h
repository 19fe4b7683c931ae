// The canonical vstcal/vst-chain@1 writer (docs/formats.md#vst-chain): a ChainSpec in one layout —
// fields in the documented order, defaults written out (world_from_virtual, eye_centre,
// virtual_image_distance, head_motion), distributions as {"distribution", "mean", "sigma"},
// {"distribution", "min", "max"} or {"distribution", "value"} with one number for equal
// components, transforms and camera references as written. Reading what it writes gives the same
// ChainSpec, so writing that again gives the same bytes (`err-sim normalize`).
#pragma once

#include "vstcal/formats/errsim/chain_spec.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// `provenance` is written unless the chain has its own (kept as read).
OrderedJson ChainSpecToJson(const ChainSpec& spec, const Provenance& provenance);

}  // namespace vstcal
