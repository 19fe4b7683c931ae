// libmrcal 2.2's headers have no extern "C" guards and ship no CMake files (cmake/VstcalDependencies).
#pragma once

extern "C" {
#include <mrcal/mrcal.h>
}
