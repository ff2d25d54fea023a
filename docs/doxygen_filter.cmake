# Doxygen's INPUT_FILTER for the headers (docs/Doxyfile.in):
#   cmake -DWORK=<scratch directory> -P doxygen_filter.cmake <header>
# prints the header with each comment line that starts a line ("// ...") as a
# documentation comment ("/// ..."), so that the reference shows the comments
# the headers are written with. Outside `code spans`, the characters Doxygen
# would read as markup are escaped: '<' before a letter or '/' (an HTML tag to
# Doxygen), '\', '@' and '#' (commands and links). Code lines are unchanged.
cmake_minimum_required(VERSION 3.25)
math(EXPR last "${CMAKE_ARGC} - 1")
set(header "${CMAKE_ARGV${last}}")
if(NOT WORK OR NOT EXISTS "${header}")
  message(FATAL_ERROR "usage: cmake -DWORK=<scratch directory> -P doxygen_filter.cmake <header>")
endif()
file(READ "${header}" text)

# Lines travel through CMake lists: ';', brackets and '\' become control characters meanwhile.
string(ASCII 1 sc)
string(ASCII 2 lb)
string(ASCII 3 rb)
string(ASCII 4 bs)
string(ASCII 5 cut)
string(REPLACE "\\" "${bs}" text "${text}")
string(REPLACE ";" "${sc}" text "${text}")
string(REPLACE "[" "${lb}" text "${text}")
string(REPLACE "]" "${rb}" text "${text}")
string(REPLACE "\n" ";" lines "${text}")

set(out "")
foreach(line IN LISTS lines)
  if(line MATCHES "^[ \t]*///")
    # already a documentation comment
  elseif(line MATCHES "^([ \t]*)//( .*)?$")
    set(indent "${CMAKE_MATCH_1}")
    set(rest "${CMAKE_MATCH_2}")
    # Alternate outside / inside backticks: escape outside only.
    string(REPLACE "`" "${cut}`${cut}" pieces "${rest}")
    string(REPLACE "${cut}" ";" pieces "${pieces}")
    set(inside FALSE)
    set(rest "")
    foreach(piece IN LISTS pieces)
      if(piece STREQUAL "`")
        if(inside)
          set(inside FALSE)
        else()
          set(inside TRUE)
        endif()
      elseif(NOT inside)
        string(REPLACE "${bs}" "${bs}${bs}" piece "${piece}")
        string(REPLACE "@" "${bs}@" piece "${piece}")
        string(REPLACE "#" "${bs}#" piece "${piece}")
        string(REGEX REPLACE "<([A-Za-z/])" "${bs}<\\1" piece "${piece}")
      endif()
      string(APPEND rest "${piece}")
    endforeach()
    set(line "${indent}///${rest}")
  endif()
  string(APPEND out "${line}\n")
endforeach()
string(REGEX REPLACE "\n$" "" out "${out}")  # the newline after the last element, which is not a line

string(REPLACE "${rb}" "]" out "${out}")
string(REPLACE "${lb}" "[" out "${out}")
string(REPLACE "${sc}" ";" out "${out}")
string(REPLACE "${bs}" "\\" out "${out}")
string(SHA1 key "${header}")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/${key}.hpp" "${out}")
execute_process(COMMAND ${CMAKE_COMMAND} -E cat "${WORK}/${key}.hpp")
