// The canonical vstcal/vst-chain@1 writer (docs/formats.md#vst-chain): a ChainSpec in one layout —
// fields in the documented order, defaults written out (world_from_virtual, eye_centre,
// virtual_image_distance, head_motion), distributions as {"distribution", "mean", "sigma"},
// {"distribution", "min", "max"} or {"distribution", "value"} with one number for equal
// components, transforms and camera references as written. Reading what it writes gives the same
// ChainSpec, so writing that again gives the same bytes (`err-sim normalize`).
#pragma once

#include "vstcal/errsim/formats/chain_spec.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal::errsim {

// `provenance` is written unless the chain has its own (kept as read).
io::OrderedJson ChainSpecToJson(const ChainSpec& spec, const io::Provenance& provenance);

}  // namespace vstcal::errsim
