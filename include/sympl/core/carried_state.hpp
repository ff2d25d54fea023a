#pragma once
// What a stepper carries between steps beyond q, p and stepper_memory (its
// own coordinates, a kernel's state, a second copy), as one flat list of
// numbers: a stepper's carried() writes it, restore_carried() reads it back,
// and a stepper so restored continues bit for bit (the program's checkpoints
// store the list as exact hexadecimal floats). The layout is each stepper's
// own; a list of the wrong length or of another stepper is refused by name.
//
// A type describes what it carries once, as one list of fields in order,
// which the writer and the reader both walk:
//
//   template <class Self, class List>
//   static void carried_fields(Self& self, List& l) {  // Self: const to write
//       l.flag(self.loaded_);
//       l.number(self.dt_);
//       l.numbers(self.last_.q);
//       l.check(self.last_.q.size() == self.last_.p.size(), "holds q and p of unequal sizes");
//       l.part(self.flows_);  // a member with carried_fields of its own, or a variant of such
//   }
//
// carried_list(x) writes the list, restore_carried_list(x, values, who) reads
// it back into x (check() refuses a list whose fields do not fit, naming
// `who`; the writer skips it), and the stepper's carried() and
// restore_carried() are those two calls.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "error.hpp"

namespace sympl::detail {

template <class T, class List>
void carried_part(T& part, List& l);

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
    template <class V>
    void numbers_of_size(const V& v) {
        numbers(v);
    }
    // The elements alone, for a vector whose size both sides know.
    template <class V>
    void values(const V& v) {
        for (std::size_t i = 0; i < std::size_t(v.size()); ++i) out.push_back(v.data()[i]);
    }
    // A whole number (a count, an id; exact below 2^53).
    // Integral only: the reader's whole(limit, what) returns a count, and a
    // list that called it would otherwise write the limit.
    template <class I>
        requires std::is_integral_v<I>
    void whole(I n, const char* = nullptr) {
        out.push_back(S(n));
    }
    // Ids: their count, then each.
    void ids(const std::vector<std::uint64_t>& id, const char* = nullptr) {
        whole(id.size());
        for (std::uint64_t i : id) whole(i);
    }
    void check(bool, const char*) const {}
    template <class T>
    void part(const T& t) {
        carried_part(t, *this);
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
    // The same, into the field a carried_fields list names.
    void number(S& v) { v = number(); }
    void flag(bool& b) { b = flag(); }
    template <class I>
        requires std::is_integral_v<I>
    void whole(I& n, const char* what) {
        n = I(whole(what));
    }
    // Ids: their count (bounded by what is left to read), then each.
    void ids(std::vector<std::uint64_t>& id, const char* what) {
        id.resize(std::size_t(whole(left(), what)));
        for (auto& i : id) i = whole(what);
    }
    // A condition the fields read so far must meet, or the list is refused with `what`.
    void check(bool ok, const char* what) const {
        if (!ok) refuse(what);
    }
    template <class T>
    void part(T& t) {
        carried_part(t, *this);
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
    // Exactly v.size() numbers into v, no size written before them.
    template <class V>
    void values(V& v) {
        if (in.size() - at < std::size_t(v.size())) refuse("ends early");
        for (std::size_t i = 0; i < std::size_t(v.size()); ++i) v.data()[i] = in[at++];
    }
    // The numbers not read yet (a list another reader takes), read.
    std::span<const S> rest() {
        const std::span<const S> left_over = in.subspan(at);
        at = in.size();
        return left_over;
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

template <class T>
struct is_variant : std::false_type {};
template <class... A>
struct is_variant<std::variant<A...>> : std::true_type {};

// A part of a carried list: a type with carried_fields, or a variant of such
// (the alternative held is the one walked; the list does not say which).
template <class T, class List>
void carried_part(T& part, List& l) {
    using U = std::remove_const_t<T>;
    if constexpr (is_variant<U>::value)
        std::visit([&](auto& alternative) { carried_part(alternative, l); }, part);
    else
        U::carried_fields(part, l);
}

// T's carried list, from its carried_fields.
template <class S, class T>
std::vector<S> carried_list(const T& t) {
    std::vector<S> out;
    carried_writer<S> w{out};
    carried_part(t, w);
    return out;
}

// T restored from the list carried_list wrote; `who` names T in a refusal.
// Read into a copy: a list that does not fit leaves t as it was.
template <class S, class T>
void restore_carried_list(T& t, std::span<const S> values, const char* who) {
    T read = t;
    carried_reader<S> r{values, who};
    carried_part(read, r);
    r.done();
    t = std::move(read);
}

}  // namespace sympl::detail
