#pragma once
// What a stepper carries between steps beyond q, p and stepper_memory (its
// own coordinates, a kernel's state, a second copy), as one flat list of
// numbers: a stepper's carried() writes it, restore_carried() reads it back,
// and a stepper so restored continues bit for bit (the program's checkpoints
// store the list as exact hexadecimal floats). The layout is each stepper's
// own; a list of the wrong length or of another stepper is refused by name.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "error.hpp"

namespace sympl::detail {

// Appends numbers, flags (0 or 1) and sized vectors to a carried list.
template <class S>
struct carried_writer {
    std::vector<S>& out;
    void number(S v) { out.push_back(v); }
    void flag(bool b) { out.push_back(b ? S(1) : S(0)); }
    // The size, then the elements (any contiguous vector: Eigen's, std::vector).
    template <class V>
    void numbers(const V& v) {
        out.push_back(S(v.size()));
        for (std::size_t i = 0; i < std::size_t(v.size()); ++i) out.push_back(v.data()[i]);
    }
};

// Reads a carried list in the order it was written; `who` names the stepper
// in the error for a list that does not fit.
template <class S>
struct carried_reader {
    std::span<const S> in;
    const char* who;
    std::size_t at = 0;

    S number() {
        if (at >= in.size()) refuse("ends early");
        return in[at++];
    }
    bool flag() {
        const S v = number();
        if (v != S(0) && v != S(1)) refuse("holds a flag that is neither 0 nor 1");
        return v == S(1);
    }
    // 2^53: doubles count exactly below it, so no count or id carried reaches it.
    static constexpr double whole_limit = 9007199254740992.0;

    // A whole number below `limit` (at most whole_limit), or the list
    // refused with `what`: a count.
    std::uint64_t whole(double limit, const char* what) {
        const S v = number();
        if (!(v >= S(0) && v < S(std::min(limit, whole_limit))) || S(std::uint64_t(v)) != v) refuse(what);
        return std::uint64_t(v);
    }
    // Any whole number below whole_limit: an id.
    std::uint64_t whole(const char* what) { return whole(whole_limit, what); }
    // How many numbers are left to read: a bound for a count read next.
    double left() const { return double(in.size() - at); }
    // A vector resized to the size written (Eigen's or std::vector); a
    // fixed-size Eigen vector takes only its own size.
    template <class V>
    void numbers(V& v) {
        const S n = number();
        if (!(n >= S(0) && n <= S(in.size() - at)) || S(std::size_t(n)) != n) refuse("holds a bad vector size");
        if constexpr (requires { V::SizeAtCompileTime; })
            if (V::SizeAtCompileTime >= 0 && std::size_t(n) != std::size_t(V::SizeAtCompileTime))
                refuse("holds a vector of another size than the stepper's");
        v.resize(std::size_t(n));
        for (std::size_t i = 0; i < std::size_t(n); ++i) v.data()[i] = in[at++];
    }
    // A vector of exactly v's present size.
    template <class V>
    void numbers_of_size(V& v) {
        const std::size_t expected = std::size_t(v.size());
        if (at < in.size() && in[at] != S(expected)) refuse("holds a vector of another size than the stepper's");
        numbers(v);
    }
    void done() const {
        if (at != in.size()) refuse("is longer than what the stepper carries");
    }
    [[noreturn]] void refuse(const char* what) const {
        throw invalid_argument(std::string(who) + ": the carried state of " + std::to_string(in.size()) +
                               " numbers " + what + " (at number " + std::to_string(at) +
                               "); expected a list this stepper's carried() wrote");
    }
};

}  // namespace sympl::detail
