# Installs sympl into a scratch prefix and builds examples/ as an outside
# project that only does find_package(sympl) and links sympl::sympl. The
# largest example, api_tour, is built once, by the project with nothing but
# CMake's defaults (tests/consumer/), not again in Release.
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE};-B;${WORK}/sympl;-DSYMPL_BUILD_TESTS=OFF;-DSYMPL_BUILD_BENCH=OFF;-DSYMPL_BUILD_PROGRAM=OFF;-DCMAKE_INSTALL_PREFIX=${prefix}"
    "${CMAKE_COMMAND};--install;${WORK}/sympl"
    "${CMAKE_COMMAND};-S;${SOURCE}/examples;-B;${WORK}/examples;-DCMAKE_PREFIX_PATH=${prefix}"
    "${CMAKE_COMMAND};--build;${WORK}/examples;-j2;--target;quickstart;oscillator_energy;loop_area"
    "${WORK}/examples/quickstart"
    "${CMAKE_COMMAND};-S;${SOURCE}/tests/consumer;-B;${WORK}/defaults;-DCMAKE_PREFIX_PATH=${prefix}"
    "${CMAKE_COMMAND};--build;${WORK}/defaults;-j2"
    "${WORK}/defaults/api_tour")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "example built against the installed package and ran:\n${out}")
