# Every dependency comes from a Debian bookworm package; scripts/setup installs them.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Ceres REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core calib3d imgproc imgcodecs videoio aruco)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(apriltag REQUIRED)
find_package(Threads REQUIRED)
find_package(Qhull REQUIRED CONFIG)  # the measured volume: the calibration points' convex hull (libqhull_r)
find_package(PkgConfig REQUIRED)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)  # libyaml: ROS camera_info and Kalibr camchain YAML
# Boost.Random (header-only) for the Sobol quasi-random sequence of lib/vstcal/sensitivity.
find_package(Boost 1.74 REQUIRED)

# What only the tests need (scripts/setup's test rows): scripts/build --demo configures without them.
if(VSTCAL_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(ZLIB REQUIRED)  # an independent CRC-32 for the PNG chunks vstcal writes
  # libmrcal 2.2 ships neither CMake nor pkg-config files, and its headers have no extern "C"
  # guards: tests/support/mrcal.h, the one place that includes them, wraps them in extern "C" { }.
  find_library(MRCAL_LIBRARY NAMES mrcal REQUIRED)
  find_path(MRCAL_INCLUDE_DIR NAMES mrcal/mrcal.h REQUIRED)
  add_library(vstcal_mrcal INTERFACE)
  target_link_libraries(vstcal_mrcal INTERFACE ${MRCAL_LIBRARY})
  target_include_directories(vstcal_mrcal SYSTEM INTERFACE ${MRCAL_INCLUDE_DIR})
endif()
if(VSTCAL_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
