#pragma once
// The catalog of published splitting methods, looked up by name: catalog(),
// method(name), force_gradient_method(name), processed(name). The tables
// themselves, with their citations, are catalog_tables.hpp's.
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/table.hpp"
#include "catalog_tables.hpp"
#include "processing.hpp"

namespace sympl {

namespace detail {
inline const std::string& name_of(const table& t) { return t.name(); }
inline const std::string& name_of(const processed_method& m) { return m.name; }

// The entry of `entries` called `name`; an unknown name lists the valid ones.
template <class Entry>
const Entry& find_named(const std::vector<Entry>& entries, const std::string& name, const char* what) {
    std::string valid;
    for (const Entry& e : entries) {
        if (name_of(e) == name) return e;
        valid += (valid.empty() ? "" : ", ") + name_of(e);
    }
    throw invalid_argument(std::string("unknown ") + what + " '" + name + "'; expected one of: " + valid);
}
}  // namespace detail

// All catalog entries, built once, in order of increasing order.
inline const std::vector<table>& catalog() {
    static const std::vector<table> entries = [] {
        // Families: "basic" (order 1-2), "near-integrable" (Laskar-Robutel and
        // successors), "composition" (of the leapfrog), "RKN" (designed for
        // T = p^2/2), "splitting" (general-purpose, any T).
        const std::pair<std::vector<table>, const char*> groups[] = {
            {detail::basic_methods(), "basic"},
            {detail::laskar_robutel_methods(), "near-integrable"},
            {detail::order_3_and_4_methods(), "splitting"},
            {detail::near_integrable_methods(), "near-integrable"},
            {detail::order_5_to_8_methods(), "splitting"},
            {detail::order_6_methods(), "splitting"},
            {detail::order_8_and_10_methods(), "composition"}};
        std::vector<table> all;
        for (const auto& [group, family] : groups)
            for (const table& t : group)
                all.push_back(!t.family().empty()       ? t
                              : t.needs_quadratic_kinetic() ? t.with_family("RKN")
                                                            : t.with_family(family));
        return all;
    }();
    return entries;
}

// Catalog names, in catalog order.
inline std::vector<std::string> catalog_names() {
    std::vector<std::string> names;
    for (const table& t : catalog()) names.push_back(t.name());
    return names;
}

// The catalog entry called `name`; an unknown name lists the valid ones.
inline const table& method(const std::string& name) { return detail::find_named(catalog(), name, "method"); }

// The force-gradient methods, built once. Kept apart from catalog(): the
// program's scenes and table files carry kick and drift coefficients only.
inline const std::vector<table>& force_gradient_catalog() {
    static const std::vector<table> entries = [] {
        std::vector<table> all;
        for (const table& t : detail::force_gradient_methods()) all.push_back(t.with_family("force-gradient"));
        return all;
    }();
    return entries;
}

// The force-gradient method called `name`; an unknown name lists the valid ones.
inline const table& force_gradient_method(const std::string& name) {
    return detail::find_named(force_gradient_catalog(), name, "force-gradient method");
}

// The processed methods (processing.hpp), built once.
inline const std::vector<processed_method>& processed_catalog() {
    static const std::vector<processed_method> entries = detail::processed_methods();
    return entries;
}

// The processed method called `name`; an unknown name lists the valid ones.
inline const processed_method& processed(const std::string& name) {
    return detail::find_named(processed_catalog(), name, "processed method");
}

}  // namespace sympl
