# Writes OUTPUT, a C++ file holding the text of each *.toml file of SCENE_DIR
# (sorted by name) as builtin_scene_texts(): the built-in scenes are these
# TOML files, compiled into the program.
#   cmake -DOUTPUT=builtin_scenes.cpp -DSCENE_DIR=src/scenes -P embed.cmake
file(GLOB SCENES "${SCENE_DIR}/*.toml")
list(SORT SCENES)
set(body "")
foreach(file IN LISTS SCENES)
  file(READ "${file}" text)
  string(FIND "${text}" ")sympl_scene\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )sympl_scene\"")
  endif()
  get_filename_component(name "${file}" NAME)
  string(APPEND body "        {\"${name}\", R\"sympl_scene(${text})sympl_scene\"},\n")
endforeach()
file(WRITE "${OUTPUT}.new" "// Generated from src/scenes/*.toml by src/scenes/embed.cmake; edit those files instead.
#include \"reading/scene.hpp\"

namespace sympl::app {

const std::vector<std::pair<std::string, std::string>>& builtin_scene_texts() {
    static const std::vector<std::pair<std::string, std::string>> texts = {
${body}    };
    return texts;
}

}  // namespace sympl::app
")
file(COPY_FILE "${OUTPUT}.new" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.new")
