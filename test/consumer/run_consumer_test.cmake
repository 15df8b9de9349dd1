# SPDX-License-Identifier: GPL-3.0-or-later
#
# The install test, run by CTest as
#   cmake -DPROJECT_BUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=...
#         [-DGENERATOR=...] [-DWITH_EXAMPLE=ON] -P run_consumer_test.cmake
# 1. installs the built project into WORK_DIR/prefix (cmake --install --prefix);
# 2. checks the installed headers: export.h is there, every <pcl/cocone/...> they
#    include is installed too, and none includes CGAL (CGAL stays private to the
#    library, so users need neither CGAL nor its GPL headers to build against it);
# 3. configures, builds and runs test/consumer against that prefix only, together with
#    the pipeline example's source as installed under share/doc;
# 4. runs the installed cocone_pipeline (found through its $ORIGIN RPATH) on its demo.
# WITH_EXAMPLE (set when the tools are built) enables the example parts of 3 and 4.
# CONSUMER_PROGRAM names the consumer's executable (default: consumer).
cmake_minimum_required(VERSION 3.16)

foreach(var PROJECT_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_consumer_test.cmake: -D${var}=... is required")
  endif()
endforeach()

if(NOT CONSUMER_PROGRAM)
  set(CONSUMER_PROGRAM consumer)
endif()
set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# Runs a command, echoing it; stops the test with its output on failure.
function(run_step what)
  list(JOIN ARGN " " command)
  message(STATUS "${what}: ${command}")
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}):\n${output}")
  endif()
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

# --- 1. install -------------------------------------------------------------------
run_step("install" ${CMAKE_COMMAND} --install ${PROJECT_BUILD_DIR} --prefix ${prefix})

# --- 2. installed headers ---------------------------------------------------------
if(NOT EXISTS ${prefix}/include/pcl/cocone/export.h)
  message(FATAL_ERROR "include/pcl/cocone/export.h (generated) is not installed")
endif()
file(GLOB_RECURSE headers LIST_DIRECTORIES false ${prefix}/include/*)
if(NOT headers)
  message(FATAL_ERROR "no header installed under ${prefix}/include")
endif()
set(problems "")
foreach(header IN LISTS headers)
  file(READ ${header} text)
  file(RELATIVE_PATH name ${prefix}/include ${header})
  if(text MATCHES "CGAL/")
    string(APPEND problems "  ${name} mentions CGAL/\n")
  endif()
  string(REGEX MATCHALL "#[ \t]*include[ \t]*[<\"]pcl/cocone/[^>\"]+" includes "${text}")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE ".*[<\"]" "" included "${line}")
    if(NOT EXISTS ${prefix}/include/${included})
      string(APPEND problems "  ${name} includes ${included}, which is not installed\n")
    endif()
  endforeach()
endforeach()
if(problems)
  message(FATAL_ERROR "installed headers:\n${problems}")
endif()
list(LENGTH headers header_count)
message(STATUS "installed headers: ${header_count}, none includes CGAL, export.h present")

# --- 3. a downstream project against the prefix -----------------------------------
set(example_args "")
if(WITH_EXAMPLE)
  file(GLOB example ${prefix}/share/doc/*/examples/cocone_pipeline.cpp)
  if(NOT example)
    message(FATAL_ERROR "the pipeline example's source is not installed under share/doc")
  endif()
  set(example_args -DPCL_COCONE_EXAMPLE_SOURCE=${example})
endif()
set(generator_args "")
if(GENERATOR)
  set(generator_args -G ${GENERATOR})
endif()
run_step("configure consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${build}
  ${generator_args} -DCMAKE_PREFIX_PATH=${prefix} ${example_args})
run_step("build consumer" ${CMAKE_COMMAND} --build ${build} --parallel 2)
run_step("run consumer" ${build}/${CONSUMER_PROGRAM})
message(STATUS "${step_output}")
if(NOT WITH_EXAMPLE)
  message(STATUS "install test passed (tools not built: example not checked)")
  return()
endif()
run_step("run example built from share/doc" ${build}/cocone_pipeline_from_doc -h)

# --- 4. the installed example -----------------------------------------------------
run_step("installed cocone_pipeline --demo" ${prefix}/bin/cocone_pipeline
  --demo ${WORK_DIR}/demo)
if(NOT step_output MATCHES "demo result as expected")
  message(FATAL_ERROR "installed cocone_pipeline --demo:\n${step_output}")
endif()
message(STATUS "install test passed")
