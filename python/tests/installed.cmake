# The installed package: cmake --install into a fresh prefix, then import rigid_contact_iga from
# <prefix>/<IGA_PYTHON_INSTALL_DIR> (not from the build tree) and project a point on a sphere.
# (cmake -DBIN=<build> -DWORK=<dir> -DPYTHON=<python3> -DPYDIR=<relative dir> -P this)
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BIN}" --prefix "${prefix}"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
set(script [=[
import sys, numpy as np, rigid_contact_iga as r
assert r.__file__.startswith(sys.argv[1]), r.__file__
d = r.RigidSurface([r.Sphere(1.0)]).closest_points(np.array([[0.0, 0.0, 3.0]]))["distance"][0]
assert abs(d - 2.0) < 1e-14, d
print("installed package:", r.__file__)
]=])
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYDIR}"
                        "${PYTHON}" -c "${script}" "${prefix}"
                WORKING_DIRECTORY "${WORK}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "importing the installed package failed (${rc}):\n${out}\n${err}")
endif()
message(STATUS "${out}")
