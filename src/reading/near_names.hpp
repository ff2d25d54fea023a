#pragma once
// "Did you mean ...?": the known names nearest a mistyped one, by the
// optimal-string-alignment distance (Levenshtein's edits plus a swap of two
// neighbours, Damerau 1964), case-insensitive.
#include <string>
#include <vector>

namespace sympl::app {

// Edits (insert, delete, replace, swap neighbours) from a to b.
std::size_t edit_distance(const std::string& a, const std::string& b);

// The names within a few edits of `given` (1 for names up to 4 letters, 2 up
// to 8, else 3), nearest first, at most three; or those that `given` starts
// or ends (a method's "yoshida" for "yoshida_4").
std::vector<std::string> near_names(const std::string& given, const std::vector<std::string>& known);

// "did you mean 'run'? " or "did you mean 'a' or 'b'? ", or "" when none is near.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& known);

// "did you mean 'run'? expected one of: a, b, c": the end of an error about
// an unknown name.
std::string expected_one_of(const std::string& given, const std::vector<std::string>& known);

}  // namespace sympl::app
