# SPDX-License-Identifier: GPL-3.0-or-later
#
# The Python module's install test, run by CTest as
#   cmake -DPROJECT_BUILD_DIR=... -DWORK_DIR=... -DPYTHON=... -DMODULE_DIR=... -P ...
# installs the built project into WORK_DIR/prefix (cmake --install --prefix) and
# imports the module from MODULE_DIR under that prefix, with nothing of the build tree
# on the path: the installed module must find the installed library through its
# RPATH, and reconstruct a small sphere.
cmake_minimum_required(VERSION 3.16)

foreach(var PROJECT_BUILD_DIR WORK_DIR PYTHON MODULE_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_install_test.cmake: -D${var}=... is required")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${PROJECT_BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "install failed (${result}):\n${output}")
endif()

set(site ${prefix}/${MODULE_DIR})
set(check [=[
import sys, numpy, pcl_cocone
assert pcl_cocone.__file__.startswith(sys.argv[1]), pcl_cocone.__file__
p = numpy.random.default_rng(1).normal(size=(500, 3))
p /= numpy.linalg.norm(p, axis=1, keepdims=True)
mesh = pcl_cocone.reconstruct(p)
assert len(mesh.triangles) == 996, len(mesh.triangles)
print("installed module:", pcl_cocone.__file__)
]=])
# env -i: no PYTHONPATH or LD_LIBRARY_PATH of the caller can help the module; and the
# folder it runs in comes first on sys.path with -c, so not the build's.
execute_process(
  COMMAND env -i PYTHONPATH=${site} PYTHONDONTWRITEBYTECODE=1 ${PYTHON} -c "${check}" ${site}
  WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message(STATUS "${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the installed module does not work (${result})")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
