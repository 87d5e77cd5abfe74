# A downstream project builds against the installed tree: install into a fresh prefix, configure
# tests/install/downstream with find_package(rigid_contact_iga), build it, run it on the installed
# rollup model, and expect the rolled-up rod's tip back at its clamp (the closed circle of
# rollup.json: |tip - clamp| < 1e-3 L, L = 12, as tests/iga/model/test_analysis.cpp).
# (cmake -DBIN=<build> -DSRC=<tests/install/downstream> -DWORK=<dir> -P this)
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BIN}" --prefix "${prefix}"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
foreach(f lib/cmake/rigid_contact_iga/rigid_contact_igaConfig.cmake
          include/rigid_contact_iga/iga/model/analysis.hpp include/rigid_contact_iga/iga/core/body.hpp)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SRC}" -B "${WORK}/build" -G Ninja
                        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the downstream project failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK}/build"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the downstream project failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${WORK}/build/downstream" "${prefix}/share/iga-contact/data/rollup.json"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "tip to clamp distance ([0-9.eE+-]+)")
  message(FATAL_ERROR "the downstream program failed (${rc}):\n${out}\n${err}")
endif()
set(d "${CMAKE_MATCH_1}")
if(NOT d LESS 0.012)
  message(FATAL_ERROR "the downstream program's rod did not close the circle: ${d}\n${out}")
endif()
message(STATUS "downstream program: ${out}")
