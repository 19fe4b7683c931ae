// calib-convert's bad-input cases, shared by the tests of each format family
// (calib_convert_test.cc: vstcal, OpenCV, mrcal; calib_convert_interop_test.cc: ROS, Kalibr):
// one parameterized test, CliCalibConvertBad.FailsWithOneLineAndNoOutput, instantiated in each.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "cli_fixture.h"

namespace vstcal::cli_test {

struct BadInput {
  std::string name;
  std::string file;  // written under in/
  std::string text;
  std::vector<std::string> flags;
  std::string location;
  std::vector<std::string> phrases;
  std::string output = "out/cam.json";
};

inline void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

class CliCalibConvertBad : public CliTest, public ::testing::WithParamInterface<BadInput> {};

}  // namespace vstcal::cli_test
