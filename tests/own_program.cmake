# Installs this build tree (the library and the program's parts) into a
# scratch prefix and builds examples/own_program, a program of one's own
# made by sympl_add_program, as an outside project; then runs it: its
# `systems` lists only its own two systems, and a scene of each runs (the
# quartic oscillator's with one method on the generic path).
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE}/examples/own_program;-B;${WORK}/own;-DCMAKE_PREFIX_PATH=${prefix}"
    "${CMAKE_COMMAND};--build;${WORK}/own;-j2"
    "${WORK}/own/my_sympl;systems"
    "${WORK}/own/my_sympl;report;${SOURCE}/examples/own_program/quartic.toml;--quick;--no-plots;--out;${WORK}/report"
    "${WORK}/own/my_sympl;run;${SOURCE}/examples/own_program/cluster.toml"
    "${WORK}/own/my_sympl;run;${SOURCE}/examples/own_program/quartic.toml")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
  if(step MATCHES ";systems$")
    set(listing "${out}")
  endif()
  if(step MATCHES "cluster.toml$")
    set(cluster "${out}")
  endif()
endforeach()
if(NOT listing MATCHES "quartic_oscillator" OR NOT listing MATCHES "planar_cluster" OR listing MATCHES "kepler")
  message(FATAL_ERROR "my_sympl systems: expected quartic_oscillator and planar_cluster alone, got:\n${listing}")
endif()
# The cluster's four methods are all compiled for it: no row on the generic path.
if(NOT cluster MATCHES "dprkn8" OR cluster MATCHES "generic path")
  message(FATAL_ERROR "my_sympl run cluster.toml: expected every row compiled, got:\n${cluster}")
endif()
foreach(expected "leapfrog_kdk" "blanes_moan_s6" "rk4" "dprkn6")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "my_sympl run quartic.toml: no row for ${expected}:\n${out}")
  endif()
endforeach()
if(NOT out MATCHES "generic")
  message(FATAL_ERROR "my_sympl run quartic.toml: dprkn6 is not compiled for the system and should be marked "
                      "generic:\n${out}")
endif()
if(NOT EXISTS ${WORK}/report/work_precision.csv)
  message(FATAL_ERROR "my_sympl report quartic.toml wrote no work_precision.csv")
endif()
# The report's default set is sympl's built-in scenes: none is of this
# program's systems, which it says.
execute_process(COMMAND ${WORK}/own/my_sympl report --quick --out ${WORK}/none RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "no built-in scene is of this program's systems \\(quartic_oscillator, planar_cluster\\)")
  message(FATAL_ERROR "my_sympl report with no scene: expected a refusal naming quartic_oscillator, got ${rc}: ${err}")
endif()
message(STATUS "a program of one's own built against the installed parts and ran:\n${out}")
