# scripts/demo's tools compile neither the hand-eye nor the stereo domain, the rig's solve or the
# formats exchanged with other tools (lib/CMakeLists.txt: vstcal_app_handeye, vstcal_app_stereo,
# vstcal_formats_exchange): on a fresh machine those would be ~200 CPU-s of the demo's build
# (docs/reliability.md#ci-time). The tools are read from scripts/demo's own build line; the
# compile commands from this build's ninja. calib-stereo and calib-handeye must compile them — the
# control that the objects' paths are what this test looks for.
#   cmake -DROOT=<source dir> -DBUILD=<build dir> -DNINJA=<ninja> -P tests/house_plan/demo_closure_test.cmake
cmake_minimum_required(VERSION 3.22)
file(STRINGS "${ROOT}/scripts/demo" build_line REGEX "scripts/build\" --demo --target ")
if(NOT build_line)
  message(FATAL_ERROR "scripts/demo: no 'scripts/build\" --demo --target …' line to read the demo's tools from")
endif()
string(REGEX REPLACE ".*--target ([^>]*)>.*" "\\1" tools "${build_line}")
separate_arguments(tools UNIX_COMMAND "${tools}")
list(LENGTH tools n)
if(n LESS 3)
  message(FATAL_ERROR "scripts/demo: read only '${tools}' as the demo's tools")
endif()

function(compiled_objects out)
  execute_process(COMMAND "${NINJA}" -C "${BUILD}" -t commands ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ninja -t commands ${ARGN} failed: ${err}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

set(kept_out vstcal_handeye.dir vstcal_stereo.dir vstcal_calib_stereo.dir vstcal_formats_exchange.dir
  vstcal_app_handeye.dir vstcal_app_stereo.dir)
set(failures "")
compiled_objects(demo ${tools})
foreach(dir IN LISTS kept_out)
  string(FIND "${demo}" "/${dir}/" at)
  if(NOT at EQUAL -1)
    string(APPEND failures "\n  scripts/demo's tools (${tools}) compile ${dir}: link the library only from the tool that runs it")
  endif()
endforeach()
compiled_objects(others calib-stereo calib-handeye calib-convert)
foreach(dir IN LISTS kept_out)
  string(FIND "${others}" "/${dir}/" at)
  if(at EQUAL -1)
    string(APPEND failures "\n  control: calib-stereo, calib-handeye and calib-convert compile no ${dir} (renamed? update this test)")
  endif()
endforeach()
if(failures)
  message(FATAL_ERROR "The demo's build:${failures}")
endif()
message(STATUS "scripts/demo's ${n} tools compile none of: ${kept_out}")
