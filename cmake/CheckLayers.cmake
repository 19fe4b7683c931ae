# The house plan of docs/architecture.md, checked over the include graph: every
# `#include "vstcal/<folder>/…"` of lib/, tools/ and python/ must go down a floor, or sideways where the
# floor allows it. Run by the build before anything compiles (target vstcal_layers), so a broken
# rule fails the build with the file, the line and the rule:
#   cmake -DROOT=<source dir> [-DSTAMP=<file>] -P cmake/CheckLayers.cmake
#
# Nodes are lib/vstcal's folders (formats/<domain> each a node of its own), `tools` and `python`
# (the Python module's bindings, a main of their own). Each has a
# floor and a rank; an include from A to B is allowed when
#   floor(B) < floor(A), or
#   A == B, or
#   floor(A) == floor(B) on a floor whose folders may stand on each other (foundations, formats and
#   pages) and rank(B) < rank(A): a fixed order, so no loop can form.
# Domains (floor 2) never include each other: what two domains share moves down to the foundations.
# A domain's model (cmake/DomainModels.cmake: the value types its files hold, a library under its
# algorithms) includes only the foundations and its own model, so the formats floor can link a
# model without the domain's solvers.

cmake_minimum_required(VERSION 3.22)

if(NOT ROOT)
  message(FATAL_ERROR "CheckLayers.cmake: pass -DROOT=<vstcal source dir>")
endif()

# Floor 1, in rank order: each may include the ones before it.
set(floor_1 core random geometry files json sensitivity camera image scene estimators)
# Floor 2: the domains, side by side.
set(floor_2 calib stereo capture handeye errsim report)
# Floor 3, in rank order: the formats of each domain, then the pages that show them.
set(floor_3 formats/camera formats/calib formats/stereo formats/capture formats/handeye formats/report
            formats/errsim pages)
set(floor_4 app)
include("${ROOT}/cmake/DomainModels.cmake")
foreach(domain IN LISTS vstcal_domain_models)
  foreach(stem IN LISTS vstcal_model_${domain})
    set(model_of_${stem} ${domain})
  endforeach()
endforeach()
set(floor_5 tools python)
set(sideways_floors 1 3)

foreach(floor 1 2 3 4 5)
  set(rank 0)
  foreach(node IN LISTS floor_${floor})
    set(floor_of_${node} ${floor})
    set(rank_of_${node} ${rank})
    math(EXPR rank "${rank} + 1")
  endforeach()
endforeach()

# The node of a path under lib/vstcal/ ("formats/errsim/x.h" → formats/errsim, "calib/x.h" → calib).
function(node_of path out)
  if(path MATCHES "^formats/([^/]+)/")
    set(${out} "formats/${CMAKE_MATCH_1}" PARENT_SCOPE)
  elseif(path MATCHES "^([^/]+)/")
    set(${out} "${CMAKE_MATCH_1}" PARENT_SCOPE)
  else()
    set(${out} "" PARENT_SCOPE)
  endif()
endfunction()

file(GLOB_RECURSE lib_files RELATIVE "${ROOT}/lib/vstcal" "${ROOT}/lib/vstcal/*.h" "${ROOT}/lib/vstcal/*.cc")
file(GLOB_RECURSE tool_files RELATIVE "${ROOT}" "${ROOT}/tools/*.h" "${ROOT}/tools/*.cc" "${ROOT}/python/*.h"
     "${ROOT}/python/*.cc")

set(broken "")
set(files "")
foreach(f IN LISTS lib_files)
  list(APPEND files "lib/vstcal/${f}")
endforeach()
list(APPEND files ${tool_files})

foreach(file IN LISTS files)
  if(file MATCHES "^tools/")
    set(from tools)
  elseif(file MATCHES "^python/")
    set(from python)
  else()
    string(REGEX REPLACE "^lib/vstcal/" "" rel "${file}")
    node_of("${rel}" from)
  endif()
  if(NOT DEFINED floor_of_${from})
    string(APPEND broken "\n  ${file}: folder '${from}' is on no floor of docs/architecture.md; add it to cmake/CheckLayers.cmake and the plan")
    continue()
  endif()
  string(REGEX REPLACE "^lib/vstcal/(.*)\\.(h|cc)$" "\\1" stem "${file}")
  set(model "")
  if(DEFINED model_of_${stem})
    set(model ${model_of_${stem}})
  endif()
  file(STRINGS "${ROOT}/${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"vstcal/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"vstcal/([^\"]+)\".*" "\\1" target "${line}")
    node_of("${target}" to)
    if(model)
      string(REGEX REPLACE "\\.(h|cc)$" "" target_stem "${target}")
      if(NOT to STREQUAL "" AND NOT "${floor_of_${to}}" STREQUAL "1" AND NOT "${model_of_${target_stem}}" STREQUAL "${model}")
        string(APPEND broken "\n  ${file}: #include \"vstcal/${target}\": ${model}'s model (cmake/DomainModels.cmake) includes only the foundations and its own model")
        continue()
      endif()
    endif()
    if(to STREQUAL "" OR to STREQUAL from)
      continue()
    endif()
    if(NOT DEFINED floor_of_${to})
      string(APPEND broken "\n  ${file}: includes vstcal/${target}, whose folder '${to}' is on no floor")
      continue()
    endif()
    set(fa ${floor_of_${from}})
    set(fb ${floor_of_${to}})
    if(fb LESS fa)
      continue()
    endif()
    if(fb EQUAL fa AND fa IN_LIST sideways_floors AND rank_of_${to} LESS rank_of_${from})
      continue()
    endif()
    if(fb EQUAL fa)
      if(fa EQUAL 2)
        set(why "a domain includes another domain (move what they share down to the foundations)")
      else()
        set(why "'${to}' stands above '${from}' on floor ${fa} (cmake/CheckLayers.cmake's order)")
      endif()
    else()
      set(why "floor ${fa} ('${from}') includes floor ${fb} ('${to}'): includes only go down")
    endif()
    string(APPEND broken "\n  ${file}: #include \"vstcal/${target}\": ${why}")
  endforeach()
endforeach()

# Library messages name a request's options (core/option_name.h: VSTCAL_OPT("tilt_deg")), never one
# front end's spelling of them: a string literal in lib/ that spells a flag ("--tilt-deg") breaks
# the plan. A line that must (a file's header naming the command that wrote it, a peer tool's own
# command line) says "house-plan: names a command" in its comment.
foreach(f IN LISTS lib_files)
  if(NOT f MATCHES "\\.(cc|h)$")
    continue()
  endif()
  file(STRINGS "${ROOT}/lib/vstcal/${f}" spelled REGEX "\"[^\"]*--[a-z]")
  foreach(line IN LISTS spelled)
    if(NOT line MATCHES "house-plan: names a command" AND NOT line MATCHES "^[ \t]*//")
      string(STRIP "${line}" line)
      string(APPEND broken "\n  lib/vstcal/${f}: a flag spelled in a library message (name the option with VSTCAL_OPT): ${line}")
    endif()
  endforeach()
endforeach()

if(broken)
  message(FATAL_ERROR "The house plan (docs/architecture.md) is broken:${broken}")
endif()
if(STAMP)
  file(TOUCH "${STAMP}")
endif()
