#pragma once
// The grammar of a method's name, read in one place (method_kinds.cpp reads
// what each head means):
//
//   name                           a table, a family's member, a classic stepper
//   head(inner[, argument]...)     inner: a method's name; an argument: a value
//                                  or `key = value`
//
// Arguments are read from the right, at commas outside parentheses, so that
// the inner name keeps its own (extrapolated(logh(leapfrog_dkd), 6)); a
// scene's inline table may hold commas in its name, which is why the caller,
// not the grammar, decides where the inner name ends.
#include <optional>
#include <string>

namespace sympl::app {

// `head(inside)`: the name before the first '(' and what the outer
// parentheses hold, trimmed; nullopt for a plain name or an empty inside.
struct method_call {
    std::string head, inside;
};
std::optional<method_call> call_of(const std::string& name);

// `inside` split at its last comma outside parentheses: what is before it and
// the argument after it, both trimmed; nullopt when there is none.
struct last_argument {
    std::string before, argument;
};
std::optional<last_argument> split_last(const std::string& inside);

// An argument as `key = value`, trimmed; a bare word has no value.
struct method_option {
    std::string key;
    std::optional<std::string> value;
};
method_option option_of(const std::string& argument);

std::string trimmed(const std::string& s);

}  // namespace sympl::app
