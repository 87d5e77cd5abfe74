# An installed capstan reads its model from <prefix>/share/iga-contact, not from the source
# tree: install into a fresh prefix, break the installed model (EA = -3), and expect the
# capstan to reject it naming the installed file. (cmake -DBIN=<build> -DPREFIX=<dir> -P this)
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BIN}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
set(model "${PREFIX}/share/iga-contact/data/capstan.json")
foreach(f bin/capstan bin/helix bin/saddle bin/iga share/iga-contact/data/capstan.json
          share/iga-contact/scripts/plot_capstan.py share/iga-contact/scripts/plot_common.py)
  if(NOT EXISTS "${PREFIX}/${f}")
    message(FATAL_ERROR "not installed: ${PREFIX}/${f}")
  endif()
endforeach()
file(READ "${model}" text)
string(REGEX REPLACE "\"EA\": *[0-9.eE+-]+" "\"EA\": -3" text "${text}")
file(WRITE "${model}" "${text}")
execute_process(COMMAND "${PREFIX}/bin/capstan" --quick --out "${PREFIX}/out"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "share/iga-contact/data/capstan.json: /materials/rope/EA: must be > 0")
  message(FATAL_ERROR "the installed capstan did not read the installed model: exit ${rc}, ${err}")
endif()
message(STATUS "installed capstan read ${model}: ${err}")
