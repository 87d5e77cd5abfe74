# mpirun -n 2 iga run on the indented plate refined to one element (it cannot be cut into 2
# blocks of at least one element): exit status 1, the model error said once (by process 0,
# naming the surface's JSON path), no abort of the processes.
execute_process(
  COMMAND ${MPIEXEC} --oversubscribe -n 2 ${IGA} run ${MODEL}
          --set /geometry/plate/refine/subdivide=1 --out ${OUT} --quiet
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 100)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "exit status ${status}, expected 1\nstdout:\n${out}\nstderr:\n${err}")
endif()
string(REGEX MATCHALL "cannot be cut into 2 blocks" said "${err}")
list(LENGTH said times)
if(NOT times EQUAL 1)
  message(FATAL_ERROR "the error said ${times} times, expected once\nstderr:\n${err}")
endif()
if(NOT err MATCHES "/bodies/plate/surface" OR err MATCHES "MPI_ABORT")
  message(FATAL_ERROR "not the model error at its path, or the processes were aborted:\n${err}")
endif()
