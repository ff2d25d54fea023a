// The grammar of a method's name (method_name.hpp).
#include "methods/method_name.hpp"

namespace sympl::app {

std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
    return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

std::optional<method_call> call_of(const std::string& name) {
    const auto open = name.find('(');
    if (open == std::string::npos || open == 0 || name.back() != ')') return std::nullopt;
    std::string inside = trimmed(name.substr(open + 1, name.size() - open - 2));
    if (inside.empty()) return std::nullopt;
    return method_call{name.substr(0, open), std::move(inside)};
}

std::optional<last_argument> split_last(const std::string& inside) {
    int depth = 0;
    for (std::size_t i = inside.size(); i-- > 0;) {
        const char c = inside[i];
        if (c == ')') ++depth;
        else if (c == '(') --depth;
        else if (c == ',' && depth == 0) return last_argument{trimmed(inside.substr(0, i)), trimmed(inside.substr(i + 1))};
    }
    return std::nullopt;
}

method_option option_of(const std::string& argument) {
    const auto equals = argument.find('=');
    if (equals == std::string::npos) return {trimmed(argument), std::nullopt};
    return {trimmed(argument.substr(0, equals)), trimmed(argument.substr(equals + 1))};
}

}  // namespace sympl::app
