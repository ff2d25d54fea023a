# Installs this build tree into a scratch prefix and imports the Python
# module from there, with the build tree out of the path: it runs a method
# and reads the installed module's file, which must be under the prefix.
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix} RESULT_VARIABLE rc OUTPUT_QUIET
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${err}")
endif()
set(check "import sympl; r = sympl.System('pendulum').run('leapfrog_kdk', t_end=1.0, dt=0.1); print(r['steps'], sympl.__file__)")
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${MODULE_DIR} ${PYTHON} -c "${check}"
                WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^10 ${prefix}/")
  message(FATAL_ERROR "import sympl from ${prefix}/${MODULE_DIR} failed (${rc}):\n${out}\n${err}")
endif()
