# Checks the code blocks of README.md and docs/*.md.
#
#   cmake -DSOURCE=<repository> -DWORK=<scratch directory> [-DJOBS=2] [-DONLY=<regex>] -P tests/doc_snippets.cmake
#
# (ONLY: check only the pages whose path relative to SOURCE matches, e.g. docs/odeint.md.)
#
# ```cpp blocks: sympl is installed into WORK/prefix (header-only configure),
# and every block becomes one program of a generated CMake project that only
# does find_package(sympl) and links sympl::sympl. The rule for a block:
#   - it contains "int main": it is compiled as it stands, as a whole file;
#   - otherwise its "#include" lines are moved to the top of the file and all
#     its other lines become the body of int main() { ... }.
# So a block that needs declarations at namespace scope (a struct with member
# templates, a function) writes its own main(). Each program is built and run
# (a block that throws or returns non-zero fails too).
#
# ```sh blocks: the first line is "# not run by CI: <why>", or every command in
# the block is one CI runs (the two set-up commands of README.md, listed below;
# change them here when they change there, and keep .ci/run in step).
#
# Only fences at the start of a line are read. The first bad block fails the
# script with FILE:LINE.
cmake_minimum_required(VERSION 3.25)
if(NOT SOURCE OR NOT WORK)
  message(FATAL_ERROR "usage: cmake -DSOURCE=<repository> -DWORK=<scratch directory> -P doc_snippets.cmake")
endif()
get_filename_component(SOURCE "${SOURCE}" ABSOLUTE)
get_filename_component(WORK "${WORK}" ABSOLUTE)
if(NOT JOBS)
  set(JOBS 2)
endif()
string(FIND "${SOURCE}/" "${WORK}/" inside)
if(inside EQUAL 0)
  message(FATAL_ERROR "WORK = ${WORK} holds SOURCE = ${SOURCE}; expected a scratch directory elsewhere (it is emptied)")
endif()

# The commands CI runs: README.md's set-up commands, verbatim.
set(ci_command_1 [==[pkgs="cmake g++ make libeigen3-dev libboost-dev doctest-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev gnuplot-nox libopenmpi-dev openmpi-bin libboost-mpi-dev"; dpkg -s $pkgs >/dev/null 2>&1 || { apt-get update && apt-get install -y --no-install-recommends $pkgs; }; cmake -S . -B build && cmake --build build -j2 --target sympl_program && build/sympl report --quick]==])
set(ci_command_2 [==[pkgs="cmake g++ make libeigen3-dev libboost-dev doctest-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev gnuplot-nox libopenmpi-dev openmpi-bin libboost-mpi-dev pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib"; dpkg -s $pkgs >/dev/null 2>&1 || { apt-get update && apt-get install -y --no-install-recommends $pkgs; }; cmake -S . -B build && cmake --build build -j2 && (cd build && ctest -j2 -LE packaging --output-on-failure)]==])

# Lines travel through CMake lists: ';', brackets and backslashes are encoded while they do.
function(encode text out)
  string(REPLACE "\\" "@BS@" text "${text}")
  string(REPLACE ";" "@SC@" text "${text}")
  string(REPLACE "[" "@LB@" text "${text}")
  string(REPLACE "]" "@RB@" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()
function(decode text out)
  string(REPLACE "@SC@" ";" text "${text}")
  string(REPLACE "@LB@" "[" text "${text}")
  string(REPLACE "@RB@" "]" text "${text}")
  string(REPLACE "@BS@" "\\" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

set(ci_encoded "")
foreach(name ci_command_1 ci_command_2)
  encode("${${name}}" e)
  list(APPEND ci_encoded "${e}")
endforeach()

set(project_dir ${WORK}/snippets)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${project_dir})

file(GLOB pages ${SOURCE}/docs/*.md)
list(SORT pages)
list(PREPEND pages ${SOURCE}/README.md)

set(programs "")    # target names, in document order
set(cpp_blocks 0)
set(sh_blocks 0)
foreach(page IN LISTS pages)
  file(RELATIVE_PATH page_name ${SOURCE} ${page})
  if(ONLY AND NOT page_name MATCHES "${ONLY}")
    continue()
  endif()
  file(READ ${page} content)
  encode("${content}" content)
  string(REPLACE "\n" ";" lines "${content}")
  set(number 0)
  set(kind "")          # cpp, sh, other: inside a fence of that kind
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    if(kind STREQUAL "")
      if(line MATCHES "^```cpp[ \t\r]*$")
        set(kind cpp)
        math(EXPR first "${number} + 1")
        set(block_lines "")
        set(block_numbers "")
      elseif(line MATCHES "^```sh[ \t\r]*$")
        set(kind sh)
        math(EXPR first "${number} + 1")
        set(block_lines "")
      elseif(line MATCHES "^```")
        set(kind other)
      endif()
      continue()
    endif()
    if(NOT line MATCHES "^```[ \t\r]*$")
      if(kind STREQUAL "cpp")
        list(APPEND block_lines "${line}")
        list(APPEND block_numbers ${number})
      elseif(kind STREQUAL "sh")
        list(APPEND block_lines "${line}")
      endif()
      continue()
    endif()
    # The closing fence.
    if(kind STREQUAL "sh")
      math(EXPR sh_blocks "${sh_blocks} + 1")
      if(block_lines STREQUAL "")
        message(FATAL_ERROR "${page_name}:${first}: an empty ```sh block")
      endif()
      list(GET block_lines 0 head)
      if(NOT head MATCHES "^# not run by CI: [^ ].*")
        foreach(command IN LISTS block_lines)
          if(command STREQUAL "")
            continue()
          endif()
          list(FIND ci_encoded "${command}" found)
          if(found EQUAL -1)
            decode("${command}" shown)
            message(FATAL_ERROR "${page_name}:${first}: a ```sh block whose command CI does not run:\n  ${shown}\n"
                    "Start the block with a line '# not run by CI: <why>', or make CI run it and list it in "
                    "tests/doc_snippets.cmake.")
          endif()
        endforeach()
      endif()
    elseif(kind STREQUAL "cpp")
      math(EXPR cpp_blocks "${cpp_blocks} + 1")
      string(MAKE_C_IDENTIFIER "${page_name}_${first}" target)
      set(file ${project_dir}/${target}.cpp)
      set(whole FALSE)
      foreach(code IN LISTS block_lines)
        if(code MATCHES "int main")
          set(whole TRUE)
        endif()
      endforeach()
      set(head "// ${page_name}:${first}\n")
      set(body "")
      set(expected 0)   # the line that follows the last one written, 0: none yet
      list(LENGTH block_lines count)
      if(count EQUAL 0)
        message(FATAL_ERROR "${page_name}:${first}: an empty ```cpp block")
      endif()
      math(EXPR last "${count} - 1")
      foreach(i RANGE ${last})
        list(GET block_lines ${i} code)
        list(GET block_numbers ${i} at)
        decode("${code}" code)
        if(NOT whole AND code MATCHES "^[ \t]*#[ \t]*include")
          string(APPEND head "#line ${at} \"${page}\"\n${code}\n")
        else()
          if(NOT at EQUAL expected)
            string(APPEND body "#line ${at} \"${page}\"\n")
          endif()
          string(APPEND body "${code}\n")
          math(EXPR expected "${at} + 1")
        endif()
      endforeach()
      if(whole)
        file(WRITE ${file} "${head}${body}")
      else()
        file(WRITE ${file} "${head}\nint main() {\n${body}}\n")
      endif()
      list(APPEND programs ${target})
      set(where_${target} "${page_name}:${first}")
    endif()
    set(kind "")
  endforeach()
  if(NOT kind STREQUAL "")
    message(FATAL_ERROR "${page_name}:${first}: a code block that is never closed")
  endif()
endforeach()
if(cpp_blocks EQUAL 0)
  message(FATAL_ERROR "no ```cpp block found under ${SOURCE}: wrong SOURCE?")
endif()

string(CONCAT listing "cmake_minimum_required(VERSION 3.25)\nproject(sympl_doc_snippets LANGUAGES CXX)\n"
                      "find_package(sympl REQUIRED)\n")
foreach(target IN LISTS programs)
  string(APPEND listing "add_executable(${target} ${target}.cpp)\n"
                        "target_link_libraries(${target} PRIVATE sympl::sympl)\n")
endforeach()
file(WRITE ${project_dir}/CMakeLists.txt "${listing}")

# Install sympl (headers only) and configure the snippets against it.
set(prefix ${WORK}/prefix)
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE};-B;${WORK}/sympl;-DSYMPL_BUILD_TESTS=OFF;-DSYMPL_BUILD_BENCH=OFF;-DSYMPL_BUILD_PROGRAM=OFF;-DCMAKE_INSTALL_PREFIX=${prefix}"
    "${CMAKE_COMMAND};--install;${WORK}/sympl"
    "${CMAKE_COMMAND};-S;${project_dir};-B;${WORK}/build;-DCMAKE_PREFIX_PATH=${prefix}")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()

# All at once; on a failure, one by one in document order to name the first bad block.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build -j${JOBS} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  foreach(target IN LISTS programs)
    execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build --target ${target}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${where_${target}}: this ```cpp block does not compile "
                          "(as ${project_dir}/${target}.cpp):\n${out}\n${err}")
    endif()
  endforeach()
  message(FATAL_ERROR "the snippets' build failed, but no single block did:\n${out}\n${err}")
endif()
foreach(target IN LISTS programs)
  execute_process(COMMAND ${WORK}/build/${target} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 120)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${where_${target}}: this ```cpp block compiles but its program failed (${rc}):\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "${cpp_blocks} C++ blocks built and run, ${sh_blocks} shell blocks checked")
