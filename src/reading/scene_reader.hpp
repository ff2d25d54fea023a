#pragma once
// Reading a scene's TOML (scene.cpp, scene_ensemble.cpp): every error names
// the file, line and column and what was expected.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "output/format.hpp"
#include "reading/near_names.hpp"
#include "reading/scene.hpp"
#include "running/systems.hpp"

namespace sympl::app {

inline std::string join(const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
    return out;
}

// Reads typed values and reports where a value is wrong. Unknown names (keys,
// the system, methods) are collected and reported together, one line each,
// with the first error that stops the reading or at its end (throw_unknown).
struct reader {
    std::string source;
    // The system's characteristic period for the scene's parameters (0: none)
    // and what it is: what {periods = N} and {per_period = N} count in.
    double period = 0;
    std::string period_meaning{};
    mutable std::vector<std::string> unknown{};

    std::string at(const toml::source_region& where) const {
        return printable(source) + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) + ": ";
    }
    [[noreturn]] void fail(const toml::source_region& where, const std::string& what) const {
        std::string all = unknown_lines();
        throw scene_error(all + (all.empty() ? "" : "\n") + at(where) + printable(what));
    }
    [[noreturn]] void fail(const toml::node& n, const std::string& what) const { fail(n.source(), what); }

    // An unknown name: noted, and the reading goes on to find the others.
    void unknown_name(const toml::node& n, const std::string& what) const {
        unknown.push_back(at(n.source()) + printable(what));
    }
    void throw_unknown() const {
        if (unknown.empty()) return;
        throw scene_error(unknown_lines());
    }
    // The unknown names, one line each, the first 20 of them and how many more.
    static constexpr std::size_t listed_unknown = 20;
    std::string unknown_lines() const {
        std::string all;
        for (std::size_t i = 0; i < unknown.size() && i < listed_unknown; ++i)
            all += (all.empty() ? "" : "\n") + unknown[i];
        if (unknown.size() > listed_unknown)
            all += "\n" + source + ": and " + std::to_string(unknown.size() - listed_unknown) + " more unknown names";
        return all;
    }

    // Only the listed keys: anything else is a typo the user wants to hear about.
    void only_keys(const toml::table& t, const std::set<std::string>& allowed, const std::string& where) const {
        for (const auto& [key, node] : t)
            if (!allowed.count(std::string(key.str()))) {
                std::vector<std::string> names(allowed.begin(), allowed.end());
                unknown_name(node, "unknown key '" + std::string(key.str()) + "' in " + where + "; " +
                                       expected_one_of(std::string(key.str()), names));
            }
    }

    // Each of `keys` present in t (at n), or an error naming the first missing one.
    void need_keys(const toml::node& n, const toml::table& t, const std::vector<std::string>& keys,
                   const std::string& where) const {
        std::string form;
        for (const auto& k : keys) form += (form.empty() ? "{" : ", ") + k + " = ...";
        for (const auto& k : keys)
            if (!t.get(k))
                fail(n, (where.starts_with('[') ? where : "'" + where + "'") + " has no '" + k + "'; expected " + form + "}");
    }

    // A value as the file gives it, for an error message (cut short if long).
    static std::string text_of(const toml::node& n) {
        std::ostringstream os;
        n.visit([&](const auto& v) { os << v; });
        std::string text = os.str();
        if (text.size() > 40) text = text.substr(0, 37) + "...";
        return text;
    }

    double number(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<double>(); v && (n.is_floating_point() || n.is_integer())) return *v;
        fail(n, "'" + key + "' must be a number");
    }
    double positive(const toml::node& n, const std::string& key) const {
        const double v = number(n, key);
        if (!(v > 0) || !std::isfinite(v))
            fail(n, "'" + key + "' = " + shortest(v) + "; expected a finite number > 0");
        return v;
    }
    std::string string(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<std::string>(); v && n.is_string()) return *v;
        fail(n, "'" + key + "' must be a string");
    }
    bool boolean(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<bool>(); v && n.is_boolean()) return *v;
        fail(n, "'" + key + "' must be true or false");
    }
    std::vector<double> numbers(const toml::node& n, const std::string& key) const {
        const toml::array* a = n.as_array();
        if (!a) fail(n, "'" + key + "' must be an array of numbers");
        std::vector<double> out;
        for (const auto& e : *a) out.push_back(number(e, key));
        return out;
    }

    // The characteristic period, or an error at n saying there is none.
    double period_for(const toml::node& n, const std::string& key) const {
        if (!(period > 0))
            fail(n, "'" + key + "' counts in the system's characteristic period, and it has none" +
                        (period_meaning.empty() ? "" : " at these parameters (" + period_meaning + ")") +
                        "; expected a value in time units");
        return period;
    }

    // t_end = 100 | {periods = N}: N characteristic periods after t0.
    double span_end(const toml::node& n, const std::string& key, double t0) const {
        if (const toml::table* t = n.as_table()) {
            only_keys(*t, {"periods"}, "'" + key + "'");
            need_keys(n, *t, {"periods"}, key);
            const double periods = positive(*t->get("periods"), key + ".periods"), period = period_for(n, key);
            const double end = t0 + periods * period;
            if (!std::isfinite(end) || !(end > t0))
                fail(n, "'" + key + "': " + shortest(periods) + " periods of " + shortest(period) + " after t0 = " +
                            shortest(t0) + " give t_end = " + shortest(end) + "; expected a finite time after t0");
            return end;
        }
        return number(n, key);
    }

    // A point of a geometric sweep as the scene meant it: 1e-7 where the
    // powers reach 1.0000000000000005e-07, the nearest 12-digit decimal when
    // it is within 4 ulps; any other point as computed.
    static double meant(double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.12g", v);
        const double d = std::strtod(text, nullptr);
        return std::fabs(d - v) <= 4 * std::numeric_limits<double>::epsilon() * std::fabs(v) ? d : v;
    }

    // A computed step or tolerance that overflowed to inf or underflowed to 0
    // is refused here, at its key, with what it was made of.
    double representable(const toml::node& n, const std::string& key, double v, const std::string& made_of) const {
        if (!(std::isfinite(v) && v > 0))
            fail(n, "'" + key + "': " + made_of + " gives " + shortest(v) +
                        "; expected a finite value > 0");
        return v;
    }

    // dt = 0.01 | [0.1, 0.05] | { from = 0.1, to = 0.001, count = 7 } (geometric)
    //    | {per_period = N}, N steps per characteristic period, N any of the above.
    std::vector<double> sweep(const toml::node& n, const std::string& key) const {
        std::vector<double> out;
        if (const toml::table* t = n.as_table(); t && t->get("per_period")) {
            only_keys(*t, {"per_period"}, "'" + key + "'");
            const double p = period_for(n, key);
            for (double steps : sweep(*t->get("per_period"), key + ".per_period"))
                out.push_back(representable(n, key, p / steps, "the period " + shortest(p) + " / " + shortest(steps)));
            std::sort(out.rbegin(), out.rend());
            return out;
        }
        if (n.is_array()) {
            for (const auto& e : *n.as_array()) out.push_back(positive(e, key));
            if (out.empty()) fail(n, "'" + key + "' is an empty array; expected at least one value");
        } else if (const toml::table* t = n.as_table()) {
            only_keys(*t, {"from", "to", "count", "per_period"}, "'" + key + "'");
            const toml::node* from = t->get("from");
            const toml::node* to = t->get("to");
            const toml::node* count = t->get("count");
            need_keys(n, *t, {"from", "to", "count"}, key);
            const double a = positive(*from, key + ".from"), b = positive(*to, key + ".to");
            const auto c = count->value<std::int64_t>();
            if (!c || !count->is_integer() || *c < 1 || *c > 1000)
                fail(*count, "'" + key + ".count' = " + text_of(*count) + "; expected an integer in [1, 1000]");
            for (std::int64_t i = 0; i < *c; ++i)
                out.push_back(*c == 1 ? a
                                      : representable(n, key, meant(a * std::pow(b / a, double(i) / double(*c - 1))),
                                                      "a point between " + shortest(a) + " and " + shortest(b)));
        } else {
            out.push_back(positive(n, key));
        }
        std::sort(out.rbegin(), out.rend());
        return out;
    }
};

// [ensemble]: a grid over the system's parameters or a CSV of states.
// A [system] table of formulas (scene_formulas.cpp), after [initial]: the
// scene's own system, added to the program's by its name, in s.system.
void read_formula_system(const reader& r, const toml::node& node, const toml::table& t, scene& s);

ensemble_spec read_ensemble(const reader& r, const toml::node& node, const scene& s, const system_entry& entry,
                            const toml::array& methods);

// [test_particles]: a grid of orbital elements or a CSV of them, with the
// planets of a planetary system and one wh(...) method.
test_particle_spec read_test_particles(const reader& r, const toml::node& node, const scene& s,
                                       const toml::array& methods);

}  // namespace sympl::app
