# The house plan's check (cmake/CheckLayers.cmake) must fail the build on each rule it enforces, not
# only pass on today's tree: on a copy of the sources, each broken rule is put in on its own and the
# check must exit non-zero naming the file and the rule; the untouched copy must pass.
#   cmake -DROOT=<source dir> -DWORK=<scratch dir> -P tests/house_plan/check_layers_test.cmake
cmake_minimum_required(VERSION 3.22)
if(NOT ROOT OR NOT WORK)
  message(FATAL_ERROR "check_layers_test.cmake: pass -DROOT=<source dir> -DWORK=<scratch dir>")
endif()

set(failures "")

function(copy_tree)
  file(REMOVE_RECURSE "${WORK}")
  file(MAKE_DIRECTORY "${WORK}/lib")
  file(COPY "${ROOT}/lib/vstcal" DESTINATION "${WORK}/lib")
  file(COPY "${ROOT}/tools" "${ROOT}/python" "${ROOT}/cmake" DESTINATION "${WORK}")
endfunction()

function(run_check out_rc out_text)
  execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK} -P "${WORK}/cmake/CheckLayers.cmake"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${out_rc} "${rc}" PARENT_SCOPE)
  set(${out_text} "${out}${err}" PARENT_SCOPE)
endfunction()

# expect_broken(NAME FILE LINE EXPECTED...): FILE (under WORK) gets LINE appended; the check must
# fail and its message contain FILE and every EXPECTED text.
function(expect_broken name file line)
  copy_tree()
  file(APPEND "${WORK}/${file}" "\n${line}\n")
  run_check(rc text)
  if(rc EQUAL 0)
    string(APPEND failures "\n  ${name}: the check passed with ${file} including what it may not")
  else()
    foreach(expected IN ITEMS ${file} ${ARGN})
      string(FIND "${text}" "${expected}" at)
      if(at EQUAL -1)
        string(APPEND failures "\n  ${name}: the message does not say '${expected}':\n${text}")
      endif()
    endforeach()
  endif()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()

copy_tree()
run_check(rc text)
if(NOT rc EQUAL 0)
  string(APPEND failures "\n  the untouched tree fails the check:\n${text}")
endif()

expect_broken("a foundation includes a domain" lib/vstcal/geometry/rotation.cc
  "#include \"vstcal/calib/pipeline.h\"" "includes only go down")
expect_broken("a domain includes another domain" lib/vstcal/stereo/rectify.cc
  "#include \"vstcal/calib/pipeline.h\"" "a domain includes another domain")
expect_broken("a domain includes the formats floor" lib/vstcal/errsim/budget.cc
  "#include \"vstcal/formats/errsim/report_format.h\"" "includes only go down")
expect_broken("a model includes its domain's algorithms" lib/vstcal/capture/target.cc
  "#include \"vstcal/capture/detect.h\"" "capture's model" "cmake/DomainModels.cmake")
expect_broken("a foundation out of its floor's order" lib/vstcal/core/error.cc
  "#include \"vstcal/estimators/dlt.h\"" "stands above")
expect_broken("a library message spells a flag" lib/vstcal/calib/tsai.cc
  "const char* kHouseplanTestFlag = \"use --tilt-deg\";" "lib/vstcal/calib/tsai.cc")

file(REMOVE_RECURSE "${WORK}")
if(failures)
  message(FATAL_ERROR "cmake/CheckLayers.cmake does not enforce the plan:${failures}")
endif()
message(STATUS "cmake/CheckLayers.cmake: the untouched tree passes and each of 6 broken rules fails it")
