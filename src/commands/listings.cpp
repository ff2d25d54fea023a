// `sympl tables` and `sympl systems`.
#include "commands/listings.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <vector>

#include <nlohmann/json.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

#include "reading/coefficient_list.hpp"
#include "output/format.hpp"
#include "methods/method_kinds.hpp"
#include "reading/scene.hpp"
#include "running/systems.hpp"

namespace sympl::app {

namespace {
// The methods compiled for a system's own type at its defaults, by kind label
// (a classic stepper by its name where only some are): those it can run;
// every other method runs on the generic path (generic_path.hpp).
std::vector<std::string> compiled_names(const system_entry& s) {
    const runnable_system p = make_system(s.name, {}, {}, {}, s.name);  // the form with the entry's own facts (V < 0)
    std::vector<std::string> names;
    for (const method_kind_entry& k : method_kinds()) {
        if (!p.compiled.kinds.has(k.kind) || !why_not(k.requirement, p.form).empty()) continue;
        if (k.kind != method_kind::classic || p.compiled.classic.bits == all_classic.bits) {
            names.push_back(k.label);
            continue;
        }
        for (std::size_t i = 0; i < classic_method_count; ++i)
            if (p.compiled.classic.has(i)) names.push_back(classic_at(i).name);
    }
    const bool splits = p.compiled.kinds.has(method_kind::table) || p.compiled.kinds.has(method_kind::logh);
    if (splits && p.compiled.extrapolated && p.form.separable_hamiltonian) names.push_back("extrapolated");
    return names;
}
}  // namespace

// The registries: systems (with parameters) and method kinds.
void print_systems(bool json, const std::vector<std::string>& scene_files) {
    // The program's systems, or the systems of the scenes given (their own,
    // written as formulas, among them).
    std::vector<const system_entry*> listed;
    for (const auto& s : systems()) listed.push_back(&s);
    if (!scene_files.empty()) {
        listed.clear();
        for (const auto& f : scene_files) {
            const system_entry* e = find_system(load_scene(f).system);
            if (e && std::find(listed.begin(), listed.end(), e) == listed.end()) listed.push_back(e);
        }
    }
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const system_entry* listed_entry : listed) {
            const system_entry& s = *listed_entry;
            nlohmann::json params = nlohmann::json::array();
            for (const auto& p : s.parameters)
                params.push_back({{"name", p.name}, {"default", p.value}, {"expected", p.expected()}, {"meaning", p.meaning}});
            nlohmann::json entry = {{"name", s.name}, {"description", s.description}, {"exact", s.exact}, {"parameters", params}};
            if (s.period.value) {
                entry["period"] = {{"meaning", s.period.meaning}, {"default", period_of(s, with_defaults(s, {}, s.name))}};
            }
            entry["compiled_kinds"] = compiled_names(s);
            out.push_back(entry);
        }
        std::cout << out.dump(2) << "\n";
        return;
    }
    for (const system_entry* entry : listed) {
        const system_entry& s = *entry;
        std::cout << s.name << (s.exact ? "  (exact solution)" : "") << "\n    " << s.description << "\n";
        if (s.period.value) {  // what a scene's {periods = N} and {per_period = N} count in
            std::cout << "    period " << format_number(period_of(s, with_defaults(s, {}, s.name)), 6) << " at the defaults: "
                      << s.period.meaning << "\n";
        }
        for (const auto& p : s.parameters)
            std::cout << "    " << std::left << std::setw(16) << p.name << std::setw(10) << format_number(p.value, 6)
                      << p.expected() << "; " << p.meaning << "\n";
        const std::vector<std::string> compiled = compiled_names(s);
        std::cout << "    compiled:";
        for (const auto& name : compiled) std::cout << " " << name;
        const bool hamiltonian = s.build(with_defaults(s, {}, s.name)).hamiltonian;
        std::cout << (compiled.empty() ? " nothing" : "")
                  << (!hamiltonian         ? " (not Hamiltonian: no generic path)\n"
                      : compiled.empty()   ? "; every method on the generic path\n"
                                           : "; any other method on the generic path\n");
    }
    std::cout << "\nmethod kinds:\n";
    const auto line = [](const char* label, const char* description) {
        std::cout << "    " << std::left << std::setw(19) << label << description << "\n";
    };
    for (const auto& k : method_kinds()) {
        if (k.members.empty()) line(k.label, k.description);
        for (const named_method& member : k.members) line(k.label, member.description);
    }
    std::cout << "besides the catalog's tables (sympl tables) and a scene's own [[table]]s:";
    for (const auto& name : method_names_beside_tables()) std::cout << " " << name;
    std::cout << "\n";
}

void print_tables(bool json) {
    const auto& all = sympl::catalog();
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& t : all)
            out.push_back({{"name", t.name()},
                           {"family", t.family()},
                           {"order", t.order()},
                           {"stages", t.stages()},
                           {"force_evaluations", t.force_evaluations()},
                           {"symmetric", t.is_symmetric()},
                           {"needs_quadratic_T", t.needs_quadratic_kinetic()},
                           {"stability_interval", t.stability_interval()},
                           {"error_at_equal_cost", sympl::error_at_equal_cost(t)},
                           {"citation", t.citation()},
                           {"kick", as_doubles(t.kick())},
                           {"drift", as_doubles(t.drift())}});
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::cout << "sympl catalog: each step does, for k = 0..M-1, p += kick[k]*dt*force(q), then q += drift[k]*dt*velocity(p)\n\n";
    std::cout << std::left << std::setw(25) << "name" << std::setw(16) << "family" << std::right << std::setw(6) << "order"
              << std::setw(7) << "stages" << std::setw(7) << "forces" << std::setw(5) << "sym" << std::setw(7) << "T"
              << std::setw(10) << "stability" << std::setw(11) << "error@300" << "  citation\n";
    for (const auto& t : all)
        std::cout << std::left << std::setw(25) << t.name() << std::setw(16) << t.family() << std::right << std::setw(6)
                  << t.order() << std::setw(7) << t.stages() << std::setw(7) << t.force_evaluations() << std::setw(5)
                  << (t.is_symmetric() ? "yes" : "no") << std::setw(7) << (t.needs_quadratic_kinetic() ? "p^2/2" : "any")
                  << std::setw(10) << fixed(t.stability_interval(), 3) << std::setw(11)
                  << scientific(sympl::error_at_equal_cost(t), 1) << "  " << t.citation() << "\n";
    std::cout << "\n" << all.size() << " methods. forces: force evaluations per step (the last force is reused);"
              << " T: 'p^2/2' = the order holds only for quadratic kinetic energy;"
              << " stability: largest omega*dt stable on the harmonic oscillator;"
              << " error@300: max error on the pendulum (q0 = 1.2, p0 = 0.3) at t = 3 with 300 force evaluations"
              << " (to choose between methods: lower is better at equal cost).\n";
    // Named methods that are not kick-drift tables (not in --json, whose entries are).
    std::cout << "\nforce-gradient tables (kicks that add the force's derivative; systems with force_derivative or a "
                 "templated potential):\n";
    for (const auto& t : sympl::force_gradient_catalog())
        std::cout << "  " << std::left << std::setw(25) << t.name() << std::right << "order " << t.order() << ", "
                  << t.force_evaluations() << " forces and " << t.force_gradient_evaluations() << " force derivative"
                  << (t.force_gradient_evaluations() == 1 ? "" : "s") << " a step  " << t.citation() << "\n";
    std::cout << "\nprocessed methods (a kernel every step, its processor only where the state is looked at):\n";
    for (const auto& m : sympl::processed_catalog()) {
        std::size_t processor_kicks = 0;
        for (const auto& o : m.processor) processor_kicks += o.kind == sympl::substep::kick;
        std::cout << "  " << std::left << std::setw(25) << m.name << std::right << "effective order " << m.order << ", "
                  << m.kernel.force_evaluations() << " forces a step, processor " << processor_kicks << " kicks  "
                  << m.citation << "\n";
    }
}

}  // namespace sympl::app
