#include "vstcal/capture/apriltag_family.h"

#include <string>

extern "C" {
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h10.h>
#include <apriltag/tag36h11.h>
}

#include "vstcal/core/error.h"

namespace vstcal {

AprilTagFamilyPtr CreateAprilTagFamily(std::string_view name) {
  if (name == "tag36h11") return AprilTagFamilyPtr(tag36h11_create(), {tag36h11_destroy});
  if (name == "tag36h10") return AprilTagFamilyPtr(tag36h10_create(), {tag36h10_destroy});
  if (name == "tag25h9") return AprilTagFamilyPtr(tag25h9_create(), {tag25h9_destroy});
  if (name == "tag16h5") return AprilTagFamilyPtr(tag16h5_create(), {tag16h5_destroy});
  VSTCAL_CHECK(false, "unknown AprilTag family " + std::string(name));
}

}  // namespace vstcal
