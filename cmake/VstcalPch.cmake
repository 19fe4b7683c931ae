# Precompiled headers for the test drivers and the tool mains (docs/performance.md#build). Their
# files are short and mostly parse GoogleTest, CLI11, nlohmann-json, Eigen and Ceres's Jet: a shared
# precompiled header saves 18 % of a tool file's compile and 20-35 % of a test file's. The library
# does without: its time goes to instantiating templates, which a precompiled header does not save
# (7 % on a sample, and small files got slower), and it keeps compiling every file with nothing but
# its own includes.
# What a precompiled header cannot save is code a header makes every unit emit: CLI11's help
# formatter, config reader and error classes, about 4 CPU-s a unit, so each tool and tools/common is
# one unit instead (tools/CMakeLists.txt). The Python module has none: pybind11's header cost more
# to build than its 6 units saved; one unit saved more (stop 36).
# Off under the sanitizers, so that a test or tool file leaning on a header it does not include
# still fails somewhere.
option(VSTCAL_PCH "Precompiled headers of the tests and tools (off under the sanitizers)" ON)
if(VSTCAL_SANITIZE OR VSTCAL_FUZZ)
  set(VSTCAL_PCH OFF)
endif()

set(VSTCAL_PCH_STANDARD <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <map> <memory> <optional>
  <span> <sstream> <string> <string_view> <utility> <variant> <vector>)
set(VSTCAL_PCH_NUMERICS <Eigen/Core> <Eigen/Dense> <ceres/jet.h> <nlohmann/json.hpp>)

# vstcal_pch_for_executables(TARGET): a static library linked only into executables compiles as
# they do (-fPIE, not -fPIC) so that it and they can share one precompiled header (GCC refuses a
# header built with the other setting).
function(vstcal_pch_for_executables target)
  if(VSTCAL_PCH AND CMAKE_POSITION_INDEPENDENT_CODE)
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE OFF)
    target_compile_options(${target} PRIVATE -fPIE)
  endif()
endfunction()

# vstcal_pch(TARGET OWNER [HEADERS...]): TARGET gets a precompiled header of HEADERS, or, when
# OWNER names another target, reuses that target's (which must compile with the same flags).
function(vstcal_pch target owner)
  if(NOT VSTCAL_PCH)
    return()
  endif()
  # A header that no longer matches its user's flags says so instead of silently slowing down.
  target_compile_options(${target} PRIVATE -Winvalid-pch)
  if(owner STREQUAL target)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  else()
    target_precompile_headers(${target} REUSE_FROM ${owner})
  endif()
endfunction()

