// The method-kind registry: resolution of names and the "can it run" answer.
#include "methods/method_kinds.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include <sympl/methods/catalog.hpp>
#include <sympl/core/error.hpp>
#include <sympl/methods/extended_phase_space.hpp>
#include <sympl/methods/extrapolation.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

#include "methods/method_name.hpp"
#include "reading/near_names.hpp"

namespace sympl::app {

// The registry is listed in the order of method_kind: entry_of indexes it.
static_assert([] {
    for (std::size_t k = 0; k < method_kind_entries.size(); ++k)
        if (std::size_t(method_kind_entries[k].kind) != k) return false;
    return true;
}());

const std::array<method_kind_entry, method_kind_count>& method_kinds() { return method_kind_entries; }

classic_facts classic_at(std::size_t index) {
    classic_facts facts{"", needs::any, false, false};
    std::size_t k = 0;
    std::apply(
        [&](const auto&... c) {
            ((k++ == index ? void(facts = {c.name, c.requirement, c.history, c.symplectic}) : void()), ...);
        },
        classic_methods);
    if (index >= classic_method_count) throw invalid_argument("classic method index " + std::to_string(index) + " out of range");
    return facts;
}

std::vector<std::string> method_names_beside_tables() {
    std::vector<std::string> names;
    std::apply([&](const auto&... m) { (names.push_back(m.name), ...); }, classic_methods);
    for (const method_kind_entry& k : method_kind_entries)
        for (const named_method& member : k.members) names.push_back(member.name);
    for (const table& t : force_gradient_catalog()) names.push_back(t.name());
    for (const processed_method& m : processed_catalog()) names.push_back(m.name);
    return names;
}

namespace {
// A method of `kind` by `name`, every other field at its default.
method_spec spec(const std::string& name, method_kind kind, std::optional<table> coefficients = std::nullopt) {
    method_spec m;
    m.name = name;
    m.kind = kind;
    m.coefficients = std::move(coefficients);
    return m;
}

std::optional<std::size_t> classic_index(const std::string& name) {
    for (std::size_t k = 0; k < classic_method_count; ++k)
        if (name == classic_at(k).name) return k;
    return std::nullopt;
}

// The catalog's tables and the scene's own, by name.
std::vector<std::string> table_names(const std::map<std::string, table>& inline_tables) {
    std::vector<std::string> names = catalog_names();
    for (const auto& entry : inline_tables) names.push_back(entry.first);
    return names;
}

// "did you mean 'yoshida_6'? " for a table name that is none, or "".
std::string nearest_table(const std::string& given, const std::map<std::string, table>& inline_tables) {
    return did_you_mean(given, table_names(inline_tables));
}

// The table a method's name wraps (tao(...), wh(...), ...): a table with no
// extrapolation or compensation of its own, and none of force-gradient kicks
// unless `force_gradient` allows them ("a plain table"); else refused naming
// the inner name with the nearest table's.
table inner_table(const std::string& name, const std::string& inner_name, const std::string& usage,
                  const std::map<std::string, table>& inline_tables, bool force_gradient) {
    const auto inner = resolve_method(inner_name, inline_tables);
    const bool fits = inner && inner->kind == method_kind::table && !inner->extrapolation_columns &&
                      !inner->compensated && (force_gradient || !inner->coefficients->has_force_gradient());
    if (!fits)
        throw invalid_argument("method '" + name + "': '" + inner_name + "' is not a " + (force_gradient ? "" : "plain ") +
                               "table; " + nearest_table(inner_name, inline_tables) + usage.substr(2));
    return *inner->coefficients;
}

// extrapolated(<table or logh(<table>)>, <columns>)
method_spec extrapolated(const std::string& name, const std::string& inside,
                         const std::map<std::string, table>& inline_tables) {
    const std::string usage = "; expected extrapolated(<symmetric table or logh(<symmetric table>)>, <columns 1 to " +
                              std::to_string(max_extrapolation_columns) + ">)";
    const auto split = split_last(inside);
    if (!split) throw invalid_argument("method '" + name + "': no column count" + usage);
    const std::string& inner_name = split->before;
    const std::string& count = split->argument;
    int columns = 0;
    const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), columns);
    if (error != std::errc{} || end != count.data() + count.size() || columns < 1 || columns > max_extrapolation_columns)
        throw invalid_argument("method '" + name + "': column count '" + count + "'" + usage);
    auto inner = resolve_method(inner_name, inline_tables);
    if (!inner || (inner->kind != method_kind::table && inner->kind != method_kind::logh) || inner->extrapolation_columns)
        throw invalid_argument("method '" + name + "': '" + inner_name + "' is not a table or logh(<table>); " +
                               nearest_table(inner_name, inline_tables) + usage.substr(2));
    try {
        extrapolation_order(*inner->coefficients);
    } catch (const invalid_argument& e) {
        throw invalid_argument("method '" + name + "': " + e.what() + usage);
    }
    inner->name = name;
    inner->extrapolation_columns = columns;
    return *inner;
}

// tao(<table>[, omega = W]) or semiexplicit(<table>): a plain table (the
// catalog's or the scene's) that composes leapfrog steps symmetrically,
// checked as the library checks it; Tao's binding omega from the scene, or
// unset: from the problem's scales (problem_scales.hpp).
method_spec on_extended_phase_space(const std::string& name, method_kind kind, const method_call& call,
                                    const std::map<std::string, table>& inline_tables) {
    std::string inner_name = call.inside;
    const std::string usage = "; expected " + call.head +
                              "(<a symmetric composition of leapfrog steps: leapfrog_kdk, yoshida_4, yoshida_6, "
                              "kahan_li_8, ...>" + (kind == method_kind::tao ? "[, omega = <binding > 0>]" : "") + ")";
    std::optional<double> omega;
    // An inline table's name may hold commas: an option only where the whole is no method.
    if (const auto split = split_last(inner_name);
        kind == method_kind::tao && split && !resolve_method(inner_name, inline_tables)) {
        const method_option option = option_of(split->argument);
        if (option.key != "omega")
            throw invalid_argument("method '" + name + "': unknown option '" + option.key + "'; " +
                                   did_you_mean(option.key, {"omega"}) + "expected omega" + usage);
        const std::string value = option.value.value_or("");
        double w = 0;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), w);
        if (error != std::errc{} || end != value.data() + value.size() || !std::isfinite(w) || !(w > 0))
            throw invalid_argument("method '" + name + "': omega = '" + value + "'" + usage);
        omega = w;
        inner_name = split->before;
    }
    const table coefficients = inner_table(name, inner_name, usage, inline_tables, true);
    sympl::detail::leapfrog_composition_weights(coefficients, "method '" + name + "'");  // throws naming it
    method_spec m = spec(name, kind, coefficients);
    m.omega = omega;
    return m;
}

// cartesian_split(<table>): a symmetric composition of leapfrog steps, as
// the library checks it; cylindrical_split(<table>): any kick-drift table
// without force-gradient kicks.
method_spec charged_split(const std::string& name, charged_scheme scheme, const method_call& call,
                          const std::map<std::string, table>& inline_tables) {
    const bool composition = scheme == charged_scheme::cartesian_split;
    const std::string usage = "; expected " + call.head + "(" +
                              (composition ? "<a symmetric composition of leapfrog steps: leapfrog_kdk, yoshida_6, "
                                             "kahan_li_8, ...>)"
                                           : "<a table of kicks and drifts: leapfrog_kdk, blanes_moan_srkn11b, ...>)");
    const table coefficients = inner_table(name, call.inside, usage, inline_tables, false);
    if (composition)
        sympl::detail::leapfrog_composition_weights(coefficients, "method '" + name + "'");  // throws naming it
    method_spec m = spec(name, method_kind::charged, coefficients);
    m.parameters.scheme = scheme;
    return m;
}

// One option of wh(...) into m, or refused with the value and the choices.
void wisdom_holman_option(method_spec& m, const std::string& name, const std::string& key, const std::string& value,
                          const std::string& usage) {
    if (key == "corrector") {
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), m.corrector_order);
        if (error != std::errc{} || end != value.data() + value.size() || m.corrector_order < 1)
            throw invalid_argument("method '" + name + "': corrector = '" + value + "'" + usage);
    } else if (key == "coordinates") {
        if (value == "jacobi") m.jacobi = true;
        else if (value != "democratic_heliocentric")
            throw invalid_argument("method '" + name + "': coordinates = '" + value + "'; " +
                                   did_you_mean(value, {"democratic_heliocentric", "jacobi"}) + usage.substr(2));
    } else if (value == "composition") {
        m.composition_kernel = true;
    } else if (value == "lazy") {
        m.lazy_kernel = true;
    } else if (value != "kick") {
        throw invalid_argument("method '" + name + "': kernel = '" + value + "'; " +
                               did_you_mean(value, {"composition", "lazy", "kick"}) + usage.substr(2));
    }
}

// wh(<table>[, corrector = K][, kernel = composition|lazy][, coordinates =
// jacobi]): any plain table (the catalog's or the scene's); its drifts become
// Kepler flows, its kicks the planets' interaction. The options are the
// library's wisdom_holman_options, checked against the table as the stepper
// checks them (plan_wisdom_holman), so a misfit is refused before any run.
method_spec wisdom_holman(const std::string& name, const method_call& call,
                          const std::map<std::string, table>& inline_tables) {
    const std::string usage = "; expected wh(<a table of kicks and drifts: leapfrog_kdk, saba_2, sbab_3, ...>"
                              "[, corrector = 3|5|7|9|11|17][, kernel = composition|lazy]"
                              "[, coordinates = democratic_heliocentric|jacobi])";
    const std::set<std::string> keys = {"corrector", "kernel", "coordinates"};
    std::string inner_name = call.inside;
    method_spec m = spec(name, method_kind::wisdom_holman);
    std::set<std::string> seen;
    for (auto split = split_last(inner_name); split; split = split_last(inner_name)) {
        const method_option option = option_of(split->argument);
        if (!keys.count(option.key)) {
            // Part of an inline table's name (which may hold commas), or a misspelt option.
            if (option.value && !resolve_method(inner_name, inline_tables))
                throw invalid_argument("method '" + name + "': unknown option '" + option.key + "'; " +
                                       did_you_mean(option.key, {"corrector", "kernel", "coordinates"}) +
                                       "expected corrector, kernel or coordinates" + usage);
            break;
        }
        if (!option.value || option.value->empty())
            throw invalid_argument("method '" + name + "': option '" + split->argument + "' has no value" + usage);
        if (!seen.insert(option.key).second)
            throw invalid_argument("method '" + name + "': '" + option.key + "' given twice" + usage);
        wisdom_holman_option(m, name, option.key, *option.value, usage);
        inner_name = split->before;
    }
    m.coefficients = inner_table(name, inner_name, usage, inline_tables, false);
    plan_wisdom_holman(*m.coefficients, wisdom_holman_options_of(m), "method '" + name + "'");  // throws naming the misfit
    return m;
}
}  // namespace

std::string did_you_mean_method(const std::string& name, const std::map<std::string, table>& inline_tables) {
    // logh(<table>) and compensated(<table>) resolve to nothing when their
    // table is unknown: the same pattern around the nearest table.
    const auto call = call_of(name);
    if (!call || (call->head != "logh" && call->head != "compensated")) return "";
    const std::vector<std::string> near = near_names(call->inside, table_names(inline_tables));
    if (near.empty()) return "";
    return "did you mean '" + call->head + "(" + near.front() + ")'? ";
}

wisdom_holman_options wisdom_holman_options_of(const method_spec& m) {
    return {.corrector_order = m.corrector_order,
            .kernel = m.composition_kernel ? wh_kernel::composition
                      : m.lazy_kernel      ? wh_kernel::lazy
                                           : wh_kernel::kick,
            .coordinates = m.jacobi ? wh_coordinates::jacobi : wh_coordinates::democratic_heliocentric};
}

namespace {
// How deep the parentheses of a name nest.
int nesting_of(const std::string& name) {
    int depth = 0, deepest = 0;
    for (char c : name) {
        if (c == '(') deepest = std::max(deepest, ++depth);
        else if (c == ')') --depth;
    }
    return deepest;
}

// A name as an error quotes it: its first 60 characters, with its length when
// it is longer (a scene's name may be a megabyte).
std::string quoted_start(const std::string& name) {
    if (name.size() <= 60) return "'" + name + "'";
    return "'" + name.substr(0, 60) + "...' (" + std::to_string(name.size()) + " characters)";
}
}  // namespace

std::optional<method_spec> resolve_method(const std::string& name, const std::map<std::string, table>& inline_tables) {
    if (const int depth = nesting_of(name); depth > max_method_nesting)
        throw invalid_argument("method " + quoted_start(name) + " nests its parentheses " + std::to_string(depth) +
                               " deep; expected at most " + std::to_string(max_method_nesting) +
                               " (extrapolated(logh(leapfrog_dkd), 6) nests 2 deep)");
    const std::optional<method_call> call = call_of(name);
    if (call && call->head == "extrapolated") return extrapolated(name, call->inside, inline_tables);
    if (auto it = inline_tables.find(name); it != inline_tables.end()) return spec(name, method_kind::table, it->second);
    if (call && call->head == "compensated") {
        auto inner = resolve_method(call->inside, inline_tables);
        if (!inner || inner->kind != method_kind::table || inner->extrapolation_columns) return std::nullopt;
        inner->name = name;
        inner->compensated = true;
        return inner;
    }
    if (call && call->head == "logh") {
        auto inner = resolve_method(call->inside, inline_tables);
        if (!inner || inner->kind != method_kind::table) return std::nullopt;
        // LogH's extended Hamiltonian has no force derivative of its own.
        if (inner->coefficients->has_force_gradient())
            throw invalid_argument("method '" + name + "': '" + inner->name +
                                   "' has force-gradient kicks; expected logh(<table without them>)");
        return spec(name, method_kind::logh, inner->coefficients);
    }
    if (call && call->head == "wh") return wisdom_holman(name, *call, inline_tables);
    if (call && call->head == "tao") return on_extended_phase_space(name, method_kind::tao, *call, inline_tables);
    if (call && call->head == "semiexplicit")
        return on_extended_phase_space(name, method_kind::semiexplicit, *call, inline_tables);
    if (call && call->head == "cartesian_split")
        return charged_split(name, charged_scheme::cartesian_split, *call, inline_tables);
    if (call && call->head == "cylindrical_split")
        return charged_split(name, charged_scheme::cylindrical_split, *call, inline_tables);
    for (const method_kind_entry& k : method_kind_entries)
        for (const named_method& member : k.members)
            if (name == member.name) {
                method_spec m = spec(name, k.kind);
                m.parameters = member.parameters;
                return m;
            }
    if (const auto index = classic_index(name)) {
        method_spec m = spec(name, method_kind::classic);
        m.classic = *index;
        return m;
    }
    const auto& names = catalog_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) return spec(name, method_kind::table, method(name));
    for (const table& t : force_gradient_catalog())
        if (t.name() == name) return spec(name, method_kind::table, t);
    for (const processed_method& p : processed_catalog())
        if (p.name == name) {
            method_spec m = spec(name, method_kind::processed);
            m.processing = p;
            return m;
        }
    return std::nullopt;
}

bool symplectic(const method_spec& m) {
    if (m.extrapolation_columns > 0) return false;
    if (m.kind == method_kind::classic) return classic_at(m.classic).symplectic;
    const method_kind_entry& row = entry_of(m.kind);
    for (const named_method& n : row.members)
        if (n.parameters == m.parameters) return n.symplectic;
    return row.symplectic;
}

std::string why_not_resumable(const method_spec& m) {
    const method_kind_entry& row = entry_of(m.kind);
    const bool history = m.kind == method_kind::classic && classic_at(m.classic).history;
    const char* member = "";
    for (const named_method& n : row.members)
        if (n.name == m.name) member = n.not_resumable;
    for (const char* why : {history ? row.history_not_resumable : "", member,
                            m.extrapolation_columns > 0 ? row.extrapolated_not_resumable : "", row.not_resumable,
                            adaptive(m) ? row.controlled_not_resumable : ""})
        if (*why) return "method '" + m.name + "' cannot be checkpointed: " + why;
    return "";
}

needs requirement_of(const method_spec& m) {
    if (m.kind == method_kind::table && m.coefficients->has_force_gradient()) return needs::differentiable_force;
    // Extrapolation and compensated sums wrap the separable stepper only.
    if (m.kind == method_kind::table && (m.extrapolation_columns > 0 || m.compensated)) return needs::separable_hamiltonian;
    if (m.kind == method_kind::classic) return classic_at(m.classic).requirement;
    return entry_of(m.kind).requirement;  // logh: also a separable Hamiltonian
}

std::string why_not(const method_spec& m, const system_form& form) {
    const std::string why = why_not(requirement_of(m), form);
    return why.empty() ? "" : "method '" + m.name + "' " + why;
}

}  // namespace sympl::app
