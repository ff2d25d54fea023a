// The systems the program knows: one entry each (see systems.hpp).
#include "running/systems.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <mutex>

#include "output/format.hpp"
#include "reading/near_names.hpp"

namespace sympl::app {

namespace {
const std::vector<system_entry>& registry() {
    static const std::vector<system_entry> entries = program_systems();
    return entries;
}
}  // namespace

bool parameter::accepts(double v) const {
    if (!std::isfinite(v)) return false;
    if (v < low || (low_open && v == low) || v > high || (high_open && v == high)) return false;
    return !integer || v == std::floor(v);
}

std::string parameter::expected() const {
    const std::string what = integer ? "an integer" : "a finite number";
    const auto shortest = [this](double v) { return integer ? std::to_string(std::int64_t(v)) : app::shortest(v); };
    const bool bounded_below = std::isfinite(low), bounded_above = std::isfinite(high);
    if (bounded_below && bounded_above)
        return what + " in " + (low_open ? "(" : "[") + shortest(low) + ", " + shortest(high) +
               (high_open ? ")" : "]");
    if (bounded_below) return what + (low_open ? " > " : " >= ") + shortest(low);
    if (bounded_above) return what + (high_open ? " < " : " <= ") + shortest(high);
    return what;
}

const parameter* system_entry::find(const std::string& parameter_name) const {
    for (const auto& p : parameters)
        if (p.name == parameter_name) return &p;
    return nullptr;
}

const std::vector<system_entry>& systems() { return registry(); }

namespace {
// The scenes' own systems ([system] tables of formulas), added as scenes are
// read; a deque, so that an entry found stays where it is.
struct scene_registry {
    std::mutex mutex;
    std::deque<std::pair<system_entry, std::string>> entries;  // with what defines each
};
scene_registry& scene_systems() {
    static scene_registry r;
    return r;
}
}  // namespace

std::string scene_system_definition(const std::string& name) {
    scene_registry& r = scene_systems();
    std::lock_guard lock(r.mutex);
    for (const auto& [s, defined] : r.entries)
        if (s.name == name) return defined;
    return {};
}

const system_entry& add_scene_system(system_entry entry, const std::string& definition) {
    for (const auto& s : registry())
        if (s.name == entry.name)
            throw invalid_argument("a [system] named '" + entry.name + "', the name of a built-in system; expected "
                                   "a name of its own");
    scene_registry& r = scene_systems();
    std::lock_guard lock(r.mutex);
    for (const auto& [s, defined] : r.entries)
        if (s.name == entry.name) {
            if (defined == definition) return s;
            throw invalid_argument("a [system] named '" + entry.name + "' defined differently by another scene of "
                                   "this run; expected one definition per name");
        }
    r.entries.emplace_back(std::move(entry), definition);
    return r.entries.back().first;
}

const system_entry* find_system(const std::string& name) {
    for (const auto& s : registry())
        if (s.name == name) return &s;
    scene_registry& r = scene_systems();
    std::lock_guard lock(r.mutex);
    for (const auto& [s, defined] : r.entries)
        if (s.name == name) return &s;
    return nullptr;
}

std::vector<std::string> system_names() {
    std::vector<std::string> names;
    for (const auto& s : registry()) names.push_back(s.name);
    scene_registry& r = scene_systems();
    std::lock_guard lock(r.mutex);
    for (const auto& [s, defined] : r.entries) names.push_back(s.name);
    return names;
}

double period_of(const system_entry& entry, const parameter_values& values) {
    if (!entry.period.value) return 0;
    const double t = entry.period.value(values);
    return std::isfinite(t) && t > 0 ? t : 0;
}

std::vector<std::string> state_columns(const std::string& system, std::size_t degrees_of_freedom) {
    const system_entry* entry = find_system(system);
    std::vector<std::string> columns;
    if (entry && entry->coordinate_names.size() == degrees_of_freedom) {
        for (const auto& q : entry->coordinate_names) columns.push_back(q);
        for (const auto& q : entry->coordinate_names) {  // "jupiter_x" -> "jupiter_px"
            const auto cut = q.rfind('_');
            columns.push_back(cut == std::string::npos ? "p_" + q : q.substr(0, cut + 1) + "p" + q.substr(cut + 1));
        }
        return columns;
    }
    for (const char* coordinate : {"q", "p"})
        for (std::size_t i = 1; i <= degrees_of_freedom; ++i) columns.push_back(coordinate + std::to_string(i));
    return columns;
}

parameter_values with_defaults(const system_entry& entry, const parameter_values& given, const std::string& where) {
    parameter_values v;
    for (const auto& p : entry.parameters) v[p.name] = p.value;
    for (const auto& [name, value] : given) {
        const parameter* p = entry.find(name);
        if (!p) {
            std::vector<std::string> names;
            for (const auto& q : entry.parameters) names.push_back(q.name);
            throw invalid_argument(where + ": " + entry.name + " has no parameter '" + name + "'; " +
                                   expected_one_of(name, names));
        }
        if (!p->accepts(value))
            throw invalid_argument(where + ": " + entry.name + " " + name + " = " + shortest(value) +
                                   "; expected " + p->expected());
        v[name] = value;
    }
    return v;
}

runnable_system make_system(const std::string& system, const parameter_values& given, const std::vector<double>& q0,
                     const std::vector<double>& p0, const std::string& where) {
    const system_entry* entry = find_system(system);
    if (!entry)
        throw invalid_argument(where + ": unknown system '" + system + "'; " +
                               expected_one_of(system, system_names()));
    runnable_system p;
    try {
        p = entry->build(with_defaults(*entry, given, where));
    } catch (const invalid_argument& e) {
        const std::string what = e.what();
        throw invalid_argument(what.rfind(where, 0) == 0 ? what : where + ": " + what);
    }
    p.system = system;
    p.form.negative_potential = entry->negative_potential;
    if (entry->kinetic_not_quadratic) p.form.quadratic_kinetic = false;
    // What the registry's values add to the type's answers (V < 0, T quadratic)
    // is in the form that runnable_system::run asks before the method runs.
    // A default start the parameters make impossible (charged_uniform's
    // speed above a speed_of_light given below it): named with the parameters
    // given, before anything reads it as an energy of NaN.
    if (q0.empty() && !std::all_of(p.x0.begin(), p.x0.end(), [](double x) { return std::isfinite(x); })) {
        std::string values, state;
        for (const auto& [name, value] : given) values += (values.empty() ? "" : ", ") + name + " = " + shortest(value);
        for (std::size_t i = 0; i < p.x0.size() && i < 12; ++i) state += (i ? ", " : "") + shortest(p.x0[i]);
        if (p.x0.size() > 12) state += ", ... (" + std::to_string(p.x0.size()) + " numbers)";
        throw invalid_argument(where + ": " + system + "'s default start is not finite at the parameters given (" +
                               (values.empty() ? "none" : values) + "): x0 = (" + state +
                               "); expected parameters it can start from (`sympl systems` describes the start) or a "
                               "start of one's own ([initial] in a scene, q0 and p0 in Python)");
    }
    if (!q0.empty()) {  // the scene's own initial state: the exact solution no longer applies, unless it is x0
        if (q0.size() != p.degrees_of_freedom || p0.size() != q0.size())
            throw invalid_argument(where + ": initial q has " + std::to_string(q0.size()) + " and p " +
                                   std::to_string(p0.size()) + " values; " + system + " expects " +
                                   std::to_string(p.degrees_of_freedom) + " each");
        std::vector<double> x0 = q0;
        x0.insert(x0.end(), p0.begin(), p0.end());
        if (x0 != p.x0) p.exact = nullptr;
        p.x0 = std::move(x0);
    }
    return p;
}

}  // namespace sympl::app
