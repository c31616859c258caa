# ctest driver of one example (examples/CMakeLists.txt, geardyn_add_example): runs EXAMPLE with
# the ;-list ARGS, echoes its output, and fails when it exits non-zero or prints nothing.
execute_process(COMMAND ${EXAMPLE} ${ARGS} RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${EXAMPLE} exited with ${code}")
endif()
string(STRIP "${out}" stripped)
if(stripped STREQUAL "")
  message(FATAL_ERROR "${EXAMPLE} printed nothing")
endif()
