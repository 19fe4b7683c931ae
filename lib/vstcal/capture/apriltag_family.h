// libapriltag's families by name, owned (internal to the capture module: the one place that maps
// the names of target.h's AprilTagFamilies() to libapriltag's constructors).
#pragma once

#include <memory>
#include <string_view>

extern "C" {
#include <apriltag/apriltag.h>
}

namespace vstcal {

struct AprilTagFamilyDeleter {
  void (*destroy)(apriltag_family_t*);
  void operator()(apriltag_family_t* family) const { destroy(family); }
};
using AprilTagFamilyPtr = std::unique_ptr<apriltag_family_t, AprilTagFamilyDeleter>;

// One of AprilTagFamilies(); an internal error for another name (targets are checked first).
AprilTagFamilyPtr CreateAprilTagFamily(std::string_view name);

}  // namespace vstcal
