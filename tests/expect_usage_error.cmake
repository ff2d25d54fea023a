# Runs PROGRAM with ARGS and expects exit code 2 and exactly one line on stderr
# (matching EXPECT when given).
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines n)
if(NOT rc EQUAL 2 OR err STREQUAL "" OR n GREATER 0)
  message(FATAL_ERROR "expected exit code 2 and one line on stderr; got ${rc}, stderr: '${err}'")
endif()
if(DEFINED EXPECT AND NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "the error does not say '${EXPECT}': '${err}'")
endif()
message(STATUS "rejected as expected: ${err}")
