// calib-convert's flags and what they decide (formats from the names or --to, flags that would
// change nothing refused), then the conversion as an Outcome.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "vstcal/app/outcome.h"
#include "vstcal/json/provenance.h"

namespace vstcal::tools {

struct ConvertFlags {
  std::string input, output, output_right, to, unit, mrcal_model;

  void Add(CLI::App& app);
  // The files to write (one, or a rig's two ROS files) and the notes and summary for stderr.
  app::Outcome Convert(const Provenance& provenance) const;
};

}  // namespace vstcal::tools
