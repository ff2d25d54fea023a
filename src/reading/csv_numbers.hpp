#pragma once
// One line of a CSV file of numbers (an ensemble's states, orbital elements
// of test particles): every field a finite number, or a scene_error naming
// the line (`where`, "file:line: ") and the field.
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "reading/scene.hpp"

namespace sympl::app {

inline std::vector<double> csv_numbers(const std::string& line, const std::string& where) {
    std::vector<double> x;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        const std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        double v = 0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc() || end != field.data() + field.size() || field.empty() || !std::isfinite(v))
            throw scene_error(where + "field " + std::to_string(x.size() + 1) + " '" + field +
                              "'; expected a finite number");
        x.push_back(v);
        if (comma == std::string::npos) return x;
        start = comma + 1;
    }
}

}  // namespace sympl::app
