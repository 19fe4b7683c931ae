# Precompiled headers for the test drivers and the tool mains (docs/performance.md#build). Their
# files are short and mostly parse GoogleTest, CLI11, nlohmann-json, Eigen and Ceres's Jet: a shared
# precompiled header saves 18 % of a tool file's compile and 20-35 % of a test file's. The library
# has its own since stop 36 (vstcal_library_pch, below: lighter for its small files).
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


# ---- The library's precompiled header (stop 36, docs/performance.md#build) ------------------------
# vstcal_library_pch(TARGET... JSON TARGET...): the library's static libraries share precompiled
# headers, each built once, by the first target of its group, and reused by the others. Since stop
# 35 moved Eigen's decompositions into geometry/linalg.cc, parsing headers is most of a typical
# library file's compile; but loading a header costs every file that uses it, ~1 CPU-s for the
# tests' set (nlohmann-json and Eigen/Dense in it), which more than doubles a small file's compile.
# So the foundations and the domains take the light set (the standard headers, Eigen/Core, Ceres's
# Jet), and the targets listed after JSON — the formats, the pages, the application, whose files
# read and write JSON, and the report domain, which shares the pages' -O1 — the tests' set. GCC takes a header only with its user's flags: the glue
# libraries (vstcal_glue_flags: -O1) get their own. On 29 sample files, back to back: the formats'
# and the application's 20 % less with the JSON set (8 % with the light one), the others 11 % less
# with the light one (6 % with the JSON set; docs/performance.md#build, stop 36).
# The sanitizer and fuzz builds (VSTCAL_PCH off) compile each file with its own includes alone,
# so a file that leans on a header it does not include still fails there.
set(VSTCAL_PCH_LIBRARY ${VSTCAL_PCH_STANDARD} <Eigen/Core> <ceres/jet.h>)
function(vstcal_library_pch)
  set(json FALSE)
  foreach(target IN LISTS ARGN)
    if(target STREQUAL "JSON")
      set(json TRUE)
      continue()
    endif()
    # The group is the target's own optimisation flag, if it has one (vstcal_opt_flags): a header
    # is shared only by targets compiled at the same level.
    get_target_property(options ${target} COMPILE_OPTIONS)
    set(group "opt")
    if(options)
      foreach(flag IN LISTS options)
        if(flag MATCHES "^-O")
          string(MAKE_C_IDENTIFIER "${flag}" group)
        endif()
      endforeach()
    endif()
    set(headers ${VSTCAL_PCH_LIBRARY})
    if(json)
      string(APPEND group "_json")
      set(headers ${VSTCAL_PCH_STANDARD} ${VSTCAL_PCH_NUMERICS})
    endif()
    if(NOT owner_${group})
      set(owner_${group} ${target})
    endif()
    vstcal_pch(${target} ${owner_${group}} ${headers})
  endforeach()
endfunction()
# ---- end of the library's precompiled header ------------------------------------------------------

# ---- The library's light folders as unity units (stop 37, docs/performance.md#build) --------------
# vstcal_library_unity(TARGET [BATCH N] FOLDERS folder... [ALONE file...]): TARGET's files in each
# FOLDER (under lib/vstcal/) are compiled N at a time as one unit (0: the whole folder), in the
# folder's order, split evenly. Most of a light library file's compile is what every unit pays
# again — loading the precompiled header, parsing the headers not in it, instantiating
# nlohmann-json, std::format and Eigen's expressions — so a unit of several files pays it once.
# Not the heavy files (ALONE, over ~8 CPU-s each in the cold build's log): their compile is their
# own instantiations, which a unity unit does not share and can make slower (estimators/ as one
# unit took twice the CPU of its files apart, stop 27). Groups stay inside a folder, so file-local
# names need only differ between the files of one folder (a folder of one file stays as it is). Only with VSTCAL_PCH, like the tools' units: under the
# sanitizers and in the fuzz build each file still compiles alone, so one that leans on an include
# only its neighbour makes still fails somewhere.
# VSTCAL_LIBRARY_UNITY_BATCH overrides every folder's N (1: each file alone), for measuring.
set(VSTCAL_LIBRARY_UNITY_BATCH "" CACHE STRING "Files per unity unit of the library's light folders (empty: each folder's own; 1: off)")
function(vstcal_library_unity target)
  cmake_parse_arguments(ARG "" "BATCH" "FOLDERS;ALONE" ${ARGN})
  if(NOT VSTCAL_PCH)
    return()
  endif()
  set(batch 0)
  if(DEFINED ARG_BATCH)
    set(batch ${ARG_BATCH})
  endif()
  if(NOT VSTCAL_LIBRARY_UNITY_BATCH STREQUAL "")
    set(batch ${VSTCAL_LIBRARY_UNITY_BATCH})
  endif()
  if(batch EQUAL 1)
    return()
  endif()
  get_target_property(sources ${target} SOURCES)
  foreach(file IN LISTS ARG_ALONE)
    if(NOT file IN_LIST sources)
      message(FATAL_ERROR "vstcal_library_unity: ${file} (ALONE) is not a source of ${target}")
    endif()
  endforeach()
  foreach(folder IN LISTS ARG_FOLDERS)
    set(members "")
    foreach(file IN LISTS sources)
      get_filename_component(dir ${file} DIRECTORY)
      if(dir STREQUAL "vstcal/${folder}" AND NOT file IN_LIST ARG_ALONE)
        list(APPEND members ${file})
      endif()
    endforeach()
    list(LENGTH members n)
    if(n EQUAL 0)
      message(FATAL_ERROR "vstcal_library_unity: ${target} has no file in lib/vstcal/${folder} to unify")
    endif()
    if(n EQUAL 1)
      continue()
    endif()
    set(groups 1)
    if(batch GREATER 0)
      math(EXPR groups "(${n} + ${batch} - 1) / ${batch}")
    endif()
    string(REPLACE "/" "_" stem ${folder})
    set(i 0)
    foreach(file IN LISTS members)
      math(EXPR g "${i} * ${groups} / ${n}")
      set_source_files_properties(${file} PROPERTIES UNITY_GROUP ${stem}_${g})
      math(EXPR i "${i} + 1")
    endforeach()
  endforeach()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE GROUP)
endfunction()
# ---- end of the library's unity units -------------------------------------------------------------
