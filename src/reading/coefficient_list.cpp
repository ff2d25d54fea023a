// check-table's coefficient lists (coefficient_list.hpp).
#include "reading/coefficient_list.hpp"

#include <cstdlib>
#include <sstream>

#include <sympl/core/error.hpp>

namespace sympl::app {

// "0.5,0.5" -> {0.5, 0.5}; a bad token names itself.
std::vector<coefficient> parse_coefficient_list(const std::string& text, const std::string& option) {
    std::vector<coefficient> out;
    std::stringstream in(text);
    std::string token;
    while (std::getline(in, token, ',')) {
        const auto first = token.find_first_not_of(" \t");
        const auto last = token.find_last_not_of(" \t");
        token = first == std::string::npos ? "" : token.substr(first, last - first + 1);
        char* end = nullptr;
        const long double v = std::strtold(token.c_str(), &end);
        if (token.empty() || end != token.c_str() + token.size())
            throw invalid_argument(option + ": '" + token + "' is not a number; expected a comma-separated list such as 0.5,0.5");
        out.push_back(v);
        if (out.size() > max_check_table_stages)
            throw invalid_argument(option + ": more than " + std::to_string(max_check_table_stages) +
                                   " coefficients; expected at most " + std::to_string(max_check_table_stages) +
                                   " (the order measurement's cost grows faster than the stage count: 1000 stages "
                                   "took over a minute)");
    }
    if (out.empty()) throw invalid_argument(option + ": empty list; expected comma-separated numbers");
    // getline drops an empty last field: a trailing comma means a coefficient is missing.
    if (const auto last = text.find_last_not_of(" \t"); last != std::string::npos && text[last] == ',')
        throw invalid_argument(option + ": a trailing comma after " + std::to_string(out.size()) +
                               " numbers; expected a number after every comma");
    return out;
}

}  // namespace sympl::app
