#pragma once
// `sympl tables` and `sympl systems`: the catalog and the registries, as text
// or JSON.
#include <string>
#include <vector>

namespace sympl::app {

void print_tables(bool json);
// Every system of the program, or those of the scene files given.
void print_systems(bool json, const std::vector<std::string>& scene_files = {});

}  // namespace sympl::app
