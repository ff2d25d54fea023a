#pragma once
// Numbers as text, the same everywhere the program prints or writes one.
#include <charconv>
#include <iomanip>
#include <sstream>
#include <string>

namespace sympl::app {

// Shortest of fixed or scientific with `digits` significant digits (printf %g);
// 17 digits give back the same double when read.
inline std::string format_number(double v, int digits = 4) {
    std::ostringstream s;
    s << std::setprecision(digits) << v;
    return s.str();
}

// The shortest text that reads back as the same double: for error messages,
// which name the value the user gave.
inline std::string shortest(double v) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    return std::string(buffer, end);
}

// `digits` after the decimal point.
inline std::string fixed(double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

// d.ddde-xx with `digits` after the point.
inline std::string scientific(double v, int digits) {
    std::ostringstream s;
    s << std::scientific << std::setprecision(digits) << v;
    return s.str();
}

// "[i/n] ", a progress line's counter (built with a stream: GCC 12 warns
// falsely on "[" + std::to_string(i) at -O3).
inline std::string counter(std::size_t i, std::size_t n) {
    std::ostringstream text;
    text << '[' << i << '/' << n << "] ";
    return text.str();
}

}  // namespace sympl::app
