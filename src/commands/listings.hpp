#pragma once
// `sympl tables` and `sympl systems`: the catalog and the registries, as text
// or JSON.
namespace sympl::app {

void print_tables(bool json);
void print_systems(bool json);

}  // namespace sympl::app
