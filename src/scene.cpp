// Scene files: parsing, validation with file:line:column, and the built-in set.
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include <sympl/catalog.hpp>

namespace sympl::app {

const std::vector<std::string>& system_names() {
    static const std::vector<std::string> names = {
        "harmonic_oscillator", "pendulum", "kepler", "kepler_3d", "relativistic_pendulum", "henon_heiles",
        "fpu_beta", "stiff_fpu", "outer_solar_system", "two_particle_spring", "morse", "double_well", "toda",
        "damped_oscillator"};
    return names;
}

const std::vector<std::string>& system_parameters(const std::string& system) {
    static const std::map<std::string, std::vector<std::string>> known = {
        {"harmonic_oscillator", {"mass", "omega"}},
        {"pendulum", {"mass", "length", "gravity"}},
        {"kepler", {"mu", "eccentricity", "scale"}},
        {"kepler_3d", {"eccentricity", "inclination", "node", "periapsis"}},
        {"relativistic_pendulum", {"mass", "c", "k"}},
        {"henon_heiles", {"energy", "q2", "p2"}},
        {"fpu_beta", {"n", "beta"}},
        {"stiff_fpu", {"omega", "pairs"}},
        {"outer_solar_system", {}},
        {"two_particle_spring", {"mass", "stiffness"}},
        {"morse", {"mass", "depth", "width", "position"}},
        {"double_well", {"barrier"}},
        {"toda", {"n"}},
        {"damped_oscillator", {"mass", "stiffness", "damping", "drive_amplitude", "drive_frequency"}},
    };
    static const std::vector<std::string> none;
    auto it = known.find(system);
    return it == known.end() ? none : it->second;
}

const std::vector<std::string>& classic_method_names() {
    static const std::vector<std::string> names = {"euler", "euler_cromer", "half_step", "euler_richardson", "rk2", "rk4",
                                                   "velocity_verlet", "leapfrog_two_step", "damped_leapfrog",
                                                   "predictor_corrector", "odeint_rk4", "odeint_dopri5"};
    return names;
}

namespace {

std::string join(const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
    return out;
}

struct reader {
    std::string source;

    [[noreturn]] void fail(const toml::source_region& where, const std::string& what) const {
        throw scene_error(source + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) +
                          ": " + what);
    }
    [[noreturn]] void fail(const toml::node& n, const std::string& what) const { fail(n.source(), what); }

    // Only the listed keys: anything else is a typo the user wants to hear about.
    void only_keys(const toml::table& t, const std::set<std::string>& allowed, const std::string& where) const {
        for (const auto& [key, node] : t)
            if (!allowed.count(std::string(key.str()))) {
                std::vector<std::string> names(allowed.begin(), allowed.end());
                fail(node, "unknown key '" + std::string(key.str()) + "' in " + where + "; expected one of: " + join(names));
            }
    }

    double number(const toml::node& n, const std::string& key) const {
        if (auto v = n.value<double>(); v && (n.is_floating_point() || n.is_integer())) return *v;
        fail(n, "'" + key + "' must be a number");
    }
    double positive(const toml::node& n, const std::string& key) const {
        const double v = number(n, key);
        if (!(v > 0) || !std::isfinite(v))
            fail(n, "'" + key + "' = " + std::to_string(v) + "; expected a finite number > 0");
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

    // dt = 0.01 | [0.1, 0.05] | { from = 0.1, to = 0.001, count = 7 } (geometric)
    std::vector<double> sweep(const toml::node& n, const std::string& key) const {
        std::vector<double> out;
        if (n.is_array()) {
            for (const auto& e : *n.as_array()) out.push_back(positive(e, key));
            if (out.empty()) fail(n, "'" + key + "' is an empty array; expected at least one value");
        } else if (const toml::table* t = n.as_table()) {
            only_keys(*t, {"from", "to", "count"}, "'" + key + "'");
            const toml::node* from = t->get("from");
            const toml::node* to = t->get("to");
            const toml::node* count = t->get("count");
            if (!from || !to || !count) fail(n, "'" + key + "' needs from, to and count");
            const double a = positive(*from, key + ".from"), b = positive(*to, key + ".to");
            const auto c = count->value<std::int64_t>();
            if (!c || *c < 1 || *c > 1000) fail(*count, "'" + key + ".count' must be an integer in [1, 1000]");
            for (std::int64_t i = 0; i < *c; ++i)
                out.push_back(*c == 1 ? a : a * std::pow(b / a, double(i) / double(*c - 1)));
        } else {
            out.push_back(positive(n, key));
        }
        std::sort(out.rbegin(), out.rend());
        return out;
    }
};

method_spec method_by_name(const reader& r, const toml::node& n, const std::map<std::string, table>& inline_tables) {
    const std::string name = r.string(n, "methods");
    if (auto it = inline_tables.find(name); it != inline_tables.end()) return {name, method_kind::table, it->second};
    if (name == "odeint_rk4") return {name, method_kind::odeint_rk4, std::nullopt};
    if (name == "odeint_dopri5") return {name, method_kind::odeint_dopri5, std::nullopt};
    const auto& classic = classic_method_names();
    if (std::find(classic.begin(), classic.end(), name) != classic.end()) return {name, method_kind::classic, std::nullopt};
    const auto& names = catalog_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) return {name, method_kind::table, method(name)};
    r.fail(n, "unknown method '" + name + "'; expected a catalog name (sympl tables), an inline [[table]], or one of: " +
                  join(classic));
}

}  // namespace

scene parse_scene(const std::string& text, const std::string& source) {
    const reader r{source};
    toml::table doc;
    try {
        doc = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        r.fail(e.source(), "not valid TOML: " + std::string(e.description()));
    }
    r.only_keys(doc, {"name", "system", "parameters", "initial", "methods", "table", "dt", "tolerances", "t0", "t_end",
                      "output"},
                "the scene");
    scene s;
    s.source = source;
    const toml::source_region top{{1, 1}, {1, 1}, nullptr};
    s.name = doc.get("name") ? r.string(*doc.get("name"), "name") : source;

    const toml::node* system = doc.get("system");
    if (!system) r.fail(top, "missing 'system'; expected one of: " + join(system_names()));
    s.system = r.string(*system, "system");
    const auto& systems = system_names();
    if (std::find(systems.begin(), systems.end(), s.system) == systems.end())
        r.fail(*system, "unknown system '" + s.system + "'; expected one of: " + join(systems));

    if (const toml::node* p = doc.get("parameters")) {
        const toml::table* t = p->as_table();
        if (!t) r.fail(*p, "'parameters' must be a table of numbers");
        const auto& known = system_parameters(s.system);
        r.only_keys(*t, std::set<std::string>(known.begin(), known.end()), "[parameters] of " + s.system);
        for (const auto& [key, node] : *t) s.parameters[std::string(key.str())] = r.number(node, std::string(key.str()));
    }
    if (const toml::node* i = doc.get("initial")) {
        const toml::table* t = i->as_table();
        if (!t) r.fail(*i, "'initial' must be a table with q and p");
        r.only_keys(*t, {"q", "p"}, "[initial]");
        if (!t->get("q") || !t->get("p")) r.fail(*i, "[initial] needs both q and p");
        s.q0 = r.numbers(*t->get("q"), "initial.q");
        s.p0 = r.numbers(*t->get("p"), "initial.p");
        if (s.q0.size() != s.p0.size() || s.q0.empty())
            r.fail(*i, "initial q has " + std::to_string(s.q0.size()) + " values and p has " + std::to_string(s.p0.size()) +
                           "; expected the same number, at least one");
    }

    std::map<std::string, table> inline_tables;
    if (const toml::node* tables = doc.get("table")) {
        const toml::array* a = tables->as_array();
        if (!a) r.fail(*tables, "'table' must be an array of tables: [[table]]");
        for (const auto& e : *a) {
            const toml::table* t = e.as_table();
            if (!t) r.fail(e, "each [[table]] must be a table");
            r.only_keys(*t, {"name", "kick", "drift", "order", "convention"}, "[[table]]");
            if (!t->get("name") || !t->get("kick") || !t->get("drift")) r.fail(e, "[[table]] needs name, kick and drift");
            const std::string name = r.string(*t->get("name"), "table.name");
            const auto kick = r.numbers(*t->get("kick"), "table.kick"), drift = r.numbers(*t->get("drift"), "table.drift");
            const int order = t->get("order") ? int(r.number(*t->get("order"), "table.order")) : 0;
            const std::string convention = t->get("convention") ? r.string(*t->get("convention"), "table.convention")
                                                                : "kick-first";
            std::vector<coefficient> k(kick.begin(), kick.end()), d(drift.begin(), drift.end());
            try {
                inline_tables.emplace(name, convention == "seed"          ? from_seed(name, k, d, order)
                                            : convention == "drift-first" ? from_drift_first(name, d, k, order)
                                            : convention == "kick-first"  ? table(name, k, d, order)
                                                                          : throw invalid_argument(
                                                                                "convention '" + convention +
                                                                                "'; expected kick-first, drift-first or seed"));
            } catch (const invalid_table& x) {
                r.fail(e, x.what());
            } catch (const invalid_argument& x) {
                r.fail(e, x.what());
            }
        }
    }

    const toml::node* methods = doc.get("methods");
    if (!methods) r.fail(top, "missing 'methods'; expected an array of method names");
    const toml::array* ma = methods->as_array();
    if (!ma || ma->empty()) r.fail(*methods, "'methods' must be a non-empty array of method names");
    for (const auto& m : *ma) s.methods.push_back(method_by_name(r, m, inline_tables));

    const toml::node* dt = doc.get("dt");
    if (!dt) r.fail(top, "missing 'dt'; expected a step size, an array, or {from, to, count}");
    s.dt = r.sweep(*dt, "dt");
    s.tolerances = doc.get("tolerances") ? r.sweep(*doc.get("tolerances"), "tolerances")
                                         : std::vector<double>{1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
    if (const toml::node* t0 = doc.get("t0")) s.t0 = r.number(*t0, "t0");
    const toml::node* t_end = doc.get("t_end");
    if (!t_end) r.fail(top, "missing 't_end'");
    s.t_end = r.number(*t_end, "t_end");
    if (!(s.t_end > s.t0) || !std::isfinite(s.t_end))
        r.fail(*t_end, "t_end = " + std::to_string(s.t_end) + " is not after t0 = " + std::to_string(s.t0) +
                           "; expected t_end > t0");

    if (const toml::node* o = doc.get("output")) {
        const toml::table* t = o->as_table();
        if (!t) r.fail(*o, "'output' must be a table");
        r.only_keys(*t, {"energy_error", "trajectory_every", "final_state", "loop_area", "directory"}, "[output]");
        if (auto* n = t->get("energy_error")) s.output.energy_error = r.boolean(*n, "output.energy_error");
        if (auto* n = t->get("final_state")) s.output.final_state = r.boolean(*n, "output.final_state");
        if (auto* n = t->get("loop_area")) s.output.loop_area = r.boolean(*n, "output.loop_area");
        if (auto* n = t->get("directory")) s.output.directory = r.string(*n, "output.directory");
        if (auto* n = t->get("trajectory_every")) {
            const auto k = n->value<std::int64_t>();
            if (!k || !n->is_integer() || *k < 0) r.fail(*n, "'output.trajectory_every' must be an integer >= 0");
            s.output.trajectory_every = std::size_t(*k);
        }
    }
    return s;
}

scene load_scene(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw scene_error(path + ": cannot open the scene file");
    std::stringstream text;
    text << in.rdbuf();
    return parse_scene(text.str(), path);
}

std::vector<scene> default_scenes(bool quick) {
    // Step sweeps end where the best methods reach roundoff; quick runs are shorter.
    const std::string fast = quick ? "count = 4" : "count = 7";
    const std::string symplectic =
        R"("leapfrog_kdk", "forest_ruth_4", "blanes_moan_s6", "yoshida_6", "blanes_moan_s10", "sofroniou_spaletta_10")";
    const std::string classic = R"("rk4", "odeint_rk4", "odeint_dopri5")";
    const std::string tol = quick ? "tolerances = [1e-4, 1e-7, 1e-10]\n" : "tolerances = {from = 1e-3, to = 1e-12, count = 10}\n";
    const auto make = [&](const std::string& name, const std::string& body, const std::string& methods) {
        return parse_scene("name = \"" + name + "\"\n" + body + "methods = [" + methods + "]\n" + tol, "built-in:" + name);
    };
    const std::string all = symplectic + ", " + classic;
    std::vector<scene> s;
    s.push_back(make("harmonic_oscillator",
                     "system = \"harmonic_oscillator\"\nt_end = " + std::string(quick ? "50" : "200") +
                         "\ndt = {from = 0.5, to = 0.01, " + fast + "}\n",
                     all));
    s.push_back(make("pendulum",
                     "system = \"pendulum\"\nt_end = " + std::string(quick ? "50" : "200") +
                         "\ndt = {from = 0.5, to = 0.01, " + fast + "}\n",
                     all));
    s.push_back(make("kepler_e0.5",
                     "system = \"kepler\"\nparameters = {eccentricity = 0.5}\nt_end = " +
                         std::string(quick ? "31.41592653589793" : "125.66370614359172") +
                         "\ndt = {from = 0.1, to = 0.002, " + fast + "}\n",
                     all));
    s.push_back(make("kepler_e0.9",
                     "system = \"kepler\"\nparameters = {eccentricity = 0.9}\nt_end = " +
                         std::string(quick ? "12.566370614359172" : "62.83185307179586") +
                         "\ndt = {from = 0.02, to = 0.0005, " + fast + "}\n",
                     all));
    s.push_back(make("henon_heiles", "system = \"henon_heiles\"\nparameters = {energy = 0.16666666666666666}\nt_end = " +
                                         std::string(quick ? "20" : "50") + "\ndt = {from = 0.2, to = 0.005, " + fast + "}\n",
                     all));
    s.push_back(make("fpu_beta", "system = \"fpu_beta\"\nparameters = {n = 32, beta = 1.0}\nt_end = " +
                                     std::string(quick ? "20" : "100") + "\ndt = {from = 0.2, to = 0.005, " + fast + "}\n",
                     all));
    s.push_back(make("stiff_fpu", "system = \"stiff_fpu\"\nparameters = {omega = 50.0}\nt_end = " +
                                      std::string(quick ? "5" : "20") + "\ndt = {from = 0.02, to = 0.0005, " + fast + "}\n",
                     all));
    s.push_back(make("outer_solar_system", "system = \"outer_solar_system\"\nt_end = " +
                                               std::string(quick ? "20000" : "200000") +
                                               "\ndt = {from = 200, to = 5, " + fast + "}\n",
                     all));
    s.push_back(make("two_particle_spring", "system = \"two_particle_spring\"\nt_end = " +
                                                std::string(quick ? "50" : "200") + "\ndt = {from = 0.5, to = 0.01, " +
                                                fast + "}\n",
                     all));
    s.push_back(make("damped_oscillator",
                     "system = \"damped_oscillator\"\nparameters = {damping = 0.3, drive_amplitude = 0.5, "
                     "drive_frequency = 0.7}\nt_end = " +
                         std::string(quick ? "20" : "50") + "\ndt = {from = 0.2, to = 0.005, " + fast + "}\n",
                     R"("euler", "euler_cromer", "half_step", "euler_richardson", "velocity_verlet", "damped_leapfrog", "predictor_corrector", "rk4", "odeint_rk4", "odeint_dopri5")"));
    return s;
}

}  // namespace sympl::app
