// The method-kind registry: resolution of names and the "can it run" answer.
#include "method_kinds.hpp"

#include <algorithm>
#include <charconv>

#include <sympl/catalog.hpp>
#include <sympl/error.hpp>
#include <sympl/extrapolation.hpp>

namespace sympl::app {

const std::vector<method_kind_entry>& method_kinds() {
    static const std::vector<method_kind_entry> kinds = {
        {method_kind::table, "table", false, false, needs::separable_hamiltonian,
         "a splitting table: the catalog's (sympl tables) or a scene's own [[table]]; extrapolated(<symmetric table>, k) "
         "extrapolates it over k runs of 1..k steps (order p + 2(k - 1)); compensated(<table>) sums the updates with "
         "Kahan's compensation; a force-gradient table (chin_4a, ...) also needs the force's derivative"},
        {method_kind::processed, "processed", false, false, needs::separable_hamiltonian,
         "a processed method (blanes_2001_p6, ...): a kernel every step, its processor only where the state is "
         "looked at; every output is the true state"},
        {method_kind::logh, "logh", false, false, needs::negative_potential,
         "logh(<table>): the table in LogH fictitious time (Mikkola & Tanikawa 1999); dt is the fictitious step; "
         "extrapolated(logh(<symmetric table>), k) as above"},
        {method_kind::classic, "classic", false, false, needs::any, "a classic stepper of Gould & Tobochnik or Sandvik"},
        {method_kind::odeint_rk4, "odeint", false, true, needs::any, "Boost.Odeint runge_kutta4, fixed step"},
        {method_kind::odeint_dopri5, "odeint", true, true, needs::any,
         "Boost.Odeint controlled runge_kutta_dopri5, absolute = relative tolerance"},
        {method_kind::odeint_fehlberg78, "odeint", true, true, needs::any,
         "Boost.Odeint controlled runge_kutta_fehlberg78, absolute = relative tolerance"},
        {method_kind::odeint_bulirsch_stoer, "odeint", true, true, needs::any,
         "Boost.Odeint bulirsch_stoer, absolute = relative tolerance"},
    };
    return kinds;
}

const method_kind_entry& entry_of(method_kind kind) {
    for (const auto& k : method_kinds())
        if (k.kind == kind) return k;
    throw invalid_argument("method kind " + std::to_string(int(kind)) + " has no registry entry");
}

std::string why_not(needs n, const system_form& form) {
    switch (n) {
        case needs::any: return "";
        case needs::separable_hamiltonian:
            return form.separable_hamiltonian ? ""
                                              : "needs a separable Hamiltonian H = T(p) + V(q); this system is not "
                                                "Hamiltonian (use a classic method)";
        case needs::newtonian:
            return form.newtonian ? ""
                                  : "needs Newton's form x'' = a(x, v, t); this system is Hamiltonian (use velocity_verlet)";
        case needs::damped_split:
            return form.damped_split ? "" : "needs a force split as F(x, t) - G(v); only damped_oscillator has one";
        case needs::differentiable_force:
            if (!form.separable_hamiltonian) return why_not(needs::separable_hamiltonian, form);
            return form.differentiable_force ? ""
                                             : "needs the force's derivative J_F(q) u (force-gradient kicks); this "
                                               "system gives neither force_derivative nor a potential templated on its "
                                               "scalar (use a table without force-gradient kicks)";
        case needs::negative_potential:
            if (!form.separable_hamiltonian) return why_not(needs::separable_hamiltonian, form);
            return form.negative_potential ? ""
                                           : "needs V(q) < 0 everywhere (the LogH time transformation divides by -V); "
                                             "this system's potential is not negative (use the table itself)";
    }
    return "needs what no system offers";
}

std::vector<std::string> method_names_beside_tables() {
    std::vector<std::string> names;
    std::apply([&](const auto&... m) { (names.push_back(m.name), ...); }, classic_methods);
    for (const char* odeint : {"odeint_rk4", "odeint_dopri5", "odeint_fehlberg78", "odeint_bulirsch_stoer"})
        names.push_back(odeint);
    for (const table& t : force_gradient_catalog()) names.push_back(t.name());
    for (const processed_method& m : processed_catalog()) names.push_back(m.name);
    return names;
}

namespace {
bool is_classic(const std::string& name) {
    return std::apply([&](const auto&... m) { return ((name == m.name) || ...); }, classic_methods);
}

std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
    return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// extrapolated(<table or logh(<table>)>, <columns>)
method_spec extrapolated(const std::string& name, const std::map<std::string, table>& inline_tables) {
    const std::string usage = "; expected extrapolated(<symmetric table or logh(<symmetric table>)>, <columns 1 to " +
                              std::to_string(max_extrapolation_columns) + ">)";
    const std::string args = name.substr(13, name.size() - 14);
    const auto comma = args.rfind(',');
    if (comma == std::string::npos) throw invalid_argument("method '" + name + "': no column count" + usage);
    const std::string inner_name = trimmed(args.substr(0, comma)), count = trimmed(args.substr(comma + 1));
    int columns = 0;
    const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), columns);
    if (error != std::errc{} || end != count.data() + count.size() || columns < 1 || columns > max_extrapolation_columns)
        throw invalid_argument("method '" + name + "': column count '" + count + "'" + usage);
    auto inner = resolve_method(inner_name, inline_tables);
    if (!inner || (inner->kind != method_kind::table && inner->kind != method_kind::logh) || inner->extrapolation_columns)
        throw invalid_argument("method '" + name + "': '" + inner_name + "' is not a table or logh(<table>)" + usage);
    try {
        extrapolation_order(*inner->coefficients);
    } catch (const invalid_argument& e) {
        throw invalid_argument("method '" + name + "': " + e.what() + usage);
    }
    inner->name = name;
    inner->extrapolation_columns = columns;
    return *inner;
}
}  // namespace

std::optional<method_spec> resolve_method(const std::string& name, const std::map<std::string, table>& inline_tables) {
    if (name.size() > 14 && name.rfind("extrapolated(", 0) == 0 && name.back() == ')') return extrapolated(name, inline_tables);
    if (auto it = inline_tables.find(name); it != inline_tables.end()) return method_spec{name, method_kind::table, it->second};
    if (name.size() > 13 && name.rfind("compensated(", 0) == 0 && name.back() == ')') {
        auto inner = resolve_method(name.substr(12, name.size() - 13), inline_tables);
        if (!inner || inner->kind != method_kind::table || inner->extrapolation_columns) return std::nullopt;
        inner->name = name;
        inner->compensated = true;
        return inner;
    }
    if (name.size() > 6 && name.rfind("logh(", 0) == 0 && name.back() == ')') {
        auto inner = resolve_method(name.substr(5, name.size() - 6), inline_tables);
        if (!inner || inner->kind != method_kind::table) return std::nullopt;
        // LogH's extended Hamiltonian has no force derivative of its own.
        if (inner->coefficients->has_force_gradient())
            throw invalid_argument("method '" + name + "': '" + inner->name +
                                   "' has force-gradient kicks; expected logh(<table without them>)");
        return method_spec{name, method_kind::logh, inner->coefficients};
    }
    for (const auto& [odeint, kind] : {std::pair{"odeint_rk4", method_kind::odeint_rk4},
                                       std::pair{"odeint_dopri5", method_kind::odeint_dopri5},
                                       std::pair{"odeint_fehlberg78", method_kind::odeint_fehlberg78},
                                       std::pair{"odeint_bulirsch_stoer", method_kind::odeint_bulirsch_stoer}})
        if (name == odeint) return method_spec{name, kind, std::nullopt};
    if (is_classic(name)) return method_spec{name, method_kind::classic, std::nullopt};
    const auto& names = catalog_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) return method_spec{name, method_kind::table, method(name)};
    for (const table& t : force_gradient_catalog())
        if (t.name() == name) return method_spec{name, method_kind::table, t};
    for (const processed_method& p : processed_catalog())
        if (p.name == name) return method_spec{name, method_kind::processed, std::nullopt, p};
    return std::nullopt;
}

std::string why_not_resumable(const method_spec& m) {
    bool history = false;
    std::apply([&](const auto&... c) { ((m.name == c.name ? void(history = c.history) : void()), ...); }, classic_methods);
    if ((m.kind == method_kind::table && !m.extrapolation_columns) || (m.kind == method_kind::classic && !history))
        return "";
    return "method '" + m.name + "' cannot be checkpointed: " +
           (history ? std::string("it carries a history between steps that the state does not hold")
            : m.kind == method_kind::processed
                ? std::string("its kernel runs on a processed state that the true state does not hold")
                : std::string("only tables (plain or compensated(<table>)) and the classic steppers without "
                              "history (euler, euler_cromer, euler_richardson, rk2, rk4) resume bit for bit"));
}

needs requirement_of(const method_spec& m) {
    if (m.kind == method_kind::table && m.coefficients->has_force_gradient()) return needs::differentiable_force;
    if (m.kind != method_kind::classic) return entry_of(m.kind).requirement;  // logh: also a separable Hamiltonian
    needs n = needs::any;
    std::apply([&](const auto&... c) { ((m.name == c.name ? void(n = c.requirement) : void()), ...); }, classic_methods);
    return n;
}

std::string why_not(const method_spec& m, const system_form& form) {
    const std::string why = why_not(requirement_of(m), form);
    return why.empty() ? "" : "method '" + m.name + "' " + why;
}

}  // namespace sympl::app
