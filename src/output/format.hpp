#pragma once
// Numbers as text, the same everywhere the program prints or writes one.
#include <algorithm>
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

// A message as the program prints it: one line, as written. Control
// characters a name may hold (a NUL that would end the message, a newline
// that would split it, a terminal's escape) are written as \0, \n, \x1b,
// and UTF-8's C1 controls as \u0080..\u009f; a message past 2000
// characters (a megabyte name quoted in it) keeps its first 1200 and last
// 600 with the count cut between them.
inline std::string printable(const std::string& what) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(std::min<std::size_t>(what.size(), 4096));
    for (std::size_t i = 0; i < what.size(); ++i) {
        const char c = what[i];
        const auto u = static_cast<unsigned char>(c);
        const auto next = i + 1 < what.size() ? static_cast<unsigned char>(what[i + 1]) : 0u;
        if (u == 0xc2 && next >= 0x80 && next <= 0x9f) {  // U+0080..U+009F: C1 controls (U+009B starts an escape)
            out += std::string("\\u00") + hex[next >> 4] + hex[next & 15];
            ++i;
        } else if (u >= 0x20 && u != 0x7f) out += c;
        else if (c == '\n') out += "\\n";
        else if (c == '\t') out += "\\t";
        else if (c == '\0') out += "\\0";
        else out += std::string("\\x") + hex[u >> 4] + hex[u & 15];
    }
    constexpr std::size_t longest = 2000, head = 1200, tail = 600;
    if (out.size() <= longest) return out;
    return out.substr(0, head) + " ... (" + std::to_string(out.size() - head - tail) + " characters cut) ... " +
           out.substr(out.size() - tail);
}

// Each line of a message made printable (main's last word on any error: a
// path or name that reached a message unescaped is escaped there).
inline std::string printable_lines(const std::string& what) {
    std::string out;
    std::size_t from = 0;
    for (std::size_t lines = 0;; ++lines) {
        const std::size_t end = what.find('\n', from);
        if (lines == 1000) return out + "\n... (" + std::to_string(what.size() - from) + " characters more)";
        out += (lines ? "\n" : "") + printable(what.substr(from, end == std::string::npos ? std::string::npos : end - from));
        if (end == std::string::npos) return out;
        from = end + 1;
    }
}

}  // namespace sympl::app
