# Precompiled headers for the test drivers and the tool mains (docs/performance.md#build). Their
# files are short and mostly parse GoogleTest, CLI11, nlohmann-json, Eigen and Ceres's Jet: a shared
# precompiled header saves 18 % of a tool file's compile and 20-35 % of a test file's. The library
# does without: its time goes to instantiating templates, which a precompiled header does not save
# (7 % on a sample, and small files got slower), and it keeps compiling every file with nothing but
# its own includes.
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


# ---- The library's precompiled header (stop 36, docs/performance.md#build) ------------------------
# vstcal_library_pch(TARGET...): the library's static libraries share one precompiled header of the
# standard set and the numerics (Eigen, Ceres's Jet, nlohmann-json), built with vstcal_foundations,
# the floor every other one stands on. GCC takes a header only with its user's flags, so the glue
# libraries (vstcal_glue_flags: -O1) share a second one, built with the first of them. Since stop 35
# moved Eigen's decompositions into geometry/linalg.cc, parsing headers is most of a typical library
# file's compile: FIGURE-TBD.
# The sanitizer and fuzz builds (VSTCAL_PCH off) compile each file with its own includes alone,
# so a file that leans on a header it does not include still fails there.
function(vstcal_library_pch)
  set(owner "")
  set(glue_owner "")
  foreach(target IN LISTS ARGN)
    get_target_property(options ${target} COMPILE_OPTIONS)
    set(glue FALSE)
    if(options AND VSTCAL_GLUE_OPT)
      set(glue TRUE)
      foreach(flag IN LISTS VSTCAL_GLUE_OPT)
        if(NOT flag IN_LIST options)
          set(glue FALSE)
        endif()
      endforeach()
    endif()
    if(glue)
      if(NOT glue_owner)
        set(glue_owner ${target})
      endif()
      vstcal_pch(${target} ${glue_owner} ${VSTCAL_PCH_STANDARD} ${VSTCAL_PCH_NUMERICS})
    else()
      if(NOT owner)
        set(owner ${target})
      endif()
      vstcal_pch(${target} ${owner} ${VSTCAL_PCH_STANDARD} ${VSTCAL_PCH_NUMERICS})
    endif()
  endforeach()
endfunction()
# ---- end of the library's precompiled header ------------------------------------------------------
